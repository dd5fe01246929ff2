//! The checks of a joint's own values (MuJoCo's `mjCJoint::Compile`).

use crate::model::layout::{JointType, joint_type};

use super::{Check, found, on};

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "joint-springdamper-positive",
        on: on::joint,
        test: |at| {
            let sd = at.floats("springdamper")?;
            let (a, b) = (*sd.first()?, sd.get(1).copied().unwrap_or(0.0));
            // A nan is "defined" but not below zero, as in MuJoCo.
            ((a != 0.0 || b != 0.0) && (a <= 0.0 || b <= 0.0)).then_some(())?;
            found("springdamper", "when defined, springdamper values must be positive in joint")
        },
        fix: "give springdamper a positive time constant and damping ratio, or 0 0",
    },
    Check {
        name: "joint-springyield",
        on: on::joint,
        test: |at| {
            (at.float("springyield")? < 0.0).then_some(())?;
            found("springyield", "springyield cannot be negative in joint")
        },
        fix: "give springyield zero or a positive value",
    },
    Check {
        name: "joint-axis-zero",
        on: on::joint,
        test: |at| {
            // A ball or free joint's axis MuJoCo sets itself.
            let ty = joint_type(at.e.model, at.e.node, at.e.class);
            if matches!(ty, JointType::Ball | JointType::Free) {
                return None;
            }
            let axis = at.floats("axis")?;
            let n: f64 = axis.iter().take(3).map(|x| x * x).sum();
            (axis.len() >= 3 && n < 1e-14).then_some(())?;
            found("axis", "axis too small in joint")
        },
        fix: "give the axis a non-zero direction",
    },
];

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn joint(attrs: &str) -> String {
        format!(
            r#"<mujoco><worldbody><body><joint {attrs}/><geom size=".1"/></body></worldbody></mujoco>"#
        )
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_joints_spring_and_axis_are_judged_as_mujoco_judges_them() {
        let pairs = [
            (joint(r#"springdamper="-1 1""#), joint(r#"springdamper="1 1""#)),
            (joint(r#"springdamper="0 1""#), joint(r#"springdamper="0 0""#)),
            (
                r#"<mujoco><default><joint springdamper="1 -1"/></default><worldbody><body><joint/><geom size=".1"/></body></worldbody></mujoco>"#.into(),
                joint(r#"springdamper="nan 1""#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("joint-springdamper-positive", &pairs);
        let pairs = [
            (joint(r#"springyield="-1e-300""#), joint(r#"springyield="0""#)),
            (joint(r#"springyield="-inf""#), joint(r#"springyield="nan""#)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("joint-springyield", &pairs);
        let pairs = [
            (joint(r#"axis="0 0 0""#), joint(r#"type="ball" axis="0 0 0""#)),
            (joint(r#"type="slide" axis="0 0 1e-7""#), joint(r#"type="slide" axis="0 0 2e-7""#)),
            (
                r#"<mujoco><default><joint axis="0 0 0"/></default><worldbody><body><joint/><geom size=".1"/></body></worldbody></mujoco>"#.into(),
                r#"<mujoco><default><joint axis="0 0 0"/></default><worldbody><body><joint type="ball"/><geom size=".1"/></body></worldbody></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("joint-axis-zero", &pairs);
    }
}
