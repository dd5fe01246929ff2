//! The checks of an asset mesh's own values: its `builtin` shape's `params`
//! (MuJoCo's `mjs_makeMesh`, as MuJoCo 4.0.0 words it) and `maxhullvert` (its reader).

use super::{At, Check, Found, found, on};
use crate::schema::{ElementKind, Role};

/// An `<asset>` `<mesh>`.
fn asset_mesh(k: ElementKind) -> bool {
    k.is(Role::Mesh)
}

/// A `<mesh>` anywhere: in `<asset>`, or a default class's (MuJoCo's reader judges
/// both where they are written).
fn any_mesh(k: ElementKind) -> bool {
    k.is(Role::Mesh) || on::default_of(k, "mesh")
}

/// A number as C's `static_cast<int>` makes it on the machines MuJoCo runs on: cut
/// toward zero; nan and numbers past `int`'s range give its least value.
pub(crate) fn c_int(x: f64) -> i64 {
    if x.is_nan() || x >= 2_147_483_648.0 || x <= -2_147_483_649.0 {
        i64::from(i32::MIN)
    } else {
        x.trunc() as i64
    }
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "mesh-builtin-params",
        on: asset_mesh,
        test: builtin_params,
        fix: "give the builtin shape the parameters it takes, each in its range",
    },
    Check {
        name: "mesh-maxhullvert",
        on: any_mesh,
        test: |at| {
            // Its own value: a class's is judged where the class writes it.
            let n = at.own_int("maxhullvert")?;
            (n != -1 && n < 4).then_some(())?;
            found("maxhullvert", "maxhullvert must be larger than 3")
        },
        fix: "give maxhullvert -1 (no limit) or at least 4",
    },
];

/// What MuJoCo 4.0.0 refuses of a builtin mesh's `params` (read only when both are
/// written; a missing `params` is the reader's).
fn builtin_params(at: &At<'_, '_>) -> Option<Found> {
    let builtin = at.own_str("builtin")?;
    let p = at.own_floats("params").filter(|p| !p.is_empty())?;
    let msg = builtin_message(builtin, &p)?;
    found("params", msg)
}

/// MuJoCo's message for the builtin shape `builtin` with parameters `p`, if it
/// refuses them.
fn builtin_message(builtin: &str, p: &[f64]) -> Option<&'static str> {
    let n = p.len();
    match builtin {
        "none" => Some("Unsupported mesh type"),
        "hemisphere" | "sphere" => {
            let (count, negative, large, max) = if builtin == "sphere" {
                (
                    "Sphere mesh type requires 1 parameter",
                    "Sphere subdivision cannot be negative",
                    "Sphere subdivision cannot be greater than 4",
                    4,
                )
            } else {
                (
                    "Hemisphere mesh type requires 1 parameter",
                    "Hemisphere resolution cannot be negative",
                    "Hemisphere resolution cannot be greater than 10",
                    10,
                )
            };
            if n != 1 {
                return Some(count);
            }
            let s = c_int(p[0]);
            first(&[(s < 0, negative), (s > max, large)])
        }
        "supersphere" => {
            if n != 3 {
                return Some("Supersphere mesh type requires 3 parameters");
            }
            first(&[
                (c_int(p[0]) < 3, "Supersphere resolution must be greater than 2"),
                (p[1] < 0.0, "Supersphere 'e' cannot be negative"),
                (p[2] < 0.0, "Supersphere 'n' cannot be negative"),
            ])
        }
        "supertorus" => {
            if n != 4 {
                return Some("Supertorus mesh type requires 4 parameters");
            }
            first(&[
                (c_int(p[0]) < 3, "Supertorus resolution must be greater than 3"),
                (p[1] <= 0.0 || p[1] > 1.0, "Supertorus radius must be in (0, 1]"),
                (p[2] <= 0.0, "Supertorus 's' must be greater than 0"),
                (p[3] <= 0.0, "Supertorus 't' must be greater than 0"),
            ])
        }
        "wedge" => {
            if n != 5 {
                return Some("Wedge builtin mesh types require 5 parameters");
            }
            first(&[
                (p[2] <= 0.0 || p[2] > 180.0, "fov[0] must be a float between (0, 180] degrees"),
                (p[3] <= 0.0 || p[3] > 90.0, "`fov[1]` must be a float between (0, 90] degrees"),
                (
                    c_int(p[0]) <= 0 || c_int(p[1]) <= 0,
                    "Horizontal and vertical resolutions must be positive",
                ),
                (p[4] < 0.0 || p[4] > 1.0, "`gamma` must be a nonnegative float between [0, 1]"),
            ])
        }
        "plate" => {
            if n != 2 {
                return Some("Plate builtin mesh type requires 2 parameters");
            }
            (c_int(p[0]) <= 0 || c_int(p[1]) <= 0)
                .then_some("Horizontal and vertical resolutions must be positive")
        }
        "cone" => {
            if n != 2 {
                return Some("Cone mesh type requires 2 parameters");
            }
            first(&[
                (c_int(p[0]) < 3, "Cone nvert must be at least 3"),
                (!(0.0..=1.0).contains(&p[1]), "Cone radius must be in [0, 1]"),
            ])
        }
        "grid" => grid_message(p),
        "box" | "cylinder" | "ellipsoid" => {
            if n != 6 && n != 7 {
                return Some(
                    "Box/cylinder/ellipsoid mesh type requires 6 or 7 parameters (count[3], spacing[3], [dim])",
                );
            }
            first(&[
                (
                    n == 7 && !matches!(c_int(p[6]), 2 | 3),
                    "Mesh dim must be 2 or 3 for box/cylinder/ellipsoid",
                ),
                (
                    p[..3].iter().any(|c| c_int(*c) < 2),
                    "Box/cylinder/ellipsoid count must be at least 2",
                ),
            ])
        }
        "square" | "disc" => {
            if n != 6 {
                return Some("Square/disc mesh type requires 6 parameters (count[3], spacing[3])");
            }
            first(&[
                (p[..3].iter().any(|c| c_int(*c) < 1), "Count must be positive"),
                (c_int(p[2]) != 1, "Square/disc count[2] must be 1"),
            ])
        }
        _ => None,
    }
}

