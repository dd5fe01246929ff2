//! The checks of an `<inertial>`'s own values (MuJoCo's `mjCBody::Compile` and its
//! `mjuu_fullInertia`, whose eigenvalues are computed here as MuJoCo computes them).

use super::{At, Check, found, on};

/// MuJoCo's `mjEPS`.
const EPS: f64 = 1e-14;
/// MuJoCo's tolerance of its 3x3 eigen solver (`kEigEPS`).
const EIG_EPS: f64 = 1e-12;

/// The inertial's `fullinertia`, when given (MuJoCo's "defined": its first number not
/// nan).
pub(crate) fn fullinertia(at: &At<'_, '_>) -> Option<[f64; 6]> {
    let f = at.floats("fullinertia")?;
    (f.len() == 6 && !f[0].is_nan()).then(|| [f[0], f[1], f[2], f[3], f[4], f[5]])
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "inertial-full-and-diagonal",
        on: on::inertial,
        test: |at| {
            fullinertia(at)?;
            at.floats("diaginertia")?.iter().take(3).any(|x| *x != 0.0).then_some(())?;
            found("diaginertia", "fullinertia and diagonal inertia cannot both be specified")
        },
        fix: "give fullinertia or diaginertia, not both",
    },
    Check {
        name: "inertial-full-eigenvalues",
        on: on::inertial,
        test: |at| {
            let eig = eigenvalues(&fullinertia(at)?);
            (eig[2] < EPS).then_some(())?;
            let message = "error 'inertia must have positive eigenvalues' in fullinertia";
            found("fullinertia", message)
        },
        fix: "give fullinertia a positive-definite matrix (ixx iyy izz ixy ixz iyz)",
    },
];

/// The eigenvalues of the symmetric matrix `fullinertia` (`ixx iyy izz ixy ixz iyz`)
/// as MuJoCo's `mjuu_eig3` computes them (Jacobi rotations kept as a quaternion, the
/// same operations in the same order), largest first.
pub(crate) fn eigenvalues(f: &[f64; 6]) -> [f64; 3] {
    let mat = [f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2]];
    let mut quat = [1.0, 0.0, 0.0, 0.0];
    let mut eig = [0.0; 3];
    for _ in 0..500 {
        let v = quat2mat(&quat);
        let d = mulmat(&mulmat(&transpose(&v), &mat), &v);
        eig = [d[0], d[4], d[8]];
        let (rk, ck, rotk) = if d[1].abs() > d[2].abs() && d[1].abs() > d[5].abs() {
            (0, 1, 2)
        } else if d[2].abs() > d[5].abs() {
            (0, 2, 1)
        } else {
            (1, 2, 0)
        };
        if d[3 * rk + ck].abs() < EIG_EPS {
            break;
        }
        let tau = (d[4 * ck] - d[4 * rk]) / (2.0 * d[3 * rk + ck]);
        let t = if tau >= 0.0 {
            1.0 / (tau + (1.0 + tau * tau).sqrt())
        } else {
            -1.0 / (-tau + (1.0 + tau * tau).sqrt())
        };
        let c = 1.0 / (1.0 + t * t).sqrt();
        if c > 1.0 - EIG_EPS {
            break;
        }
        let mut rot = [0.0; 4];
        let s = (0.5 - 0.5 * c).sqrt();
        rot[rotk + 1] = if tau >= 0.0 { -s } else { s };
        if rotk == 1 {
            rot[rotk + 1] = -rot[rotk + 1];
        }
        rot[0] = (1.0 - rot[rotk + 1] * rot[rotk + 1]).sqrt();
        normvec(&mut rot);
        quat = mulquat(&quat, &rot);
        normvec(&mut quat);
    }
    // Sorted largest first, as MuJoCo sorts them (0, 1, 0; a tie left in place).
    for j in 0..3 {
        let j1 = j % 2;
        if eig[j1] + EIG_EPS < eig[j1 + 1] {
            eig.swap(j1, j1 + 1);
        }
    }
    eig
}

/// MuJoCo's `mjuu_normvec`: `v` scaled to unit length unless near zero or near unit.
fn normvec(v: &mut [f64]) {
    let n: f64 = v.iter().map(|x| x * x).sum();
    if n < EPS {
        return;
    }
    let n = n.sqrt();
    if (n - 1.0).abs() > EPS {
        v.iter_mut().for_each(|x| *x /= n);
    }
}

/// MuJoCo's `mjuu_quat2mat`.
fn quat2mat(q: &[f64; 4]) -> [f64; 9] {
    if *q == [1.0, 0.0, 0.0, 0.0] {
        return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    }
    let (q00, q01, q02, q03) = (q[0] * q[0], q[0] * q[1], q[0] * q[2], q[0] * q[3]);
    let (q11, q12, q13) = (q[1] * q[1], q[1] * q[2], q[1] * q[3]);
    let (q22, q23, q33) = (q[2] * q[2], q[2] * q[3], q[3] * q[3]);
    [
        q00 + q11 - q22 - q33,
        2.0 * (q12 - q03),
        2.0 * (q13 + q02),
        2.0 * (q12 + q03),
        q00 - q11 + q22 - q33,
        2.0 * (q23 - q01),
        2.0 * (q13 - q02),
        2.0 * (q23 + q01),
        q00 - q11 - q22 + q33,
    ]
}

/// MuJoCo's `mjuu_mulquat` (normalized).
fn mulquat(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    let mut r = [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ];
    normvec(&mut r);
    r
}

/// MuJoCo's `mjuu_mulmat` (3x3, row-major).
fn mulmat(a: &[f64; 9], b: &[f64; 9]) -> [f64; 9] {
    let mut r = [0.0; 9];
    for i in 0..3 {
        for j in 0..3 {
            r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
        }
    }
    r
}

/// The transpose of a 3x3 matrix.
fn transpose(m: &[f64; 9]) -> [f64; 9] {
    [m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]]
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn inertial(attrs: &str) -> String {
        format!(
            r#"<mujoco><worldbody><body><inertial pos="0 0 0" mass="1" {attrs}/></body></worldbody></mujoco>"#
        )
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn full_inertia_is_judged_as_mujoco_judges_it() {
        let pairs = [
            (
                inertial(r#"diaginertia="0 0 1e-300" fullinertia="1 1 1 0 0 0""#),
                inertial(r#"diaginertia="0 0 0" fullinertia="1 1 1 0 0 0""#),
            ),
            (
                inertial(r#"diaginertia="nan 0 0" fullinertia="1 1 1 0 0 0""#),
                inertial(r#"diaginertia="1 1 1" fullinertia="nan 1 1 0 0 0""#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("inertial-full-and-diagonal", &pairs);
        let pairs = [
            (inertial(r#"fullinertia="1 1 1 5 0 0""#), inertial(r#"fullinertia="1 1 1 0 0 0""#)),
            (
                inertial(r#"fullinertia="1 1 1 1 1 1""#),
                inertial(r#"fullinertia="1 1 1e-14 0 0 0""#),
            ),
            (
                inertial(r#"fullinertia="2 2 2 1 1 -1""#),
                inertial(r#"fullinertia="2 2 2 0.5 0.5 0""#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("inertial-full-eigenvalues", &pairs);
    }
}
