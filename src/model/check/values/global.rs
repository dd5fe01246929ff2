//! The checks of the global settings MuJoCo's XML reader refuses (its `Compiler`,
//! `Option`, `Size`, `Statistic` and `Visual` readers): each judges the value written,
//! the sections merged across attachments (see [`super::Values`]).

use super::{At, Check, Found, NUSER, found, on};

/// `<size>`'s counts MuJoCo takes from -1 up ("nconmax must be >= -1"), besides the
/// user-data counts ([`NUSER`]).
const SIZE_COUNTS: [&str; 3] = ["nconmax", "nstack", "njmax"];

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "compiler-global-coordinates",
        on: |k| on::at(k, "compiler"),
        test: |at| {
            (at.str("coordinate")? == "global").then_some(())?;
            found(
                "coordinate",
                "global coordinates no longer supported. To convert existing models, load and \
                 save them in MuJoCo 2.3.3 or older",
            )
        },
        fix: "give the model's poses in local coordinates (coordinate=\"local\")",
    },
    Check {
        name: "option-actuatorgroupdisable-range",
        on: |k| on::at(k, "option"),
        test: actuator_groups,
        fix: "disable actuator groups 0 to 30 only",
    },
    Check {
        name: "size-count-range",
        on: |k| on::at(k, "size"),
        test: |at| {
            let attr =
                SIZE_COUNTS.into_iter().chain(NUSER).find(|a| at.int(a).is_some_and(|n| n < -1))?;
            found(attr, format!("{attr} must be >= -1"))
        },
        fix: "give the count -1 (MuJoCo's choice) or more",
    },
    Check {
        name: "statistic-extent-positive",
        on: |k| on::at(k, "statistic"),
        test: |at| {
            (at.float("extent")? <= 0.0).then_some(())?;
            found("extent", "extent must be strictly positive")
        },
        fix: "give a positive extent, or none (MuJoCo computes it)",
    },
    Check {
        name: "visual-realtime-positive",
        on: |k| on::at(k, "visual/global"),
        test: |at| {
            (at.float("realtime")? <= 0.0).then_some(())?;
            found("realtime", "realtime must be greater than 0")
        },
        fix: "give a positive realtime (1 is real time)",
    },
    Check {
        name: "visual-znear-positive",
        on: |k| on::at(k, "visual/map"),
        test: |at| {
            (at.float("znear")? <= 0.0).then_some(())?;
            found("znear", "znear must be strictly positive")
        },
        fix: "give a positive znear",
    },
];

