//! Converting a model's angles into another model's conventions (`<compiler angle>`
//! and `eulerseq`), so that composing two models whose conventions differ compiles
//! every element as it compiled in its own file. What is converted and when, and what
//! is still refused, is [`Model::attach`](crate::Model::attach)'s rule (decision
//! D17); the numbers MuJoCo 4.0.0 reads by these settings were found in
//! `ResolveOrientation` (orientations, a `replicate`'s `euler`) and
//! `mjCJoint::Compile` (a joint's `range`, `ref`, `springref`), and checked with its
//! library.
//!
//! # How
//! - a unit change scales: `euler`, the fourth number of `axisangle`, a limited
//!   hinge's or ball's `range`, a hinge's `ref` and `springref`;
//! - a sequence change rewrites `euler` as the `axisangle` of the same rotation
//!   (computed as MuJoCo composes it: lower case letters turn about the moving axes,
//!   upper case about the fixed ones), in the receiving model's unit. `axisangle`,
//!   like `euler`, is one of MuJoCo's alternative orientations, so it takes the
//!   same precedence over a default class's orientation as the `euler` it replaces.
//!   A `replicate` has no `axisangle`: its `euler` is carried over when it turns
//!   about one axis only (the sequence has a letter for that axis), and refused
//!   otherwise ([`ErrorKind::AttributeConflict`] on `eulerseq`): the steps `i·euler`
//!   of a rotation about several axes have no equivalent in another sequence;
//! - joints: a joint's type can come from a default class while its `range`, `ref`
//!   or `springref` comes from another (a class setting `range` for slide joints
//!   and hinges alike). A class's numbers are never rewritten; instead each joint
//!   of the model that is a hinge (or a limited ball, for `range`) and takes one of
//!   these from a class gets the converted value set on itself. So the classes mean
//!   what they meant for every element of the model written or read before
//!   (a joint added later to such a class reads the class's number in the new
//!   unit: set its `range` on the joint).

use std::f64::consts::PI;

use crate::error::ErrorKind;
use crate::model::Model;
use crate::model::layout::{JointType, class_in_force, effective, joint_type};
use crate::model::pose::{Angles, euler_rotation};
use crate::model::settings;
use crate::model::tree::{Attached, Attr, Node};
use crate::schema::{ElementKind, Role};
use crate::value::Value;

/// The compiler's `angle` and `eulerseq` as a model sets them (explicitly, in its
/// merged settings); `None` where it does not.
#[derive(Clone, Debug, Default, PartialEq)]
struct Explicit {
    angle: Option<Value>,
    eulerseq: Option<Value>,
}

impl Explicit {
    /// The explicit values of the merged `compiler` of `sections`.
    fn of(sections: &[Node]) -> Explicit {
        let compiler = sections.iter().find(|n| n.kind() == ElementKind::COMPILER);
        let get = |name: &str| compiler.and_then(|c| c.attr(c.kind().attr_index(name)?)).cloned();
        Explicit { angle: get("angle"), eulerseq: get("eulerseq") }
    }
}

/// Whether an `angle` value means degrees (MuJoCo's default: anything but `radian`).
fn is_degree(v: Option<&Value>) -> bool {
    v.and_then(Value::as_str).is_none_or(|a| a != "radian")
}

/// An `eulerseq` value as three letters of `xyzXYZ`; `None` for any other.
fn sequence(v: Option<&Value>) -> Option<[u8; 3]> {
    let s = v.and_then(Value::as_str).unwrap_or("xyz");
    let seq = <[u8; 3]>::try_from(s.as_bytes()).ok()?;
    seq.iter().all(|c| b"xyzXYZ".contains(c)).then_some(seq)
}

/// How a model's numbers change: from its conventions to the receiving model's, and
/// the receiving model's values of the attributes that change.
#[derive(Clone, Debug)]
pub(crate) struct Change {
    from: Angles,
    to: Angles,
    /// The receiving model's `angle`, when the unit changes.
    angle: Option<Value>,
    /// The receiving model's `eulerseq`, when the sequence changes.
    eulerseq: Option<Value>,
}

