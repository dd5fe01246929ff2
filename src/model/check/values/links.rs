//! The checks of the elements that tie two others together: a contact `<pair>`'s
//! own values (MuJoCo's `mjCPair::Compile`) and an equality's two objects
//! (`mjCEquality::ResolveReferences`).

use crate::model::check::target::{named, resolve, same};
use crate::model::layout::{JointType, effective, joint_type};
use crate::model::tree::Node;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::{At, Check, Found, found, found_element, on};

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "pair-condim",
        on: |k| on::at(k, "contact/pair"),
        test: |at| {
            let c = at.int("condim")?;
            (![1, 3, 4, 6].contains(&c)).then_some(())?;
            found("condim", "invalid condim in contact pair")
        },
        fix: "use condim 1, 3, 4 or 6",
    },
    Check {
        name: "equality-repeated",
        on: equality,
        test: repeated,
        fix: "name two different elements (an equality with one body ties it to the world)",
    },
    Check {
        name: "equality-joint-type",
        on: |k| on::at(k, "equality/joint"),
        test: |at| {
            let hinge_or_slide = |attr| {
                named(at.e.model, at.e.node, at.e.class, attr).is_none_or(|j| {
                    matches!(
                        joint_type(j.model, j.node, j.class),
                        JointType::Hinge | JointType::Slide
                    )
                })
            };
            (!hinge_or_slide("joint1") || !hinge_or_slide("joint2")).then_some(())?;
            found_element("only HINGE and SLIDE joint allowed in constraint")
        },
        fix: "tie hinge or slide joints",
    },
];

fn equality(k: ElementKind) -> bool {
    on::in_section(k, "equality")
}

/// The pairs of attributes naming an equality's two objects, by the kind MuJoCo
/// reads them as: a site pair before a body pair (a weld or connect names one).
const OBJECTS: [(&str, &str); 4] =
    [("site1", "site2"), ("body1", "body2"), ("joint1", "joint2"), ("tendon1", "tendon2")];

/// An equality naming one element twice, or a body equality naming only the world
/// (its second body is the world).
fn repeated(at: &At<'_, '_>) -> Option<Found> {
    let (model, node) = (at.e.model, at.e.node);
    let value = |attr: &str| {
        let i = node.kind().attr_index(attr)?;
        Some((i, effective(model, node, at.e.class, attr)?))
    };
    let (one, two) = OBJECTS.iter().find(|(a, _)| value(a).is_some())?;
    let (i, first) = value(one)?;
    let twice = match value(two) {
        Some((j, second)) => same((model, node, i, first), (model, node, j, second)),
        None => *one == "body1" && is_world(at, node, i, first),
    };
    twice.then_some(())?;
    let name = first.as_str().map(str::to_owned).or_else(|| {
        resolve(model, node, i, first).and_then(|t| t.node.identifier().map(str::to_owned))
    });
    let label = at.name();
    found_element(format!(
        "element '{}' is repeated in equality constraint '{label}'",
        name.unwrap_or_default()
    ))
}

/// Whether a body reference names the world.
fn is_world(at: &At<'_, '_>, node: &Node, i: usize, v: &Value) -> bool {
    v.as_str() == Some("world")
        || resolve(at.e.model, node, i, v).is_some_and(|t| t.node.kind().is(Role::Worldbody))
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn with(sections: &str) -> String {
        format!(
            r#"<mujoco><worldbody><body name="b"><joint name="j"/><joint name="k" type="slide"/><geom name="g" size=".1"/>
            <site name="s"/></body><body name="b2"><joint name="ba" type="ball"/><geom name="g2" size=".1"/></body>
            </worldbody><tendon><fixed name="t1"><joint joint="j" coef="1"/></fixed><fixed name="t2"><joint joint="k" coef="1"/></fixed></tendon>
            {sections}</mujoco>"#
        )
    }

    fn pairs(rule: &str, pairs: &[(&str, &str)]) {
        let texts: Vec<(String, String)> = pairs.iter().map(|(a, b)| (with(a), with(b))).collect();
        let refs: Vec<(&str, &str)> = texts.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs(rule, &refs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn pairs_and_equalities_are_judged_as_mujoco_judges_them() {
        pairs(
            "pair-condim",
            &[(
                r#"<contact><pair geom1="g" geom2="g2" condim="2"/></contact>"#,
                r#"<contact><pair geom1="g" geom2="g2" condim="6"/></contact>"#,
            )],
        );
        let eq = |s: &str| format!("<equality>{s}</equality>");
        let repeated = [
            (r#"<joint joint1="j" joint2="j"/>"#, r#"<joint joint1="j" joint2="k"/>"#),
            (r#"<joint joint1="j" joint2="j" active="false"/>"#, r#"<joint joint1="j"/>"#),
            (r#"<tendon tendon1="t1" tendon2="t1"/>"#, r#"<tendon tendon1="t1" tendon2="t2"/>"#),
            (r#"<weld body1="b" body2="b"/>"#, r#"<weld body1="b"/>"#),
            (
                r#"<connect body1="world" anchor="0 0 0"/>"#,
                r#"<connect body1="b" body2="world" anchor="0 0 0"/>"#,
            ),
            (r#"<weld site1="s" site2="s"/>"#, r#"<weld body1="b2" body2="b"/>"#),
        ];
        for (bad, good) in repeated {
            pairs("equality-repeated", &[(&eq(bad), &eq(good))]);
        }
        let joints = [
            (r#"<joint joint1="j" joint2="ba"/>"#, r#"<joint joint1="j" joint2="k"/>"#),
            (r#"<joint joint1="ba"/>"#, r#"<joint joint1="k"/>"#),
        ];
        for (bad, good) in joints {
            pairs("equality-joint-type", &[(&eq(bad), &eq(good))]);
        }
    }
}