/// `actuatorgroupdisable`: each group from 0 to 30, judged in order (the first out of
/// range is refused).
fn actuator_groups(at: &At<'_, '_>) -> Option<Found> {
    let groups = at.floats("actuatorgroupdisable")?;
    let bad = groups.into_iter().find(|g| *g < 0.0 || *g > 30.0)?;
    found(
        "actuatorgroupdisable",
        if bad < 0.0 {
            "disabled actuator group value must be non-negative"
        } else {
            "disabled actuator group value cannot exceed 30"
        },
    )
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn model(settings: &str) -> String {
        format!("<mujoco>{settings}<worldbody/></mujoco>")
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn global_settings_are_judged_as_mujoco_reads_them() {
        let cases: &[(&str, &[(&str, &str)])] = &[
            (
                "compiler-global-coordinates",
                &[(r#"<compiler coordinate="global"/>"#, r#"<compiler coordinate="local"/>"#)],
            ),
            (
                "option-actuatorgroupdisable-range",
                &[
                    (
                        r#"<option actuatorgroupdisable="-1"/>"#,
                        r#"<option actuatorgroupdisable="0"/>"#,
                    ),
                    (
                        r#"<option actuatorgroupdisable="31"/>"#,
                        r#"<option actuatorgroupdisable="30"/>"#,
                    ),
                    (
                        r#"<option actuatorgroupdisable="2 31 -1"/>"#,
                        r#"<option actuatorgroupdisable="2 30 1"/>"#,
                    ),
                ],
            ),
            (
                "size-count-range",
                &[
                    (r#"<size nconmax="-2"/>"#, r#"<size nconmax="-1"/>"#),
                    (r#"<size nstack="-2"/>"#, r#"<size nstack="-1"/>"#),
                    (r#"<size njmax="-2"/>"#, r#"<size njmax="0"/>"#),
                    (r#"<size nuser_body="-2"/>"#, r#"<size nuser_body="-1"/>"#),
                    (r#"<size nuser_jnt="-2"/>"#, r#"<size nuser_jnt="2"/>"#),
                    (r#"<size nuser_geom="-2"/>"#, r#"<size nuser_geom="-1"/>"#),
                    (r#"<size nuser_site="-2"/>"#, r#"<size nuser_site="-1"/>"#),
                    (r#"<size nuser_cam="-2"/>"#, r#"<size nuser_cam="-1"/>"#),
                    (r#"<size nuser_tendon="-2"/>"#, r#"<size nuser_tendon="-1"/>"#),
                    (r#"<size nuser_actuator="-2"/>"#, r#"<size nuser_actuator="-1"/>"#),
                    (r#"<size nuser_sensor="-2"/>"#, r#"<size nuser_sensor="-1"/>"#),
                    // nkey is not range-checked by MuJoCo's reader.
                    (r#"<size nconmax="-2" nkey="-2"/>"#, r#"<size nkey="-2"/>"#),
                ],
            ),
            (
                "statistic-extent-positive",
                &[
                    (r#"<statistic extent="0"/>"#, r#"<statistic extent="1"/>"#),
                    (r#"<statistic extent="-inf"/>"#, r#"<statistic extent="nan"/>"#),
                ],
            ),
            (
                "visual-realtime-positive",
                &[
                    (
                        r#"<visual><global realtime="0"/></visual>"#,
                        r#"<visual><global realtime="1"/></visual>"#,
                    ),
                    (
                        r#"<visual><global realtime="-1"/></visual>"#,
                        r#"<visual><global realtime="nan"/></visual>"#,
                    ),
                ],
            ),
            (
                "visual-znear-positive",
                &[
                    (
                        r#"<visual><map znear="0"/></visual>"#,
                        r#"<visual><map znear="0.01"/></visual>"#,
                    ),
                    (
                        r#"<visual><map znear="-1"/></visual>"#,
                        r#"<visual><map znear="nan"/></visual>"#,
                    ),
                ],
            ),
        ];
        for (rule, pairs) in cases.iter() {
            let pairs: Vec<(String, String)> =
                pairs.iter().map(|(a, b)| (model(a), model(b))).collect();
            let pairs: Vec<(&str, &str)> =
                pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
            assert_pairs(rule, &pairs);
        }
    }

    /// The value judged is the one written, the sections merged across attachments
    /// (the least `znear`, the greatest `nconmax`): what MuJoCo 4.0.0 makes of the
    /// written models (`<map znear="0"/>` refused, `<size nconmax="5"/>` compiled).
    #[test]
    fn a_setting_is_judged_as_written_once_merged_across_attachments() {
        use crate::model::Model;
        use crate::model::check::ProblemKind;
        let composed = |outer: &str, part: &str| {
            let mut m = Model::from_xml_str(&model(outer)).unwrap();
            let child = Model::from_xml_str(&model(part)).unwrap().with_name("part");
            m.attach_mut(&m.worldbody(), &child).unwrap();
            m
        };
        let rules = |m: &Model| -> Vec<(String, &'static str)> {
            m.check()
                .into_iter()
                .filter_map(|p| match p.kind {
                    ProblemKind::Refused { rule, .. } => Some((p.path, rule)),
                    _ => None,
                })
                .collect()
        };
        let m = composed(
            r#"<visual><map znear="1"/></visual>"#,
            r#"<visual><map znear="0"/></visual>"#,
        );
        assert!(m.to_xml_string().unwrap().contains(r#"znear="0""#));
        assert_eq!(rules(&m), [("visual".to_string(), "visual-znear-positive")]);
        // A section only the attachment gives.
        let m = composed("", r#"<visual><map znear="0"/></visual>"#);
        assert!(m.to_xml_string().unwrap().contains(r#"znear="0""#));
        assert_eq!(rules(&m), [("visual".to_string(), "visual-znear-positive")]);
        let m = composed(r#"<size nconmax="5"/>"#, r#"<size nconmax="-2"/>"#);
        assert!(m.to_xml_string().unwrap().contains(r#"nconmax="5""#));
        assert_eq!(rules(&m), []);
    }
}
