//! The checks of an element's orientation (MuJoCo's `ResolveOrientation` and its XML
//! reader's `ReadAlternative` and `ReadQuat`), one helper for every element kind that
//! has one: bodies, inertials, geoms, sites, cameras and frames.

use crate::model::tree::Node;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::{At, Check, Found, found, found_element, numbers, on};

pub(crate) use crate::model::frame::ORIENTATIONS;

/// MuJoCo's `mjEPS` (the squared norm below which a vector is zero).
const EPS: f64 = 1e-14;

/// An element kind whose orientation MuJoCo resolves (the elements, not defaults).
fn oriented(k: ElementKind) -> bool {
    on::geom(k) || on::site(k) || on::camera(k) || on::body(k) || on::frame(k) || on::inertial(k)
}

/// An element kind whose own attributes MuJoCo's reader reads as an orientation: the
/// oriented elements and the defaults of geoms, sites and cameras.
fn read_oriented(k: ElementKind) -> bool {
    oriented(k) || ["geom", "site", "camera"].iter().any(|t| on::default_of(k, t))
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "orientation-multiple",
        // An inertial's extra orientations are refused by MuJoCo's schema instead.
        on: |k| read_oriented(k) && !on::inertial(k),
        test: |at| {
            let given = ORIENTATIONS.iter().filter(|a| at.own(a).is_some()).count();
            (given > 1).then_some(())?;
            found_element("multiple orientation specifiers are not allowed")
        },
        fix: "keep one of quat, axisangle, xyaxes, zaxis and euler",
    },
    Check {
        name: "orientation-zero-quaternion",
        on: read_oriented,
        test: |at| {
            let q = at.own("quat").and_then(numbers)?;
            (q.len() == 4 && q.iter().all(|x| *x == 0.0)).then_some(())?;
            found("quat", "zero quaternion is not allowed")
        },
        fix: "give quat a non-zero quaternion (1 0 0 0: no rotation)",
    },
    Check {
        name: "orientation-degenerate",
        on: oriented,
        test: degenerate,
        fix: "give the orientation non-zero, non-parallel axes and an eulerseq of x, y, z, X, Y, Z",
    },
];

/// The orientation alternative in force for the element: the attribute and numbers
/// of the nearest level (its own, then its classes') that gives one; `None` when
/// that level gives `quat` (no alternative to resolve) or none does.
pub(crate) fn alternative(at: &At<'_, '_>) -> Option<(&'static str, Vec<f64>)> {
    at.levels().into_iter().find_map(level_alternative).flatten()
}

/// The alternative a level gives: `Some(None)` for `quat` alone, `None` for nothing.
/// Of several (refused anyway), the last MuJoCo's reader reads.
fn level_alternative(level: &Node) -> Option<Option<(&'static str, Vec<f64>)>> {
    let own = |a: &str| level.kind().attr_index(a).and_then(|i| level.attr(i));
    let alt =
        ORIENTATIONS[1..].iter().rev().find_map(|a| own(a).and_then(numbers).map(|v| (*a, v)));
    match alt {
        Some(alt) => Some(Some(alt)),
        None => own("quat").map(|_: &Value| None),
    }
}

/// The squared norm of `v`.
fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum()
}

/// `v` normalized as MuJoCo's `mjuu_normvec` does (left as is when near unit length).
fn normalize(v: &mut [f64]) {
    let n = norm2(v);
    if n < EPS {
        return;
    }
    let n = n.sqrt();
    if (n - 1.0).abs() > EPS {
        v.iter_mut().for_each(|x| *x /= n);
    }
}

/// What `ResolveOrientation` says of the alternative `attr` = `v` with the compiler's
/// `eulerseq`, if it refuses it.
pub(crate) fn resolve_error(attr: &str, v: &[f64], eulerseq: &str) -> Option<&'static str> {
    match attr {
        "axisangle" if v.len() >= 3 && norm2(&v[..3]) < EPS => Some("axisangle too small"),
        "zaxis" if v.len() >= 3 && norm2(&v[..3]) < EPS => Some("zaxis too small"),
        "xyaxes" if v.len() >= 6 => {
            let (mut x, mut y) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
            if norm2(&x) < EPS {
                return Some("xaxis too small");
            }
            normalize(&mut x);
            let d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
            (0..3).for_each(|i| y[i] -= x[i] * d);
            if norm2(&y) < EPS {
                return Some("yaxis too small");
            }
            normalize(&mut y);
            let z =
                [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]];
            (norm2(&z) < EPS).then_some("cross(xaxis, yaxis) too small")
        }
        "euler" => eulerseq
            .chars()
            .take(3)
            .any(|c| !"xyzXYZ".contains(c))
            .then_some("euler sequence can only contain x, y, z, X, Y, Z"),
        _ => None,
    }
}

/// `orientation specification error '...' in geom` (and its site, camera, body,
/// frame and inertial forms): the alternative in force does not resolve. A geom or
/// site placed by `fromto` takes its orientation from it instead.
fn degenerate(at: &At<'_, '_>) -> Option<Found> {
    let k = at.kind();
    if (on::geom(k) || on::site(k))
        && at.floats("fromto").is_some_and(|f| f.first().is_some_and(|x| !x.is_nan()))
    {
        return None;
    }
    let (attr, v) = alternative(at)?;
    let err = resolve_error(attr, &v, &at.settings.eulerseq)?;
    let name = at.name();
    let attr = ORIENTATIONS.iter().find(|a| **a == attr).copied().unwrap_or("quat");
    let message = if k.is(Role::Body) && at.e.is_body {
        format!("error '{err}' in frame alternative")
    } else if on::inertial(k) {
        format!("error '{err}' in inertia alternative")
    } else if on::geom(k) {
        format!("orientation specification error '{err}' in geom '{name}'")
    } else if on::camera(k) {
        format!("orientation specification error '{err}' in camera '{name}'")
    } else {
        // A site, and a frame (MuJoCo's message calls a frame a site).
        format!("orientation specification error '{err}' in site '{name}'")
    };
    found(attr, message)
}

