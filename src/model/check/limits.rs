//! Rule *limits are ranges* ([`ProblemKind::InvalidRange`],
//! [`ProblemKind::RangeWithoutLimited`]): a limited joint, tendon or actuator range
//! must be a range, and without `autolimits` a range needs its `limited`.
//!
//! Which ranges are limited, as MuJoCo 4.0.0 decides it (checked with it): `limited`
//! (its own or its classes') `true`; `auto` or unset with the compiler's
//! `autolimits` on (the default) when the range is given with its low end below its
//! high end (so `range="1 0"` alone is simply not a limit). With `autolimits` off, a
//! range given without `limited` is refused. A joint's or tendon's limit without a
//! range is the range `0 0`. A sensor of a joint's or tendon's limit needs the joint or tendon limited.

use crate::model::Model;
use crate::model::layout::{JointType, effective, joint_type};
use crate::model::settings;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::ProblemKind;
use super::target::{Target, named};
use super::values::on;
use super::walk::{Event, Rule};

/// What a limited range must be.
#[derive(Clone, Copy)]
enum Must {
    /// Low end below high end.
    Increase,
    /// Low end 0 (a ball joint's angle).
    StartAtZero,
    /// Low end below high end, 0 between them (a tendon's actuator force).
    IncreaseAroundZero,
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
const TENDON: [Limit; 2] = [
    limit("tendon", "range", "limited", Must::Increase, "invalid limits in tendon"),
    limit(
        "tendon",
        "actuatorfrcrange",
        "actuatorfrclimited",
        Must::IncreaseAroundZero,
        "invalid actuatorfrcrange in tendon",
    ),
];
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
        let off = settings::merged(model).ok().is_some_and(|sections| {
            sections.iter().filter(|n| n.kind() == ElementKind::COMPILER).any(|c| {
                let kind = c.kind();
                let v = kind.attr_index("autolimits").and_then(|i| c.attr(i));
                v.and_then(Value::as_str) == Some("false")
            })
        });
        Limits { autolimits: !off }
    }

    /// Whether `limited` (the element's own or its classes') makes the range `range`
    /// (its numbers, if given) a limit; `Err` when the compiler's `autolimits` is off
    /// and the range is given without `limited` (refused).
    fn is_on(&self, limited: Option<&str>, range: Option<&[f64]>) -> Result<bool, ()> {
        match (limited, range) {
            (Some("true"), _) => Ok(true),
            (Some("false"), _) | (_, None) => Ok(false),
            // `auto` or unset, with a range given.
            (_, Some(r)) if self.autolimits => Ok(r[0] < r[1]),
            (_, Some(_)) => Err(()),
        }
    }

    /// Whether the element `t` (a joint or tendon, in its model with its class) is
    /// limited by `limit`; `None` when that is refused in itself.
    fn limited(&self, t: &Target<'_>, limit: &Limit) -> Option<bool> {
        let range = t.get(limit.range).and_then(Value::as_floats).filter(|r| r.len() >= 2);
        self.is_on(t.get(limit.limited).and_then(Value::as_str), range).ok()
    }

    /// The problem with `limit` on the element of `e`, if any.
    fn judge(&self, e: &Event<'_>, limit: &Limit) -> Option<ProblemKind> {
        let value = |attr| effective(e.model, e.node, e.class, attr);
        let range = value(limit.range).and_then(Value::as_floats).filter(|r| r.len() >= 2);
        let limited = value(limit.limited).and_then(Value::as_str);
        let Ok(on) = self.is_on(limited, range) else {
            return Some(ProblemKind::RangeWithoutLimited {
                element: limit.element,
                attribute: limit.range,
                limited: limit.limited,
            });
        };
        // A limit without a range is the range `0 0`; but an actuator's range may come
        // from a class's default of another actuator tag (MuJoCo's actuator defaults
        // are one for all tags), which is not read here: not judged.
        if range.is_none() && e.node.kind().role().is_some_and(Role::is_actuator) {
            return None;
        }
        let r = range.map_or([0.0, 0.0], |r| [r[0], r[1]]);
        let wrong = match limit.must {
            Must::Increase => r[0] >= r[1],
            Must::StartAtZero => r[0] != 0.0,
            Must::IncreaseAroundZero => r[0] >= r[1] || r[0] > 0.0 || r[1] < 0.0,
        };
        (on && wrong).then_some(ProblemKind::InvalidRange {
            attribute: limit.range,
            range: r,
            mujoco: limit.mujoco,
        })
    }

    /// A sensor of a joint's or tendon's limit whose joint or tendon is not limited
    /// (a free joint never is).
    fn sensor(&self, e: &Event<'_>) -> Option<ProblemKind> {
        let is = |of: &str| {
            ["pos", "vel", "frc"]
                .iter()
                .any(|q| on::at(e.node.kind(), &format!("sensor/{of}limit{q}")))
        };
        let (attr, mujoco) = if is("joint") {
            ("joint", "joint must be limited in sensor")
        } else if is("tendon") {
            ("tendon", "tendon must be limited in sensor")
        } else {
            return None;
        };
        let t = named(e.model, e.node, e.class, attr)?;
        let limited = match t.node.kind().role() {
            Some(Role::Freejoint) => false,
            Some(Role::Joint) if joint_type(t.model, t.node, t.class) == JointType::Free => false,
            Some(Role::Joint) => self.limited(&t, &JOINT[0])?,
            Some(Role::Tendon) => self.limited(&t, &TENDON[0])?,
            _ => return None,
        };
        (!limited).then(|| ProblemKind::Refused {
            rule: "sensor-limited",
            attribute: Some(attr),
            mujoco: mujoco.into(),
            fix: "give the joint or tendon a range that is a limit",
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
            _ => {
                out.extend(self.sensor(e));
                &[]
            }
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

    fn tendon(attrs: &str) -> String {
        format!(r#"<tendon><fixed {attrs}><joint joint="j" coef="1"/></fixed></tendon>"#)
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
            // A limit without a range is `0 0`.
            ("", r#"limited="true""#, ""),
            ("", r#"actuatorfrclimited="true""#, ""),
            (
                "",
                "",
                r#"<tendon><fixed limited="true"><joint joint="j" coef="1"/></fixed></tendon>"#,
            ),
            // A tendon's actuator force range must hold 0.
            ("", "", &tendon(r#"actuatorfrcrange="1 2""#)),
            ("", "", &tendon(r#"actuatorfrclimited="true" actuatorfrcrange="-2 -1""#)),
            ("", "", &tendon(r#"actuatorfrclimited="true" actuatorfrcrange="1 0""#)),
            ("", "", &tendon(r#"actuatorfrclimited="true""#)),
            (off, "", &tendon(r#"actuatorfrcrange="-1 2""#)),
        ];
        for (compiler, body, sections) in &refused {
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
            ("", r#"type="ball" limited="true""#, ""),
            ("", r#"actuatorfrclimited="true" actuatorfrcrange="1 2""#, ""),
            ("", "", &tendon(r#"actuatorfrcrange="1 0""#)),
            ("", "", &tendon(r#"actuatorfrcrange="-1 -2""#)),
            ("", "", &tendon(r#"actuatorfrclimited="true" actuatorfrcrange="0 1""#)),
        ];
        for (compiler, body, sections) in &compiled {
            assert_eq!(problems(compiler, body, sections), [], "{compiler} {body} {sections}");
        }
    }

    /// MuJoCo 4.0.0 compiles it: its actuator defaults are one for every actuator tag,
    /// so a `<motor>` is limited by its class's `<general>` range.
    #[test]
    fn an_actuator_limit_without_its_own_range_is_not_judged() {
        let text = r#"<mujoco><default><general ctrlrange="-1 1"/></default><worldbody><body>
            <joint name="j"/><geom size=".1"/></body></worldbody>
            <actuator><motor joint="j" ctrllimited="true"/></actuator></mujoco>"#;
        let m = Model::from_xml_str(text).unwrap();
        assert_eq!(kinds_of(&m, Limits::new(&m)), []);
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

    /// Each case's verdict is MuJoCo 4.0.0's: a sensor of a joint's or tendon's limit
    /// needs it limited (a free joint never is).
    #[test]
    fn a_limit_sensor_needs_its_joint_or_tendon_limited() {
        let sensor = |compiler: &str, joint: &str, tendon: &str, sensor: &str| {
            let text = format!(
                r#"<mujoco>{compiler}<worldbody><body name="b"><joint name="j" {joint}/><geom size=".1"/></body>
                <body name="f"><freejoint name="free"/><geom size=".1"/></body>
                <body name="c"><joint name="k"/><geom size=".1"/></body></worldbody>
                <tendon><fixed name="t" {tendon}><joint joint="k" coef="1"/></fixed></tendon>
                <sensor>{sensor}</sensor></mujoco>"#
            );
            let m = Model::from_xml_str(&text).unwrap();
            kinds_of(&m, Limits::new(&m))
                .into_iter()
                .filter(|k| matches!(k, ProblemKind::Refused { rule: "sensor-limited", .. }))
                .count()
        };
        let off = r#"<compiler autolimits="false"/>"#;
        let pos = r#"<jointlimitpos joint="j"/>"#;
        let refused = [
            ("", "", "", pos),
            ("", r#"range="1 0""#, "", pos),
            ("", r#"range="0 1" limited="false""#, "", pos),
            ("", r#"type="ball" range="0 -1""#, "", pos),
            (off, "", "", r#"<jointlimitfrc joint="j"/>"#),
            ("", "", "", r#"<jointlimitvel joint="free"/>"#),
            ("", "", r#"range="1 0""#, r#"<tendonlimitfrc tendon="t"/>"#),
            ("", "", r#"range="0 1" limited="false""#, r#"<tendonlimitpos tendon="t"/>"#),
        ];
        for (c, j, t, s) in refused {
            assert_eq!(sensor(c, j, t, s), 1, "{c} {j} {t} {s}");
        }
        let compiled = [
            ("", r#"range="0 1""#, "", pos),
            ("", r#"type="ball" range="0 1""#, "", pos),
            ("", r#"type="ball" range="0 -1" limited="true""#, "", pos),
            (off, r#"range="0 1" limited="true""#, "", pos),
            ("", "", r#"range="0 1""#, r#"<tendonlimitvel tendon="t"/>"#),
        ];
        for (c, j, t, s) in compiled {
            assert_eq!(sensor(c, j, t, s), 0, "{c} {j} {t} {s}");
        }
        let class = r#"<mujoco><default><joint range="0 1"/></default><worldbody><body><joint name="j"/>
            <geom size=".1"/></body></worldbody><sensor><jointlimitvel joint="j"/></sensor></mujoco>"#;
        let m = Model::from_xml_str(class).unwrap();
        assert_eq!(kinds_of(&m, Limits::new(&m)), []);
        // A tendon's class is the class's `<tendon>`.
        let tendon = |attrs: &str| {
            format!(
                r#"<mujoco><default><tendon {attrs}/></default><worldbody><body><joint name="j"/>
                <geom size=".1"/></body></worldbody><tendon><fixed name="t"><joint joint="j" coef="1"/></fixed>
                </tendon><sensor><tendonlimitpos tendon="t"/></sensor></mujoco>"#
            )
        };
        let m = Model::from_xml_str(&tendon(r#"range="0 1""#)).unwrap();
        assert_eq!(kinds_of(&m, Limits::new(&m)), []);
        let m = Model::from_xml_str(&tendon(r#"limited="true" range="1 0""#)).unwrap();
        assert!(matches!(&kinds_of(&m, Limits::new(&m))[..], [ProblemKind::InvalidRange { .. }]));
    }
}
