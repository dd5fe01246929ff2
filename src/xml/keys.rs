//! Composed keyframes ([`WriteOptions::merge_keyframes`](crate::WriteOptions)): one
//! key per key name over the whole composed model.
//!
//! Each model's key of a name covers that model's own joints (its frames' joints
//! included), actuators and mocap bodies, in its own document order. The composed key
//! lays them out in the composed model's order (the order MuJoCo numbers them: the
//! writer's); where a model has no key of that name, its part is MuJoCo's default:
//! `qpos0` (a hinge's or slide's `ref`, a ball's unit quaternion, a free joint's body
//! pose in the world), zero velocities, activations and controls, and the mocap
//! bodies' poses.
//!
//! Limits: joint types and `ref` are read from the element and its default classes'
//! `joint` defaults only for `type` (a class's `ref` is not followed); activations are
//! counted from the actuator's own tag and attributes (`muscle`, `cylinder`,
//! `intvelocity`, a `general` with a `dyntype`, a `position` or `velocity` with a
//! `timeconst` above 0). A parent's key without a name is kept, padded with defaults;
//! attached models' unnamed keys are dropped.

use std::collections::HashMap;

use smol_str::SmolStr;

use crate::model::check::joint_type;
use crate::model::tree::{ElementId, Node};
use crate::model::{Model, Step, Walk};
use crate::schema::ElementKind;
use crate::value::{Reference, Value};

/// A rigid transform: position and unit quaternion (w, x, y, z).
#[derive(Clone, Copy, Debug)]
struct Pose {
    pos: [f64; 3],
    quat: [f64; 4],
}

const IDENTITY: Pose = Pose { pos: [0.0; 3], quat: [1.0, 0.0, 0.0, 0.0] };

fn qmul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = qmul(qmul(q, [0.0, v[0], v[1], v[2]]), [q[0], -q[1], -q[2], -q[3]]);
    [p[1], p[2], p[3]]
}

fn normalize4(q: [f64; 4]) -> [f64; 4] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 { q.map(|x| x / n) } else { [1.0, 0.0, 0.0, 0.0] }
}

fn axis_angle(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let n = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let s = (angle / 2.0).sin() / n;
    [(angle / 2.0).cos(), axis[0] * s, axis[1] * s, axis[2] * s]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 0.0 { v.map(|x| x / n) } else { v }
}

