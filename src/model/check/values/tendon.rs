//! The checks of a tendon's own values and of its path, the sequence of its children
//! (MuJoCo's `mjCTendon::Compile` and `mjCWrap::ResolveReferences`).

use crate::model::check::target::{named, same};
use crate::model::layout::effective;
use crate::model::tree::Node;
use crate::schema::ElementKind;
use crate::value::Value;

use super::{At, Check, Found, found, found_element, on};

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "tendon-path-empty",
        on: on::tendon,
        test: |at| {
            at.e.node.children().is_empty().then_some(())?;
            found_element(format!("tendon '{}': path cannot be empty", at.name()))
        },
        fix: "give the tendon a path: joints for a fixed tendon, sites (and geoms) for a spatial one",
    },
    Check {
        name: "tendon-spatial-too-short",
        on: on::tendon,
        test: |at| {
            (spatial(at) && at.e.node.children().len() < 2).then_some(())?;
            found_element(format!(
                "tendon '{}': spatial path must contain at least two objects",
                at.name()
            ))
        },
        fix: "give the spatial tendon at least two sites",
    },
    Check {
        name: "tendon-width",
        on: on::tendon,
        test: |at| {
            // 0.003 when neither the tendon nor its classes give one.
            (spatial(at) && at.float("width").unwrap_or(0.003) <= 0.0).then_some(())?;
            found("width", format!("tendon '{}' must have positive width", at.name()))
        },
        fix: "give the spatial tendon a positive width",
    },
    Check {
        name: "tendon-armature-negative",
        on: on::tendon,
        test: |at| {
            let path = !at.e.node.children().is_empty();
            (path && at.float("armature")? < 0.0).then_some(())?;
            found("armature", format!("tendon '{}': tendon armature cannot be negative", at.name()))
        },
        fix: "give the tendon an armature of 0 or more",
    },
    Check {
        name: "tendon-springlength-order",
        on: on::tendon,
        test: |at| {
            // One number is both ends (MuJoCo copies it); its own value, else its
            // classes', whole.
            let s = at.get("springlength").and_then(Value::as_floats)?;
            (s.len() >= 2 && s[0] > s[1]).then_some(())?;
            found("springlength", "invalid springlength in tendon")
        },
        fix: "give springlength its low end first",
    },
    Check {
        name: "tendon-springyield-negative",
        on: on::tendon,
        test: |at| {
            (at.float("springyield")? < 0.0).then_some(())?;
            found("springyield", "springyield cannot be negative in tendon")
        },
        fix: "give springyield 0 or more",
    },
    Check {
        name: "tendon-wrap-geom-type",
        on: on::tendon,
        test: wrap_geom_type,
        fix: "wrap the tendon around a sphere or cylinder geom",
    },
    Check { name: "tendon-spatial-path", on: on::tendon, test: spatial_path, fix: PATH_FIX },
];

const PATH_FIX: &str = "make the path sites, each geom between two sites, each pulley between \
                        sites, no pulley last, no site twice in a row";

/// The wraps of a path, by kind.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Wrap {
    Site,
    Geom,
    Pulley,
    Joint,
}

/// The kind of wrap `n` is, a child of the tendon `tendon` (its schema kind).
fn wrap(tendon: ElementKind, n: &Node) -> Wrap {
    let k = Some(n.kind());
    if k == tendon.child("site") {
        Wrap::Site
    } else if k == tendon.child("geom") {
        Wrap::Geom
    } else if k == tendon.child("pulley") {
        Wrap::Pulley
    } else {
        Wrap::Joint
    }
}

/// A spatial tendon, as MuJoCo decides it: its path's first wrap is not a joint.
fn spatial(at: &At<'_, '_>) -> bool {
    at.e.node.children().iter().next().is_some_and(|c| wrap(at.kind(), c) != Wrap::Joint)
}

