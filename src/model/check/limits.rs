//! Rule *limits are ranges* ([`ProblemKind::InvalidRange`],
//! [`ProblemKind::RangeWithoutLimited`]): a limited joint, tendon or actuator range
//! must be a range, and without `autolimits` a range needs its `limited`.
//!
//! Which ranges are limited, as MuJoCo 4.0.0 decides it (checked with it): `limited`
//! (its own or its classes') `true`; `auto` or unset with the compiler's
//! `autolimits` on (the default) when the range is given with its low end below its
//! high end (so `range="1 0"` alone is simply not a limit). With `autolimits` off, a
//! range given without `limited` is refused.

use crate::model::Model;
use crate::model::layout::{JointType, effective, joint_type};
use crate::model::settings;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// What a limited range must be.
#[derive(Clone, Copy)]
enum Must {
    /// Low end below high end.
    Increase,
    /// Low end 0 (a ball joint's angle).
    StartAtZero,
}

/// One range attribute MuJoCo checks: what MuJoCo calls the element, the attribute,
/// its `limited`, what it must be, and MuJoCo 4.0.0's message when it is not.
struct Limit {
    element: &'static str,
    range: &'static str,
    limited: &'static str,
    must: Must,
    mujoco: &'static str,
}

const fn limit(
    element: &'static str,
    range: &'static str,
    limited: &'static str,
    must: Must,
    mujoco: &'static str,
) -> Limit {
    Limit { element, range, limited, must, mujoco }
}

const JOINT: [Limit; 1] = [limit(
    "joint",
    "range",
    "limited",
    Must::Increase,
    "range[0] should be smaller than range[1] in joint",
)];
const BALL: [Limit; 1] =
    [limit("joint", "range", "limited", Must::StartAtZero, "range[0] should be 0 in ball joint")];
const JOINT_ACTUATOR_FORCE: Limit = limit(
    "joint",
    "actuatorfrcrange",
    "actuatorfrclimited",
    Must::Increase,
    "actfrcrange[0] should be smaller than actfrcrange[1] in joint",
);
const TENDON: [Limit; 1] =
    [limit("tendon", "range", "limited", Must::Increase, "invalid limits in tendon")];
const ACTUATOR: [Limit; 3] = [
    limit(
        "actuator",
        "ctrlrange",
        "ctrllimited",
        Must::Increase,
        "invalid control range for actuator",
    ),
    limit(
        "actuator",
        "forcerange",
        "forcelimited",
        Must::Increase,
        "invalid force range for actuator",
    ),
    limit("actuator", "actrange", "actlimited", Must::Increase, "invalid actrange for actuator"),
];

/// The rule, with the compiler's `autolimits` of the model as written (its merged
/// settings).
pub(super) struct Limits {
    autolimits: bool,
}

impl Limits {
    /// The rule for `model` as written.
    pub(super) fn new(model: &Model) -> Limits {
        let compiler = ElementKind::ROOT.child("compiler");
        let off = settings::merged(model).ok().is_some_and(|sections| {
            sections.iter().filter(|n| Some(n.kind()) == compiler).any(|c| {
                let kind = c.kind();
                let v = kind.attr_index("autolimits").and_then(|i| c.attr(i));
                v.and_then(Value::as_str) == Some("false")
            })
        });
        Limits { autolimits: !off }
    }

    /// The problem with `limit` on the element of `e`, if any.
    fn judge(&self, e: &Event<'_>, limit: &Limit) -> Option<ProblemKind> {
        let value = |attr| effective(e.model, e.node, e.class, attr);
        let range = value(limit.range).and_then(Value::as_floats).filter(|r| r.len() >= 2);
        let limited = value(limit.limited).and_then(Value::as_str);
        let on = match (limited, range) {
            (Some("true"), Some(_)) => true,
            (Some("false"), _) | (_, None) => false,
            // `auto` or unset, with a range given.
            (_, Some(r)) if self.autolimits => r[0] < r[1],
            (_, Some(_)) => {
                return Some(ProblemKind::RangeWithoutLimited {
                    element: limit.element,
                    attribute: limit.range,
                    limited: limit.limited,
                });
            }
        };
        let r = range?;
        let wrong = match limit.must {
            Must::Increase => r[0] >= r[1],
            Must::StartAtZero => r[0] != 0.0,
        };
        (on && wrong).then_some(ProblemKind::InvalidRange {
            attribute: limit.range,
            range: [r[0], r[1]],
            mujoco: limit.mujoco,
        })
    }
}