impl Change {
    /// The change that brings a model whose merged settings are `theirs` into the
    /// conventions of `ours`: `None` when no attribute is set on both sides with
    /// different values. An `eulerseq` that is not three of `xyzXYZ` cannot be
    /// converted ([`ErrorKind::AttributeConflict`]).
    pub(crate) fn between(ours: &[Node], theirs: &[Node]) -> Result<Option<Change>, ErrorKind> {
        let (o, t) = (Explicit::of(ours), Explicit::of(theirs));
        let unit = match (&o.angle, &t.angle) {
            (Some(a), Some(b)) => is_degree(Some(a)) != is_degree(Some(b)),
            _ => false,
        };
        let seq = match (&o.eulerseq, &t.eulerseq) {
            (Some(a), Some(b)) => a.as_str() != b.as_str(),
            _ => false,
        };
        if !unit && !seq {
            return Ok(None);
        }
        let conflict = |a: &Option<Value>, b: &Option<Value>| ErrorKind::AttributeConflict {
            tag: "compiler",
            attribute: "eulerseq",
            ours: a.as_ref().map(Value::to_string).unwrap_or_default(),
            theirs: b.as_ref().map(Value::to_string).unwrap_or_default(),
        };
        let from_seq =
            sequence(t.eulerseq.as_ref()).ok_or_else(|| conflict(&o.eulerseq, &t.eulerseq))?;
        let to_seq = if seq {
            sequence(o.eulerseq.as_ref()).ok_or_else(|| conflict(&o.eulerseq, &t.eulerseq))?
        } else {
            from_seq
        };
        let from_deg = is_degree(t.angle.as_ref());
        let to_deg = if unit { !from_deg } else { from_deg };
        Ok(Some(Change {
            from: Angles::new(from_deg, from_seq),
            to: Angles::new(to_deg, to_seq),
            angle: if unit { o.angle } else { None },
            eulerseq: if seq { o.eulerseq } else { None },
        }))
    }

    /// The factor that takes an angle in the source unit to the receiving one.
    fn scale(&self) -> f64 {
        match (self.from.degrees(), self.to.degrees()) {
            (true, false) => PI / 180.0,
            (false, true) => 180.0 / PI,
            _ => 1.0,
        }
    }

    fn unit_changes(&self) -> bool {
        self.from.degrees() != self.to.degrees()
    }

    fn seq_changes(&self) -> bool {
        self.from.seq() != self.to.seq()
    }
}

/// `child` in the conventions of a model whose merged settings are `ours`; `None`
/// when nothing needs converting (see the module docs), so `child` stays shared.
///
/// # Errors
/// [`ErrorKind::AttributeConflict`] on `eulerseq` for a sequence that cannot be
/// converted (not three of `xyzXYZ`, or a `replicate` turning about several axes).
pub(crate) fn into_conventions(ours: &[Node], child: &Model) -> Result<Option<Model>, ErrorKind> {
    let theirs = settings::merged(child)?;
    match Change::between(ours, &theirs)? {
        None => Ok(None),
        Some(change) => convert_model(child, &change).map(Some),
    }
}