/// A wrapping geom that is not a sphere or cylinder (its type its own or its
/// classes'): `geom 'g' in tendon 't', wrap 1 is not sphere or cylinder`.
fn wrap_geom_type(at: &At<'_, '_>) -> Option<Found> {
    let model = at.e.model;
    for (i, c) in at.e.node.children().iter().enumerate() {
        if wrap(at.kind(), c) != Wrap::Geom {
            continue;
        }
        let Some(geom) = named(model, c, None, "geom") else { continue };
        let ty = geom.get("type").and_then(Value::as_str).unwrap_or("sphere");
        if ty != "sphere" && ty != "cylinder" {
            let name = geom.node.identifier().unwrap_or("");
            return found_element(format!(
                "geom '{name}' in tendon '{}', wrap {i} is not sphere or cylinder",
                at.name()
            ));
        }
    }
    None
}

/// The first fault of a spatial path, in MuJoCo's order: pulleys alone, a pulley
/// after a pulley or
/// last, a site with pulleys (or the path's ends) on both sides, a site repeated next
/// to itself, a geom not between two sites, a geom with a tendon armature.
fn spatial_path<'m>(at: &At<'_, 'm>) -> Option<Found> {
    // A path of one object is refused as too short first.
    if !spatial(at) || at.e.node.children().len() < 2 {
        return None;
    }
    let nodes: Vec<&'m Node> = at.e.node.children().iter().collect();
    let kinds: Vec<Wrap> = nodes.iter().map(|n| wrap(at.kind(), n)).collect();
    let sz = kinds.len();
    let name = at.name();
    // Pulleys alone name nothing MuJoCo can find.
    if kinds.iter().all(|k| *k == Wrap::Pulley) {
        return found_element(format!("tendon '{name}': no attached reference found"));
    }
    let prev = |i: usize| (i > 0).then(|| kinds[i - 1]);
    let next = |i: usize| kinds.get(i + 1).copied();
    for i in 0..sz {
        let message = match kinds[i] {
            Wrap::Pulley if prev(i) == Some(Wrap::Pulley) => {
                format!("tendon '{name}': consecutive pulleys (pos {i})")
            }
            Wrap::Pulley if i == sz - 1 => format!("tendon '{name}': path ends with pulley"),
            Wrap::Site
                if matches!(prev(i), None | Some(Wrap::Pulley))
                    && matches!(next(i), None | Some(Wrap::Pulley)) =>
            {
                format!("tendon '{name}': site {i} needs a neighbor that is not a pulley")
            }
            Wrap::Site if next(i) == Some(Wrap::Site) && same_site(at, nodes[i], nodes[i + 1]) => {
                format!("tendon '{name}': site {i} is repeated")
            }
            Wrap::Geom if prev(i) != Some(Wrap::Site) || next(i) != Some(Wrap::Site) => {
                format!("tendon '{name}': geom at pos {i} not bracketed by sites")
            }
            Wrap::Geom if at.float("armature").is_some_and(|a| a > 0.0) => {
                format!("tendon '{name}': geom wrapping not supported by tendon armature")
            }
            _ => continue,
        };
        return found_element(message);
    }
    None
}