impl<'m> Rule<'m> for Limits {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let kind = e.node.kind();
        let limits: &[Limit] = match kind.role() {
            Some(Role::Joint) => {
                if let Some(p) = self.judge(e, &JOINT_ACTUATOR_FORCE) {
                    out.push(p);
                }
                match joint_type(e.model, e.node, e.class) {
                    JointType::Ball => &BALL,
                    JointType::Hinge | JointType::Slide => &JOINT,
                    _ => &[],
                }
            }
            Some(Role::Tendon) => &TENDON,
            Some(r) if r.is_actuator() => &ACTUATOR,
            _ => &[],
        };
        out.extend(limits.iter().filter_map(|l| self.judge(e, l)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::check::tests::kinds_of;

    fn problems(compiler: &str, body: &str, sections: &str) -> Vec<ProblemKind> {
        let text = format!(
            r#"<mujoco>{compiler}<worldbody><body name="b"><joint name="j" {body}/><geom size=".1"/></body></worldbody>{sections}</mujoco>"#
        );
        let m = Model::from_xml_str(&text).unwrap();
        let rule = Limits::new(&m);
        kinds_of(&m, rule)
    }

    /// Each case's verdict is MuJoCo 4.0.0's (refused: a problem; compiled: none).
    #[test]
    fn limited_ranges_are_judged_as_mujoco_judges_them() {
        let off = r#"<compiler autolimits="false"/>"#;
        let refused = [
            ("", r#"limited="true" range="1 1""#, ""),
            ("", r#"type="slide" limited="true" range="0 0""#, ""),
            ("", r#"type="ball" range="-1 1""#, ""),
            ("", r#"type="ball" limited="true" range="1 2""#, ""),
            ("", r#"actuatorfrclimited="true" actuatorfrcrange="1 1""#, ""),
            (off, r#"limited="true" range="1 0""#, ""),
            (off, r#"range="1 0""#, ""),
            (
                "",
                "",
                r#"<actuator><motor joint="j" ctrllimited="true" ctrlrange="1 1"/></actuator>"#,
            ),
            (
                "",
                "",
                r#"<actuator><motor joint="j" forcelimited="true" forcerange="1 1"/></actuator>"#,
            ),
            (
                "",
                "",
                r#"<actuator><general joint="j" dyntype="integrator" actlimited="true" actrange="1 1"/></actuator>"#,
            ),
            (
                "",
                "",
                r#"<tendon><fixed limited="true" range="1 0"><joint joint="j" coef="1"/></fixed></tendon>"#,
            ),
            (off, "", r#"<actuator><motor joint="j" ctrlrange="1 2"/></actuator>"#),
            (off, "", r#"<tendon><fixed range="0 1"><joint joint="j" coef="1"/></fixed></tendon>"#),
        ];
        for (compiler, body, sections) in refused {
            assert_eq!(problems(compiler, body, sections).len(), 1, "{compiler} {body} {sections}");
        }
        let compiled = [
            ("", r#"range="1 0""#, ""),
            ("", r#"range="1 1""#, ""),
            ("", r#"limited="false" range="1 0""#, ""),
            ("", r#"type="ball" range="0 0""#, ""),
            ("", r#"type="ball" limited="true" range="0 -1""#, ""),
            ("", r#"actuatorfrcrange="1 0""#, ""),
            ("", "", r#"<actuator><motor joint="j" ctrlrange="1 0"/></actuator>"#),
            (
                "",
                "",
                r#"<actuator><motor joint="j" ctrllimited="false" ctrlrange="1 0"/></actuator>"#,
            ),
            ("", "", r#"<tendon><fixed range="1 0"><joint joint="j" coef="1"/></fixed></tendon>"#),
        ];
        for (compiler, body, sections) in compiled {
            assert_eq!(problems(compiler, body, sections), [], "{compiler} {body} {sections}");
        }
    }

    #[test]
    fn a_limit_given_by_a_class_counts_and_the_default_itself_is_not_judged() {
        let text = r#"<mujoco><compiler autolimits="false"/><default><joint limited="true" range="1 0"/></default>
            <worldbody><body><joint/><geom size=".1"/></body></worldbody></mujoco>"#;
        let m = Model::from_xml_str(text).unwrap();
        let found = kinds_of(&m, Limits::new(&m));
        assert!(
            matches!(&found[..], [ProblemKind::InvalidRange { attribute: "range", .. }]),
            "{found:?}"
        );
    }
}