#[cfg(test)]
mod tests {
    use super::super::tests::{assert_pairs, refused};

    fn world(body: &str) -> String {
        format!("<mujoco><worldbody>{body}</worldbody></mujoco>")
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn every_oriented_element_refuses_a_degenerate_alternative() {
        let pairs = [
            (world(r#"<geom size=".1" zaxis="0 0 0"/>"#), world(r#"<geom size=".1" zaxis="0 0 1"/>"#)),
            (world(r#"<geom size=".1" zaxis="9e-8 0 0"/>"#), world(r#"<geom size=".1" zaxis="2e-7 0 0"/>"#)),
            (world(r#"<geom size=".1" axisangle="0 0 0 1"/>"#), world(r#"<geom size=".1" axisangle="0 0 1 0"/>"#)),
            (world(r#"<geom size=".1" xyaxes="0 0 0 0 1 0"/>"#), world(r#"<geom size=".1" xyaxes="1 0 0 0 1 0"/>"#)),
            (world(r#"<geom size=".1" xyaxes="1 0 0 2 0 0"/>"#), world(r#"<geom size=".1" xyaxes="1 0 0 2 1 0"/>"#)),
            (world(r#"<site zaxis="0 0 0"/>"#), world(r#"<site zaxis="nan 0 0"/>"#)),
            (world(r#"<camera xyaxes="1 0 0 0 0 0"/>"#), world(r#"<camera xyaxes="1 0 0 0 0 1"/>"#)),
            (world(r#"<body zaxis="0 0 0"/>"#), world(r#"<body zaxis="0 1 0"/>"#)),
            (world(r#"<frame zaxis="0 0 0"/>"#), world(r#"<frame zaxis="1 0 0"/>"#)),
            (
                world(r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" xyaxes="0 0 0 0 1 0"/></body>"#),
                world(r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1" xyaxes="0 1 0 0 0 1"/></body>"#),
            ),
            // fromto orients the geom or site: its zaxis is not read.
            (
                world(r#"<site type="capsule" size=".1" zaxis="0 0 0"/>"#),
                world(r#"<site type="capsule" size=".1" fromto="0 0 0 0 0 1" zaxis="0 0 0"/>"#),
            ),
            // A class's alternative holds unless a nearer level gives any orientation.
            (
                r#"<mujoco><default><geom zaxis="0 0 0"/></default><worldbody><geom size=".1"/></worldbody></mujoco>"#.into(),
                r#"<mujoco><default><geom zaxis="0 0 0"/></default><worldbody><geom size=".1" quat="1 0 0 0"/></worldbody></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><default><geom euler="0 0 0"/><default class="b"><geom zaxis="0 0 0"/></default></default><worldbody><geom class="b" size=".1"/></worldbody></mujoco>"#.into(),
                r#"<mujoco><default><geom zaxis="0 0 0"/><default class="b"><geom euler="0 0 0"/></default></default><worldbody><geom class="b" size=".1"/></worldbody></mujoco>"#.into(),
            ),
            // The compiler's eulerseq is read where euler is.
            (
                r#"<mujoco><compiler eulerseq="xyq"/><worldbody><geom size=".1" euler="0 0 0"/></worldbody></mujoco>"#.into(),
                r#"<mujoco><compiler eulerseq="xyq"/><worldbody><geom size=".1"/></worldbody></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><compiler eulerseq="xyq"/><worldbody><body euler="0 0 0"/></worldbody></mujoco>"#.into(),
                r#"<mujoco><compiler eulerseq="XYZ"/><worldbody><body euler="0 0 0"/></worldbody></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("orientation-degenerate", &pairs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's; the reader judges a class's defaults
    /// as it judges an element.
    #[test]
    fn the_reader_refuses_two_orientations_and_a_zero_quaternion() {
        let pairs = [
            (world(r#"<geom size=".1" euler="0 0 0" axisangle="0 0 1 0"/>"#), world(r#"<geom size=".1" euler="0 0 0"/>"#)),
            (world(r#"<frame zaxis="0 0 1" euler="0 0 0"/>"#), world(r#"<frame zaxis="0 0 1"/>"#)),
            (
                r#"<mujoco><default><geom quat="1 0 0 0" zaxis="0 0 1"/></default></mujoco>"#.into(),
                r#"<mujoco><default><geom quat="1 0 0 0"/></default><worldbody><geom size=".1" euler="0 0 0"/></worldbody></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("orientation-multiple", &pairs);
        let pairs = [
            (
                world(r#"<geom size=".1" quat="0 0 0 0"/>"#),
                world(r#"<geom size=".1" quat="nan 0 0 0"/>"#),
            ),
            (world(r#"<body quat="-0 0 0 0"/>"#), world(r#"<body quat="0 0 0 1"/>"#)),
            (
                r#"<mujoco><default><camera quat="0 0 0 0"/></default></mujoco>"#.into(),
                r#"<mujoco><default><camera quat="0 0 1 0"/></default></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("orientation-zero-quaternion", &pairs);
        // Both at once: each said.
        let both = world(r#"<site quat="0 0 0 0" zaxis="0 0 1"/>"#);
        assert_eq!(refused(&both), ["orientation-multiple", "orientation-zero-quaternion"]);
    }
}
