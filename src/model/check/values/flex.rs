//! The checks of a flex's and a flexcomp's own values (MuJoCo 4.0.0's flex
//! compiler): a flex's texture coordinates, a flexcomp's edge constraints beside its
//! elasticity.

use super::{At, Check, Found, found, on};
use crate::model::tree::Node;
use crate::value::Value;

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "flex-texcoord-even",
        on: |k| on::at(k, "deformable/flex"),
        test: |at| {
            let t = at.own_floats("texcoord")?;
            (t.len() % 2 == 1).then_some(())?;
            found("texcoord", "texcoord size must be even")
        },
        fix: "give two texture coordinates per vertex",
    },
    Check {
        name: "flexcomp-young-and-constraints",
        on: |k| on::at(k, "(world)body/flexcomp"),
        test: young_and_constraints,
        fix: "drop the edge equality or the elasticity's young (or use elastic2d bend)",
    },
];

/// A child's own value of `attr`, the first child of tag `tag`.
fn child_value<'m>(node: &'m Node, tag: &str, attr: &str) -> Option<&'m Value> {
    let child = node.children().iter().find(|c| c.kind().tag() == tag)?;
    child.attr(child.kind().attr_index(attr)?)
}

/// `flex constraints and elasticity (young) cannot both be present`: a flexcomp of 2
/// or 3 dimensions (2 when not given), not rigid, whose edges are constrained
/// (`equality` true or strain) and whose elasticity has a positive young's modulus
/// (unless its 2d elasticity is bending only).
fn young_and_constraints(at: &At<'_, '_>) -> Option<Found> {
    let node = at.e.node;
    (at.own_int("dim").unwrap_or(2) > 1).then_some(())?;
    (at.own_str("rigid") != Some("true")).then_some(())?;
    let equality = child_value(node, "edge", "equality").and_then(Value::as_str)?;
    matches!(equality, "true" | "strain").then_some(())?;
    let young = match child_value(node, "elasticity", "young")? {
        Value::Float(x) => *x,
        Value::Int(i) => *i as f64,
        _ => return None,
    };
    (young > 0.0).then_some(())?;
    let elastic2d = child_value(node, "elasticity", "elastic2d").and_then(Value::as_str);
    (elastic2d != Some("bend")).then_some(())?;
    found("young", "flex constraints and elasticity (young) cannot both be present")
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn pairs_of(pairs: &[(String, String)]) -> Vec<(&str, &str)> {
        pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect()
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn flex_texcoords_come_in_pairs() {
        let flex = |t: &str| {
            format!(
                r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><deformable><flex name="f" dim="2" body="b b b" vertex="0 0 0 1 0 0 0 1 0" element="0 1 2" texcoord="{t}"/></deformable></mujoco>"#
            )
        };
        let pairs = [(flex("0 0 1"), flex("0 0 1 0 0 1")), (flex("0"), flex(""))];
        assert_pairs("flex-texcoord-even", &pairs_of(&pairs));
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn a_flexcomps_edge_constraints_exclude_young() {
        let fc = |attrs: &str, edge: &str, elasticity: &str| {
            format!(
                r#"<mujoco><worldbody><flexcomp name="f" type="grid" spacing=".1 .1 .1" {attrs}><edge {edge}/><elasticity {elasticity}/></flexcomp></worldbody></mujoco>"#
            )
        };
        let grid2 = r#"count="3 3 1" dim="2""#;
        let grid3 = r#"count="3 3 3" dim="3""#;
        let pairs = [
            (
                fc(grid2, r#"equality="true""#, r#"young="100""#),
                fc(grid2, r#"equality="false""#, r#"young="100""#),
            ),
            (
                fc(r#"count="3 3 1""#, r#"equality="true""#, r#"young="100""#),
                fc(grid2, r#"equality="true""#, r#"young="0""#),
            ),
            (
                fc(grid3, r#"equality="true""#, r#"young="1e-300""#),
                fc(grid3, r#"equality="true""#, r#"young="-1""#),
            ),
            (
                fc(grid2, r#"equality="strain""#, r#"young="100""#),
                fc(&format!(r#"{grid2} rigid="true""#), r#"equality="true""#, r#"young="100""#),
            ),
            (
                fc(
                    grid2,
                    r#"equality="true""#,
                    r#"young="100" elastic2d="stretch" thickness=".01""#,
                ),
                fc(grid2, r#"equality="true""#, r#"young="100" elastic2d="bend" thickness=".01""#),
            ),
            (
                fc(grid2, r#"equality="true""#, r#"young="100" thickness=".01""#),
                fc(r#"count="3 1 1" dim="1""#, r#"equality="true""#, r#"young="100""#),
            ),
        ];
        assert_pairs("flexcomp-young-and-constraints", &pairs_of(&pairs));
    }
}