/// The quaternion of a rotation matrix given by its columns.
fn from_columns(x: [f64; 3], y: [f64; 3], z: [f64; 3]) -> [f64; 4] {
    let (m00, m11, m22) = (x[0], y[1], z[2]);
    let tr = m00 + m11 + m22;
    let q = if tr > 0.0 {
        let s = (tr + 1.0).sqrt() * 2.0;
        [0.25 * s, (y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s]
    } else if m00 > m11 && m00 > m22 {
        let s = (1.0 + m00 - m11 - m22).sqrt() * 2.0;
        [(y[2] - z[1]) / s, 0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s]
    } else if m11 > m22 {
        let s = (1.0 + m11 - m00 - m22).sqrt() * 2.0;
        [(z[0] - x[2]) / s, (y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s]
    } else {
        let s = (1.0 + m22 - m00 - m11).sqrt() * 2.0;
        [(x[1] - y[0]) / s, (z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s]
    };
    normalize4(q)
}

/// How the compiler reads orientations: angles in degrees or radians, and the euler
/// sequence.
struct Angles {
    degrees: bool,
    seq: [u8; 3],
}

impl Angles {
    fn radians(&self, a: f64) -> f64 {
        if self.degrees { a.to_radians() } else { a }
    }
}

fn floats<'a>(node: &'a Node, name: &str) -> Option<&'a [f64]> {
    node.attr(node.kind().attr_index(name)?).and_then(Value::as_floats)
}

/// The pose an element (body, frame, site) gives its content, as MuJoCo reads it.
fn local_pose(node: &Node, angles: &Angles) -> Pose {
    // Arrays may be shorter than their schema length (as in the reference): missing
    // entries are 0.
    let pos = floats(node, "pos")
        .map_or([0.0; 3], |p| [0, 1, 2].map(|i| p.get(i).copied().unwrap_or(0.0)));
    let quat = if let Some(q) = floats(node, "quat").filter(|q| q.len() == 4) {
        normalize4([q[0], q[1], q[2], q[3]])
    } else if let Some(a) = floats(node, "axisangle").filter(|a| a.len() == 4) {
        axis_angle([a[0], a[1], a[2]], angles.radians(a[3]))
    } else if let Some(e) = floats(node, "euler").filter(|e| e.len() == 3) {
        let mut q = [1.0, 0.0, 0.0, 0.0];
        for (i, c) in angles.seq.iter().enumerate() {
            let axis = match c.to_ascii_lowercase() {
                b'x' => [1.0, 0.0, 0.0],
                b'y' => [0.0, 1.0, 0.0],
                _ => [0.0, 0.0, 1.0],
            };
            let r = axis_angle(axis, angles.radians(e[i]));
            // Lower case: axes that move with the frame (multiply on the right);
            // upper case: fixed axes (on the left).
            q = if c.is_ascii_lowercase() { qmul(q, r) } else { qmul(r, q) };
        }
        q
    } else if let Some(a) = floats(node, "xyaxes").filter(|a| a.len() == 6) {
        let x = unit([a[0], a[1], a[2]]);
        let y0 = [a[3], a[4], a[5]];
        let d = x[0] * y0[0] + x[1] * y0[1] + x[2] * y0[2];
        let y = unit([y0[0] - d * x[0], y0[1] - d * x[1], y0[2] - d * x[2]]);
        from_columns(x, y, cross(x, y))
    } else if let Some(z) = floats(node, "zaxis").filter(|z| z.len() == 3) {
        let z = unit([z[0], z[1], z[2]]);
        let axis = cross([0.0, 0.0, 1.0], z);
        let s = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
        if s < 1e-12 {
            if z[2] >= 0.0 { [1.0, 0.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0, 0.0] }
        } else {
            axis_angle(axis, s.atan2(z[2]))
        }
    } else {
        [1.0, 0.0, 0.0, 0.0]
    };
    Pose { pos, quat }
}

fn compose(outer: Pose, inner: Pose) -> Pose {
    let p = rotate(outer.quat, inner.pos);
    Pose {
        pos: [outer.pos[0] + p[0], outer.pos[1] + p[1], outer.pos[2] + p[2]],
        quat: normalize4(qmul(outer.quat, inner.quat)),
    }
}

/// A slot of the composed key: which model's key it comes from, where in that key,
/// and its default.
struct Slot {
    inst: usize,
    offset: usize,
    default: Vec<f64>,
}

/// The composed layout of one key field (`qpos`, `qvel`, `act`, `ctrl`, `mpos`,
/// `mquat`).
#[derive(Default)]
struct Layout {
    slots: Vec<Slot>,
    /// Per instance, how many values its own layout has so far.
    next: HashMap<usize, usize>,
}

impl Layout {
    fn push(&mut self, inst: usize, default: Vec<f64>) {
        let n = self.next.entry(inst).or_insert(0);
        let offset = *n;
        *n += default.len();
        self.slots.push(Slot { inst, offset, default });
    }

    /// The composed values, taking each model's own key where it has one.
    fn values(&self, keys: &HashMap<usize, &Node>, field: &str) -> Vec<f64> {
        let mut out = Vec::new();
        for s in &self.slots {
            let own = keys.get(&s.inst).and_then(|k| floats(k, field));
            let len = s.default.len();
            match own.and_then(|v| v.get(s.offset..s.offset + len)) {
                Some(v) => out.extend_from_slice(v),
                None => out.extend_from_slice(&s.default),
            }
        }
        out
    }
}

/// The number of activations of an actuator element.
fn activations(node: &Node) -> usize {
    let positive = |name: &str| {
        node.kind()
            .attr_index(name)
            .and_then(|i| node.attr(i))
            .and_then(Value::as_float)
            .is_some_and(|x| x > 0.0)
    };
    let dyntype =
        node.kind().attr_index("dyntype").and_then(|i| node.attr(i)).and_then(Value::as_str);
    match node.kind().tag() {
        "muscle" | "cylinder" | "intvelocity" => 1,
        "general" => usize::from(dyntype.is_some_and(|d| d != "none")),
        "position" | "velocity" => usize::from(positive("timeconst")),
        _ => 0,
    }
}

/// One composed key, ready to write.
pub(crate) struct MergedKey {
    pub(crate) name: Option<SmolStr>,
    /// `(attribute, values)` in schema order; a field no model's key sets is left out.
    pub(crate) fields: Vec<(&'static str, Vec<f64>)>,
    pub(crate) time: Option<f64>,
}

/// The composed keys of `model` (see the module documentation).
pub(crate) fn merged_keys(model: &Model, compiler: Option<&Node>) -> Vec<MergedKey> {
    let angles = Angles {
        degrees: compiler
            .and_then(|c| c.attr(c.kind().attr_index("angle")?))
            .and_then(Value::as_str)
            .is_none_or(|a| a != "radian"),
        seq: compiler
            .and_then(|c| c.attr(c.kind().attr_index("eulerseq")?))
            .and_then(Value::as_str)
            .and_then(|s| <[u8; 3]>::try_from(s.as_bytes()).ok())
            .unwrap_or(*b"xyz"),
    };
    let (mut qpos, mut qvel, mut act, mut ctrl, mut mpos, mut mquat) = (
        Layout::default(),
        Layout::default(),
        Layout::default(),
        Layout::default(),
        Layout::default(),
        Layout::default(),
    );
    // Keys per instance, in document order: (name or position, node).
    let mut keys: Vec<(usize, &Node)> = Vec::new();
    let mut walk = Walk::new(model);
    // Per open element: its instance, its pose in the world, the `childclass` in force
    // for its content, the node.
    let mut open: Vec<(usize, Pose, Option<ElementId>, &Node)> = Vec::new();
    let root_class =
        |m: &Model| m.root.child_of_kind(ElementKind::ROOT.child("default")?).map(Node::id);
    while let Some(step) = walk.next() {
        match step {
            Step::Enter(item) => {
                let inst = item.inst;
                let m = walk.insts.list[inst].model;
                let node = item.node;
                let kind = node.kind();
                let parent = open.last().copied();
                let parent_tag = parent.map(|p| p.3.kind().tag());
                let parent_pose = parent.map_or(IDENTITY, |p| p.1);
                let class_attr = kind.class_attr().and_then(|c| match node.attr(c) {
                    Some(Value::Reference(Reference::Element(id))) => Some(*id),
                    _ => None,
                });
                let childclass = kind.attr_index("childclass").and_then(|c| match node.attr(c) {
                    Some(Value::Reference(Reference::Element(id))) => Some(*id),
                    _ => None,
                });
                let inherited = parent.filter(|p| p.0 == inst).and_then(|p| p.2);
                let class = class_attr.or(inherited).or_else(|| root_class(m));
                let is_body = kind.tag() == "body"
                    && kind.spec().parent.is_some_and(|p| p.tag() != "default");
                let frame_like = node.attached().is_some() || kind.tag() == "frame";
                let pose = if is_body || frame_like {
                    compose(parent_pose, local_pose(node, &angles))
                } else {
                    parent_pose
                };
                match kind.tag() {
                    "joint" | "freejoint" if matches!(parent_tag, Some("body")) => {
                        let ty = joint_type(m, node, class);
                        let (q, v) = match ty {
                            "free" => {
                                let p = open.last().map_or(IDENTITY, |o| o.1);
                                ([p.pos.as_slice(), p.quat.as_slice()].concat(), vec![0.0; 6])
                            }
                            "ball" => (vec![1.0, 0.0, 0.0, 0.0], vec![0.0; 3]),
                            _ => {
                                let r = kind
                                    .attr_index("ref")
                                    .and_then(|i| node.attr(i))
                                    .and_then(Value::as_float);
                                (vec![r.unwrap_or(0.0)], vec![0.0])
                            }
                        };
                        qpos.push(inst, q);
                        qvel.push(inst, v);
                    }
                    _ => {}
                }
                if is_body
                    && kind
                        .attr_index("mocap")
                        .and_then(|i| node.attr(i))
                        .and_then(Value::as_str)
                        .is_some_and(|v| v == "true")
                {
                    mpos.push(inst, pose.pos.to_vec());
                    mquat.push(inst, pose.quat.to_vec());
                }
                if parent_tag == Some("actuator")
                    && kind.spec().parent.is_some_and(|p| p.tag() == "actuator")
                {
                    ctrl.push(inst, vec![0.0]);
                    let n = activations(node);
                    if n > 0 {
                        act.push(inst, vec![0.0; n]);
                    }
                }
                if parent_tag == Some("keyframe") && kind.tag() == "key" {
                    keys.push((inst, node));
                }
                open.push((inst, pose, childclass.or(inherited), node));
            }
            Step::Leave(_) => {
                open.pop();
            }
        }
    }
    // Key names in order of first appearance (each found again by a hash: a scan of
    // the names so far made 100,000 keys quadratic); the parent's unnamed keys by
    // position.
    let mut order: Vec<Option<SmolStr>> = Vec::new();
    let mut slots: HashMap<SmolStr, usize> = HashMap::new();
    let mut by_name: Vec<HashMap<usize, &Node>> = Vec::new();
    for (inst, key) in &keys {
        let name = key.identifier().map(SmolStr::from);
        if name.is_none() && *inst != 0 {
            continue;
        }
        let slot = name.as_ref().and_then(|n| slots.get(n).copied());
        let i = match slot {
            Some(i) => i,
            None => {
                if let Some(n) = &name {
                    slots.insert(n.clone(), order.len());
                }
                order.push(name.clone());
                by_name.push(HashMap::new());
                order.len() - 1
            }
        };
        by_name[i].entry(*inst).or_insert(key);
    }
    order
        .into_iter()
        .zip(by_name)
        .map(|(name, keys)| {
            let sets = |field: &str| keys.values().any(|k| floats(k, field).is_some());
            let mut fields = Vec::new();
            for (field, layout) in [
                ("qpos", &qpos),
                ("qvel", &qvel),
                ("act", &act),
                ("mpos", &mpos),
                ("mquat", &mquat),
                ("ctrl", &ctrl),
            ] {
                // `qpos` is always written, so that every model's part is there.
                if field == "qpos" || sets(field) {
                    fields.push((field, layout.values(&keys, field)));
                }
            }
            // The parent's time, else that of the first model (in attach order) with one.
            let first = keys.iter().min_by_key(|(i, _)| **i).map(|(_, k)| *k);
            let time = keys
                .get(&0)
                .copied()
                .or(first)
                .and_then(|k| k.attr(k.kind().attr_index("time")?))
                .and_then(Value::as_float);
            MergedKey { name, fields, time }
        })
        .collect()
}