/// `model` (and every model attached in it, which reads its numbers as `model`'s
/// merged settings say) with its numbers converted by `change`.
fn convert_model(model: &Model, change: &Change) -> Result<Model, ErrorKind> {
    let autolimits = settings::merged(model)?
        .iter()
        .find(|n| n.kind() == ElementKind::COMPILER)
        .and_then(|c| c.attr(c.kind().attr_index("autolimits")?))
        .and_then(Value::as_str)
        .is_none_or(|v| v != "false");
    let mut failed: Option<ErrorKind> = None;
    let root = model.root.rebuild(|node, children| {
        if failed.is_some() {
            return node.clone();
        }
        let attrs = match converted_attrs(model, node, change, autolimits) {
            Ok(a) => a,
            Err(e) => {
                failed = Some(e);
                None
            }
        };
        let same_children = children.iter().zip(node.children().iter()).all(|(a, b)| a.ptr_eq(b));
        let mut out = match (attrs, same_children) {
            (None, true) => node.clone(),
            (attrs, _) => node.with_parts(attrs.unwrap_or_else(|| node.attrs().to_vec()), children),
        };
        if let Some(a) = node.attached() {
            match convert_model(&a.model, change) {
                Ok(m) => out = out.with_attached(Attached { scope: a.scope.clone(), model: m }),
                Err(e) => failed = Some(e),
            }
        }
        out
    });
    if let Some(e) = failed {
        return Err(e);
    }
    let mut index = model.index.clone();
    // The merged settings change (the compilers say the receiving model's values).
    index.merged = Default::default();
    Ok(model.next(root, index))
}

/// The converted attributes of one element of `model`, `None` when none changes.
fn converted_attrs(
    model: &Model,
    node: &Node,
    change: &Change,
    autolimits: bool,
) -> Result<Option<Vec<Attr>>, ErrorKind> {
    let kind = node.kind();
    let mut attrs: Option<Vec<Attr>> = None;
    let set = |attrs: &mut Option<Vec<Attr>>, name: &str, v: Option<Value>| {
        let Some(i) = kind.attr_index(name) else { return };
        let list = attrs.get_or_insert_with(|| node.attrs().to_vec());
        let i = i as u16;
        match (list.binary_search_by_key(&i, |(k, _)| *k), v) {
            (Ok(p), Some(v)) => list[p].1 = v,
            (Err(p), Some(v)) => list.insert(p, (i, v)),
            (Ok(p), None) => {
                list.remove(p);
            }
            (Err(_), None) => {}
        }
    };
    let own = |name: &str| kind.attr_index(name).and_then(|i| node.attr(i));
    if kind == ElementKind::COMPILER {
        if let Some(v) = &change.angle {
            if own("angle").is_some() {
                set(&mut attrs, "angle", Some(v.clone()));
            }
        }
        if let Some(v) = &change.eulerseq {
            if own("eulerseq").is_some() {
                set(&mut attrs, "eulerseq", Some(v.clone()));
            }
        }
        return Ok(attrs);
    }
    if kind.is(Role::Replicate) {
        if let Some(e) = own("euler").and_then(Value::as_floats) {
            let e = replicate_euler(e, change).ok_or_else(|| ErrorKind::AttributeConflict {
                tag: "replicate",
                attribute: "euler",
                ours: String::from_utf8_lossy(&change.to.seq()).into_owned(),
                theirs: String::from_utf8_lossy(&change.from.seq()).into_owned(),
            })?;
            set(&mut attrs, "euler", Some(Value::Floats(e.into())));
        }
        return Ok(attrs);
    }
    if kind.attr_index("axisangle").is_some() {
        if let Some(a) = own("axisangle").and_then(Value::as_floats).filter(|a| a.len() == 4) {
            if change.unit_changes() {
                let v = [a[0], a[1], a[2], a[3] * change.scale()];
                set(&mut attrs, "axisangle", Some(Value::Floats(v.into())));
            }
        }
        if let Some(e) = own("euler").and_then(Value::as_floats) {
            if change.seq_changes() {
                let e = [0, 1, 2].map(|i| e.get(i).copied().unwrap_or(0.0));
                let q = euler_rotation(&change.from, e);
                let a = axis_angle_of(q, change.to.degrees());
                set(&mut attrs, "euler", None);
                set(&mut attrs, "axisangle", Some(Value::Floats(a.into())));
            } else if change.unit_changes() {
                let v: Vec<f64> = e.iter().map(|x| x * change.scale()).collect();
                set(&mut attrs, "euler", Some(Value::Floats(v.into())));
            }
        }
    }
    if kind.is(Role::Joint) && change.unit_changes() {
        for (name, v) in joint_values(model, node, autolimits, change.scale()) {
            set(&mut attrs, name, Some(v));
        }
    }
    Ok(attrs)
}