/// A grid's parameters: count, spacing, and an optional dim (3 when not given).
fn grid_message(p: &[f64]) -> Option<&'static str> {
    let n = p.len();
    if n != 6 && n != 7 {
        return Some("Grid mesh type requires 6 or 7 parameters (count[3], spacing[3], [dim])");
    }
    let counts_positive = p[..3].iter().all(|c| c_int(*c) > 0);
    let dim = if n == 7 { c_int(p[6]) } else { 3 };
    let dim_ok = matches!(dim, 2 | 3);
    first(&[
        (counts_positive && !dim_ok, "Grid dim must be 2 or 3"),
        (dim_ok && !counts_positive, "Grid count must be positive"),
        (
            counts_positive && dim == 2 && c_int(p[2]) != 1,
            "Grid count must be 1 along dimensions beyond dim",
        ),
    ])
}

/// The message of the first condition that holds.
fn first(conditions: &[(bool, &'static str)]) -> Option<&'static str> {
    conditions.iter().find(|(c, _)| *c).map(|(_, m)| *m)
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn mesh(attrs: &str) -> String {
        format!(r#"<mujoco><asset><mesh name="m" {attrs}/></asset></mujoco>"#)
    }

    fn builtin(shape: &str, params: &str) -> String {
        mesh(&format!(r#"builtin="{shape}" params="{params}""#))
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's: the refused one with the message the
    /// check words, the other compiled.
    #[test]
    fn builtin_params_are_judged_as_mujoco_judges_them() {
        let pairs = [
            ("hemisphere", "1 2", "2"),
            ("hemisphere", "-1", "-0.5"),
            ("hemisphere", "11", "10.9"),
            ("hemisphere", "nan", "10"),
            ("hemisphere", "1e20", "0"),
            ("sphere", "1 2", "2"),
            ("sphere", "-1", "-0.9"),
            ("sphere", "5", "4.9"),
            ("supersphere", "8 1", "8 1 1"),
            ("supersphere", "2.9 1 1", "3 0 0"),
            ("supersphere", "8 -1 1", "8 1 1"),
            ("supersphere", "3 -0 -1e-300", "3 -0 0"),
            ("supertorus", "8 .5 1", "8 .5 1 1"),
            ("supertorus", "2 .5 1 1", "3 1 1 1"),
            ("supertorus", "3 0 1 1", "3 1 1 1"),
            ("supertorus", "8 .5 0 1", "8 .5 1 1"),
            ("supertorus", "8 .5 1 0", "8 .5 1 1"),
            ("wedge", "8 8 60 60", "8 8 60 60 0"),
            ("wedge", "0 0 0 0 -1", "8 8 180 90 1"),
            ("wedge", "8 8 60 100 0", "8 8 60 90 0"),
            ("wedge", "0.5 8 180 90 1", "8 8 180 90 1"),
            ("wedge", "8 8 60 60 2", "8 8 60 60 1"),
            ("plate", "8", "8 8"),
            ("plate", "0 1", "2 2"),
            ("cone", "8", "8 1"),
            ("cone", "2.9 0", "3 0"),
            ("cone", "1e10 0.5", "3 0.5"),
            ("cone", "3 -0.1", "3 1"),
            ("cone", "3 nan", "3 0"),
            ("grid", "1 2", "2 2 2 1 1 1"),
            ("grid", "3 3 3 1 1 1 1", "2 2 2 1 1 1 3"),
            ("grid", "0 2 2 1 1 1", "2 2 2 -1 1 1"),
            ("grid", "2 2 2 1 1 1 2", "3 3 1 1 1 1 2"),
            ("box", "1 2", "2 2 2 1 1 1"),
            ("cylinder", "2 2 2 1 1 1 0", "2 2 2 1 1 1 2"),
            ("ellipsoid", "2 2 1 1 1 1 2.5", "2 2 2 1 1 1 3"),
            ("square", "2 2 1 1 1 1 2", "2 2 1 1 1 1"),
            ("disc", "2 2 2 -1 1 1", "2 2 1 1 1 1"),
            ("square", "0 2 2 1 1 1", "2 2 1 1 1 1"),
            ("disc", "-1 2 1 1 1 1", "2 2 1 -1 1 1"),
        ];
        for (shape, bad, good) in pairs {
            let (bad, good) = (builtin(shape, bad), builtin(shape, good));
            assert_pairs("mesh-builtin-params", &[(&bad, &good)]);
        }
        let none = mesh(r#"builtin="none" params="1 2 3""#);
        let vertices = mesh(r#"params="1 2 3" vertex="0 0 0 1 0 0 0 1 0 0 0 1""#);
        assert_pairs("mesh-builtin-params", &[(&none, &vertices)]);
    }

    #[test]
    fn the_message_is_mujocos_for_each_shape() {
        let words = |shape: &str, params: &str| {
            let p: Vec<f64> = params.split(' ').map(|x| x.parse().unwrap()).collect();
            super::builtin_message(shape, &p)
        };
        assert_eq!(words("cone", "2 2"), Some("Cone nvert must be at least 3"));
        assert_eq!(
            words("wedge", "0 0 10 0 -1"),
            Some("`fov[1]` must be a float between (0, 90] degrees")
        );
        assert_eq!(
            words("wedge", "0 0 10 10 -1"),
            Some("Horizontal and vertical resolutions must be positive")
        );
        assert_eq!(
            words("box", "3 3 3 1 1 1 1"),
            Some("Mesh dim must be 2 or 3 for box/cylinder/ellipsoid")
        );
        assert_eq!(
            words("box", "2 2 1 1 1 1 2"),
            Some("Box/cylinder/ellipsoid count must be at least 2")
        );
        assert_eq!(words("grid", "-1 2 1 1 1 1"), Some("Grid count must be positive"));
        // nan passes these comparisons in MuJoCo (its vertices are refused later, in
        // other words).
        assert_eq!(words("supersphere", "3 nan nan"), None);
        assert_eq!(words("wedge", "8 8 nan nan 0"), None);
    }

    /// Verdicts MuJoCo 4.0.0's; a class's value is judged in the class.
    #[test]
    fn maxhullvert_is_minus_one_or_at_least_four() {
        let v = r#"vertex="0 0 0 1 0 0 0 1 0 0 0 1""#;
        let pairs = [
            (mesh(&format!(r#"{v} maxhullvert="3""#)), mesh(&format!(r#"{v} maxhullvert="4""#))),
            (mesh(&format!(r#"{v} maxhullvert="-2""#)), mesh(&format!(r#"{v} maxhullvert="-1""#))),
            (
                format!(
                    r#"<mujoco><default><mesh maxhullvert="0"/></default><asset><mesh name="m" {v}/></asset></mujoco>"#
                ),
                format!(
                    r#"<mujoco><default><mesh maxhullvert="-1"/></default><asset><mesh name="m" {v}/></asset></mujoco>"#
                ),
            ),
            (
                format!(
                    r#"<mujoco><default><default class="a"><mesh maxhullvert="3"/></default></default><asset><mesh name="m" {v}/></asset></mujoco>"#
                ),
                format!(
                    r#"<mujoco><default><default class="a"><mesh maxhullvert="4"/></default></default><asset><mesh name="m" {v}/></asset></mujoco>"#
                ),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("mesh-maxhullvert", &pairs);
    }
}
