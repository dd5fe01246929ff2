//! Poses as MuJoCo's compiler computes them: positions and orientations of bodies,
//! frames and sites from their attributes, composed down the tree.

use crate::model::tree::Node;
use crate::value::Value;

/// A rigid transform: position and unit quaternion (w, x, y, z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pose {
    pub(crate) pos: [f64; 3],
    pub(crate) quat: [f64; 4],
}

pub(crate) const IDENTITY: Pose = Pose { pos: [0.0; 3], quat: [1.0, 0.0, 0.0, 0.0] };

pub(crate) fn qmul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

pub(crate) fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let p = qmul(qmul(q, [0.0, v[0], v[1], v[2]]), [q[0], -q[1], -q[2], -q[3]]);
    [p[1], p[2], p[3]]
}

pub(crate) fn normalize4(q: [f64; 4]) -> [f64; 4] {
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
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Angles {
    degrees: bool,
    seq: [u8; 3],
}

impl Angles {
    /// As the compiler settings `compiler` say (`angle`, `eulerseq`); MuJoCo's
    /// defaults (degrees, `xyz`) without one.
    pub(crate) fn of(compiler: Option<&Node>) -> Angles {
        Angles {
            degrees: compiler
                .and_then(|c| c.attr(c.kind().attr_index("angle")?))
                .and_then(Value::as_str)
                .is_none_or(|a| a != "radian"),
            seq: compiler
                .and_then(|c| c.attr(c.kind().attr_index("eulerseq")?))
                .and_then(Value::as_str)
                .and_then(|s| <[u8; 3]>::try_from(s.as_bytes()).ok())
                .unwrap_or(*b"xyz"),
        }
    }

    /// Angles in degrees (`true`) or radians, read in the sequence `seq`.
    pub(crate) fn new(degrees: bool, seq: [u8; 3]) -> Angles {
        Angles { degrees, seq }
    }

    /// Whether angles are in degrees.
    pub(crate) fn degrees(&self) -> bool {
        self.degrees
    }

    /// The euler sequence.
    pub(crate) fn seq(&self) -> [u8; 3] {
        self.seq
    }

    pub(crate) fn radians(&self, a: f64) -> f64 {
        if self.degrees { a.to_radians() } else { a }
    }
}

pub(crate) fn floats<'a>(node: &'a Node, name: &str) -> Option<&'a [f64]> {
    node.attr(node.kind().attr_index(name)?).and_then(Value::as_floats)
}

/// The pose an element (body, frame, site, geom) gives its content, as MuJoCo reads
/// it: `pos`, and the orientation in whichever form it is given (`quat`,
/// `axisangle`, `euler` with the compiler's sequence and angle unit, `xyaxes`,
/// `zaxis`); a `fromto` (sites, geoms) gives both, its middle and the direction
/// from its end back to its start as the z axis.
pub(crate) fn local_pose(node: &Node, angles: &Angles) -> Pose {
    if let Some(ft) = floats(node, "fromto").filter(|f| f.len() == 6) {
        let (a, b) = ([ft[0], ft[1], ft[2]], [ft[3], ft[4], ft[5]]);
        let pos = [0, 1, 2].map(|i| (a[i] + b[i]) / 2.0);
        // MuJoCo's z axis points from `to` back to `from`.
        return Pose { pos, quat: z_to(unit([a[0] - b[0], a[1] - b[1], a[2] - b[2]])) };
    }
    // Arrays may be shorter than their schema length (as in the reference): missing
    // entries are 0.
    let pos = floats(node, "pos")
        .map_or([0.0; 3], |p| [0, 1, 2].map(|i| p.get(i).copied().unwrap_or(0.0)));
    let quat = if let Some(q) = floats(node, "quat").filter(|q| q.len() == 4) {
        normalize4([q[0], q[1], q[2], q[3]])
    } else if let Some(a) = floats(node, "axisangle").filter(|a| a.len() == 4) {
        axis_angle([a[0], a[1], a[2]], angles.radians(a[3]))
    } else if let Some(e) = floats(node, "euler").filter(|e| e.len() == 3) {
        euler_rotation(angles, [e[0], e[1], e[2]])
    } else if let Some(a) = floats(node, "xyaxes").filter(|a| a.len() == 6) {
        let x = unit([a[0], a[1], a[2]]);
        let y0 = [a[3], a[4], a[5]];
        let d = x[0] * y0[0] + x[1] * y0[1] + x[2] * y0[2];
        let y = unit([y0[0] - d * x[0], y0[1] - d * x[1], y0[2] - d * x[2]]);
        from_columns(x, y, cross(x, y))
    } else if let Some(z) = floats(node, "zaxis").filter(|z| z.len() == 3) {
        z_to(unit([z[0], z[1], z[2]]))
    } else {
        [1.0, 0.0, 0.0, 0.0]
    };
    Pose { pos, quat }
}

/// The rotation of euler angles `e`, in the compiler's sequence and angle unit, as
/// MuJoCo composes it (`ResolveOrientation`).
pub(crate) fn euler_rotation(angles: &Angles, e: [f64; 3]) -> [f64; 4] {
    let mut q = [1.0, 0.0, 0.0, 0.0];
    for (i, c) in angles.seq.iter().enumerate() {
        let axis = match c.to_ascii_lowercase() {
            b'x' => [1.0, 0.0, 0.0],
            b'y' => [0.0, 1.0, 0.0],
            _ => [0.0, 0.0, 1.0],
        };
        let r = axis_angle(axis, angles.radians(e[i]));
        // Lower case: axes that move with the frame (multiply on the right); upper
        // case: fixed axes (on the left).
        q = if c.is_ascii_lowercase() { qmul(q, r) } else { qmul(r, q) };
    }
    q
}

/// The shortest rotation taking the z axis to the unit vector `z`.
fn z_to(z: [f64; 3]) -> [f64; 4] {
    let axis = cross([0.0, 0.0, 1.0], z);
    let s = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
    if s < 1e-12 {
        if z[2] >= 0.0 { [1.0, 0.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0, 0.0] }
    } else {
        axis_angle(axis, s.atan2(z[2]))
    }
}

/// `outer` then `inner`: the pose of `inner` (given in `outer`'s frame) in the frame
/// `outer` is given in.
pub(crate) fn compose(outer: Pose, inner: Pose) -> Pose {
    let p = rotate(outer.quat, inner.pos);
    Pose {
        pos: [outer.pos[0] + p[0], outer.pos[1] + p[1], outer.pos[2] + p[2]],
        quat: normalize4(qmul(outer.quat, inner.quat)),
    }
}

/// The inverse transform.
pub(crate) fn inverse(p: Pose) -> Pose {
    let conj = [p.quat[0], -p.quat[1], -p.quat[2], -p.quat[3]];
    let back = rotate(conj, p.pos);
    Pose { pos: [-back[0], -back[1], -back[2]], quat: conj }
}

/// The transform between consecutive copies of a `<replicate>`: its `offset`, and its
/// `euler` rotation in the compiler's sequence and angle unit.
pub(crate) fn replicate_step(node: &Node, angles: &Angles) -> Pose {
    let pos = floats(node, "offset")
        .map_or([0.0; 3], |p| [0, 1, 2].map(|i| p.get(i).copied().unwrap_or(0.0)));
    let quat = floats(node, "euler")
        .filter(|e| e.len() == 3)
        .map_or(IDENTITY.quat, |e| euler_rotation(angles, [e[0], e[1], e[2]]));
    Pose { pos, quat }
}