/// A joint's `range`, `ref` and `springref` (its own, or its classes') converted by
/// `scale` where MuJoCo converts them: `range` of a limited hinge or ball, `ref` and
/// `springref` of a hinge.
fn joint_values(
    model: &Model,
    node: &Node,
    autolimits: bool,
    scale: f64,
) -> Vec<(&'static str, Value)> {
    let class = class_in_force(model, node);
    let ty = joint_type(model, node, class);
    let value = |name: &str| effective(model, node, class, name);
    let mut out = Vec::new();
    if matches!(ty, JointType::Hinge | JointType::Ball) {
        if let Some(r) = value("range").and_then(Value::as_floats) {
            let limited = match value("limited").and_then(Value::as_str) {
                Some("true") => true,
                Some("false") => false,
                _ => autolimits && r.iter().any(|x| *x != 0.0),
            };
            if limited {
                out.push(("range", Value::Floats(r.iter().map(|x| x * scale).collect())));
            }
        }
    }
    if ty == JointType::Hinge {
        for name in ["ref", "springref"] {
            if let Some(Value::Float(x)) = value(name) {
                out.push((name, Value::Float(x * scale)));
            }
        }
    }
    out
}

/// The `axisangle` of the unit quaternion `q`, its angle in degrees or radians.
pub(crate) fn axis_angle_of(q: [f64; 4], degrees: bool) -> [f64; 4] {
    // The rotation with w >= 0: the angle in [0, pi].
    let q = if q[0] < 0.0 { q.map(|x| -x) } else { q };
    let s = (q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    let (axis, angle) = if s < 1e-300 {
        // No rotation: MuJoCo refuses an axis of length 0.
        ([0.0, 0.0, 1.0], 0.0)
    } else {
        ([q[1] / s, q[2] / s, q[3] / s], 2.0 * s.atan2(q[0]))
    };
    let angle = if degrees { angle.to_degrees() } else { angle };
    [axis[0], axis[1], axis[2], angle]
}

/// A `replicate`'s `euler` in the receiving conventions: scaled to its unit and, when
/// the sequence changes, carried to a letter of the same axis; `None` when it turns
/// about several axes (or about one the new sequence lacks) and the sequence changes.
pub(crate) fn replicate_euler(e: &[f64], change: &Change) -> Option<Vec<f64>> {
    let scaled: Vec<f64> = e.iter().map(|x| x * change.scale()).collect();
    if !change.seq_changes() {
        return Some(scaled);
    }
    let (from, to) = (change.from.seq(), change.to.seq());
    let mut turns = scaled.iter().enumerate().filter(|(_, x)| **x != 0.0);
    let Some((i, angle)) = turns.next() else { return Some(scaled) };
    if turns.next().is_some() || i >= 3 {
        return None;
    }
    // One rotation: about the fixed or the moving axis alike.
    let axis = from[i].to_ascii_lowercase();
    let j = to.iter().position(|c| c.to_ascii_lowercase() == axis)?;
    let mut out = vec![0.0; scaled.len().max(3)];
    out[j] = *angle;
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn change(from: (bool, &[u8; 3]), to: (bool, &[u8; 3])) -> Change {
        Change {
            from: Angles::new(from.0, *from.1),
            to: Angles::new(to.0, *to.1),
            angle: None,
            eulerseq: None,
        }
    }

    /// The rotation of an `axisangle`, as MuJoCo builds it.
    fn quat_of(a: [f64; 4], degrees: bool) -> [f64; 4] {
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let angle = if degrees { a[3].to_radians() } else { a[3] };
        let (s, c) = (angle / 2.0).sin_cos();
        [c, s * a[0] / n, s * a[1] / n, s * a[2] / n]
    }

    fn same_rotation(p: [f64; 4], q: [f64; 4]) -> bool {
        let d = |s: f64| p.iter().zip(q).map(|(a, b)| (a - s * b).abs()).fold(0.0, f64::max);
        d(1.0) < 1e-12 || d(-1.0) < 1e-12
    }

    #[test]
    fn an_euler_in_any_sequence_becomes_an_axisangle_of_the_same_rotation() {
        let seqs: [&[u8; 3]; 6] = [b"xyz", b"ZYX", b"zXy", b"xyx", b"XzX", b"yYz"];
        let angles = [[10.0, -20.0, 30.0], [170.0, 80.0, -179.0], [0.0, 90.0, 0.0], [0.0; 3]];
        for seq in seqs {
            for degrees in [true, false] {
                for e in angles {
                    let e = if degrees { e } else { e.map(f64::to_radians) };
                    let q = euler_rotation(&Angles::new(degrees, *seq), e);
                    for to_degrees in [true, false] {
                        let a = axis_angle_of(q, to_degrees);
                        assert!(same_rotation(q, quat_of(a, to_degrees)), "{seq:?} {e:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn no_rotation_is_an_axisangle_with_a_unit_axis() {
        assert_eq!(axis_angle_of([1.0, 0.0, 0.0, 0.0], true), [0.0, 0.0, 1.0, 0.0]);
        // The rotation with w < 0 is the same, the angle at most half a turn.
        let a = axis_angle_of([-0.5f64.sqrt(), 0.0, 0.0, -0.5f64.sqrt()], true);
        assert!((a[3] - 90.0).abs() < 1e-12 && (a[2] - 1.0).abs() < 1e-12, "{a:?}");
    }

    #[test]
    fn a_replicate_turning_about_one_axis_keeps_the_axis_in_the_new_sequence() {
        let c = change((true, b"zyx"), (false, b"XYZ"));
        let out = replicate_euler(&[90.0, 0.0, 0.0], &c).unwrap();
        assert_eq!(out, [0.0, 0.0, 90f64.to_radians()]);
        assert_eq!(replicate_euler(&[0.0; 3], &c).unwrap(), [0.0; 3]);
        assert_eq!(replicate_euler(&[10.0, 5.0, 0.0], &c), None);
        // An axis the new sequence lacks.
        let c = change((true, b"xyz"), (true, b"zyz"));
        assert_eq!(replicate_euler(&[10.0, 0.0, 0.0], &c), None);
        // Only the unit changes: scaled, on any axes.
        let c = change((false, b"xyz"), (true, b"xyz"));
        let out = replicate_euler(&[PI, PI / 2.0, 0.0], &c).unwrap();
        assert!((out[0] - 180.0).abs() < 1e-12 && (out[1] - 90.0).abs() < 1e-12);
    }

    fn compiler(attrs: &str) -> Vec<Node> {
        let m = Model::from_xml_str(&format!("<mujoco><compiler {attrs}/></mujoco>")).unwrap();
        settings::own_sections(&m)
    }

    #[test]
    fn only_values_both_sides_set_and_differ_are_converted() {
        let between = |a: &str, b: &str| Change::between(&compiler(a), &compiler(b));
        assert!(between("", r#"angle="radian""#).unwrap().is_none());
        assert!(between(r#"angle="radian""#, "").unwrap().is_none());
        assert!(between(r#"angle="radian""#, r#"angle="radian""#).unwrap().is_none());
        let c = between(r#"angle="radian""#, r#"angle="degree""#).unwrap().unwrap();
        assert!((c.scale() - PI / 180.0).abs() < 1e-15 && !c.seq_changes());
        let c = between(r#"eulerseq="XYZ""#, r#"angle="radian" eulerseq="zyx""#).unwrap().unwrap();
        assert!(c.seq_changes() && !c.unit_changes() && !c.from.degrees());
        // A sequence MuJoCo refuses cannot be converted.
        let e = between(r#"eulerseq="xyz""#, r#"eulerseq="xyq""#).unwrap_err();
        assert!(matches!(e, ErrorKind::AttributeConflict { attribute: "eulerseq", .. }));
    }
}