/// Whether two site wraps name the same site.
fn same_site<'m>(at: &At<'_, 'm>, a: &'m Node, b: &'m Node) -> bool {
    let model = at.e.model;
    let site = |n: &'m Node| -> Option<(usize, &'m Value)> {
        let i = n.kind().attr_index("site")?;
        Some((i, effective(model, n, None, "site")?))
    };
    match (site(a), site(b)) {
        (Some((i, x)), Some((j, y))) => same((model, a, i, x), (model, b, j, y)),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    /// A model with a moving body holding site `s`, world sites `t` and `u`, a
    /// sphere `g`, a box `box`, joint `j`, and `tendon` in `<tendon>`.
    fn with(tendon: &str) -> String {
        format!(
            r#"<mujoco><worldbody><body name="b"><joint name="j"/><geom size=".1"/><site name="s"/></body>
            <site name="t"/><site name="u"/><geom name="g" size=".1"/><geom name="box" type="box" size=".1 .1 .1"/>
            </worldbody><tendon>{tendon}</tendon></mujoco>"#
        )
    }

    fn pairs(rule: &str, pairs: &[(&str, &str)]) {
        let texts: Vec<(String, String)> = pairs.iter().map(|(a, b)| (with(a), with(b))).collect();
        let refs: Vec<(&str, &str)> = texts.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs(rule, &refs);
    }

    const ST: &str = r#"<site site="s"/><site site="t"/>"#;

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_tendon_s_own_values_are_judged_as_mujoco_judges_them() {
        pairs(
            "tendon-path-empty",
            &[(r#"<fixed name="f"/>"#, r#"<fixed><joint joint="j" coef="1"/></fixed>"#)],
        );
        pairs(
            "tendon-spatial-too-short",
            &[(r#"<spatial><site site="s"/></spatial>"#, &format!("<spatial>{ST}</spatial>"))],
        );
        pairs(
            "tendon-width",
            &[
                (
                    &format!(r#"<spatial width="0">{ST}</spatial>"#),
                    &format!(r#"<spatial width="1e-9">{ST}</spatial>"#),
                ),
                (
                    &format!(r#"<spatial width="-0">{ST}</spatial>"#),
                    &format!(r#"<spatial>{ST}</spatial>"#),
                ),
            ],
        );
        pairs(
            "tendon-armature-negative",
            &[
                (
                    r#"<fixed armature="-1e-300"><joint joint="j" coef="1"/></fixed>"#,
                    r#"<fixed armature="-0"><joint joint="j" coef="1"/></fixed>"#,
                ),
                (
                    &format!(r#"<spatial armature="-1">{ST}</spatial>"#),
                    &format!(r#"<spatial armature="1">{ST}</spatial>"#),
                ),
            ],
        );
        pairs(
            "tendon-springlength-order",
            &[
                (
                    &format!(r#"<spatial springlength="-1 -2">{ST}</spatial>"#),
                    &format!(r#"<spatial springlength="-1 -1">{ST}</spatial>"#),
                ),
                (
                    &format!(r#"<spatial springlength="1 0">{ST}</spatial>"#),
                    &format!(r#"<spatial springlength="-1">{ST}</spatial>"#),
                ),
            ],
        );
        pairs(
            "tendon-springyield-negative",
            &[(
                &format!(r#"<spatial springyield="-1e-9">{ST}</spatial>"#),
                &format!(r#"<spatial springyield="0">{ST}</spatial>"#),
            )],
        );
    }

    /// A class's springlength of two numbers under the tendon's own one number is the
    /// tendon's one number, both ends; a class's width counts (MuJoCo 4.0.0's verdicts).
    #[test]
    fn a_tendon_s_class_is_its_default_class_s_tendon() {
        let text = format!(
            r#"<mujoco><default><tendon springlength="0 1"/></default><worldbody><site name="s"/>
            <site name="t" pos="1 0 0"/></worldbody><tendon><spatial springlength="2">{ST}</spatial></tendon></mujoco>"#
        );
        assert_eq!(super::super::tests::refused(&text), Vec::<&str>::new());
        // A tendon's class is the class's `<tendon>`.
        let width = |w: &str| {
            format!(
                r#"<mujoco><default><tendon width="{w}"/></default><worldbody><site name="s"/>
                <site name="t" pos="1 0 0"/></worldbody><tendon><spatial>{ST}</spatial></tendon></mujoco>"#
            )
        };
        assert_pairs("tendon-width", &[(&width("0"), &width("0.01"))]);
    }

    #[test]
    fn a_spatial_path_is_judged_in_sequence_as_mujoco_judges_it() {
        let refused_compiled = [
            // Consecutive pulleys; one pulley between sites.
            (
                r#"<spatial><site site="s"/><site site="t"/><pulley divisor="2"/><pulley divisor="2"/><site site="s"/><site site="t"/></spatial>"#,
                r#"<spatial><site site="s"/><site site="t"/><pulley divisor="2"/><site site="s"/><site site="t"/></spatial>"#,
            ),
            // A pulley last; a pulley first.
            (
                r#"<spatial><site site="s"/><site site="t"/><pulley divisor="2"/></spatial>"#,
                r#"<spatial><pulley divisor="1"/><site site="s"/><site site="t"/></spatial>"#,
            ),
            // A site between pulleys; a site between a site and a pulley.
            (
                r#"<spatial><site site="s"/><pulley divisor="2"/><site site="t"/><pulley divisor="2"/><site site="u"/></spatial>"#,
                r#"<spatial><site site="s"/><site site="t"/><pulley divisor="2"/><site site="t"/><site site="u"/></spatial>"#,
            ),
            // A site first with a pulley next.
            (
                r#"<spatial><site site="s"/><pulley divisor="1"/><site site="s"/><site site="t"/></spatial>"#,
                r#"<spatial><site site="s"/><site site="t"/><site site="s"/></spatial>"#,
            ),
            // A site twice in a row; twice, not in a row.
            (
                r#"<spatial><site site="s"/><site site="s"/></spatial>"#,
                r#"<spatial><site site="s"/><site site="t"/><site site="s"/></spatial>"#,
            ),
            // A geom last; a geom between sites.
            (
                r#"<spatial><site site="s"/><geom geom="g"/></spatial>"#,
                r#"<spatial><site site="s"/><geom geom="g"/><site site="t"/></spatial>"#,
            ),
            // Geoms side by side; a geom first.
            (
                r#"<spatial><site site="s"/><geom geom="g"/><geom geom="g"/><site site="t"/></spatial>"#,
                r#"<spatial><site site="s"/><site site="t"/></spatial>"#,
            ),
            (
                r#"<spatial><geom geom="g"/><site site="t"/></spatial>"#,
                r#"<spatial><site site="u"/><site site="t"/></spatial>"#,
            ),
            // Pulleys alone; a pulley between sites.
            (
                r#"<spatial><pulley divisor="1"/><pulley divisor="1"/></spatial>"#,
                r#"<spatial><site site="u"/><site site="t"/><pulley divisor="1"/><site site="s"/><site site="t"/></spatial>"#,
            ),
            // A wrapping geom with a tendon armature; an armature without one.
            (
                r#"<spatial armature="1"><site site="s"/><geom geom="g"/><site site="t"/></spatial>"#,
                r#"<spatial armature="1"><site site="s"/><site site="t"/></spatial>"#,
            ),
        ];
        pairs("tendon-spatial-path", &refused_compiled);
    }

    #[test]
    fn a_wrapping_geom_must_be_a_sphere_or_cylinder_by_its_own_or_class_type() {
        pairs(
            "tendon-wrap-geom-type",
            &[(
                r#"<spatial><site site="s"/><geom geom="box"/><site site="t"/></spatial>"#,
                r#"<spatial><site site="s"/><geom geom="g"/><site site="t"/></spatial>"#,
            )],
        );
        let class = |ty: &str| {
            format!(
                r#"<mujoco><default><default class="w"><geom type="{ty}" size=".1 .1"/></default></default>
                <worldbody><body name="b"><joint/><geom size=".1"/><site name="s"/></body><site name="t" pos="1 0 0"/>
                <body childclass="w"><geom name="g"/></body></worldbody>
                <tendon><spatial><site site="s"/><geom geom="g"/><site site="t"/></spatial></tendon></mujoco>"#
            )
        };
        assert_eq!(super::super::tests::refused(&class("capsule")), ["tendon-wrap-geom-type"]);
        assert_eq!(super::super::tests::refused(&class("cylinder")), Vec::<&str>::new());
    }
}
