//! The checks of a sensor's own values and of the objects it names (MuJoCo's
//! `mjCSensor::Compile`; the `data` and `num` of contact and rangefinder sensors its
//! XML reader judges).

use crate::model::check::target::{Ref, Target, named, same};
use crate::model::layout::{JointType, effective, joint_type};
use crate::schema::ElementKind;
use crate::value::Value;

use super::{At, Check, Found, found, found_element, on};

fn sensor(k: ElementKind) -> bool {
    on::in_section(k, "sensor")
}

/// Samples a sensor's history holds at most (2^24).
const MAX_SAMPLES: i64 = 1 << 24;

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "sensor-noise-negative",
        on: sensor,
        test: |at| {
            (at.float("noise")? < 0.0).then_some(())?;
            found("noise", "negative noise in sensor")
        },
        fix: "give noise 0 or more",
    },
    Check {
        name: "sensor-cutoff-negative",
        on: sensor,
        test: |at| {
            (at.float("cutoff")? < 0.0).then_some(())?;
            found("cutoff", "negative cutoff in sensor")
        },
        fix: "give cutoff 0 or more (0: none)",
    },
    Check {
        name: "sensor-interval",
        on: sensor,
        test: interval,
        fix: "give interval a period of 0 or more and a phase in (-period, 0]",
    },
    Check {
        name: "sensor-nsample-large",
        on: sensor,
        test: |at| {
            let n = at.int("nsample")?;
            (n > MAX_SAMPLES).then_some(())?;
            found("nsample", format!("at most 2^24 samples in sensor history buffer, got {n}"))
        },
        fix: "keep nsample at most 16777216",
    },
    Check {
        name: "sensor-delay-without-history",
        on: sensor,
        test: |at| {
            (at.float("delay")? > 0.0 && at.int("nsample").unwrap_or(0) <= 0).then_some(())?;
            found("delay", "setting delay > 0 without a history buffer")
        },
        fix: "give nsample a positive number of samples, or no delay",
    },
    Check {
        name: "sensor-cutoff-axis-or-quaternion",
        on: sensor,
        test: |at| {
            (at.float("cutoff")? > 0.0 && axis_or_quaternion(at)).then_some(())?;
            found("cutoff", "cutoff applied to axis or quaternion datatype in sensor")
        },
        fix: "remove cutoff: a direction or orientation cannot be clamped",
    },
    Check {
        name: "sensor-user-dim",
        on: |k| on::at(k, "sensor/user"),
        test: user_dim,
        fix: "give dim 3 for an axis, 4 for a quaternion, 0 or more otherwise",
    },
    Check {
        name: "sensor-joint-type",
        on: sensor,
        test: joint_kind,
        fix: "name a joint of the type the sensor reads",
    },
    Check {
        name: "sensor-data",
        on: |k| on::at(k, "sensor/contact") || on::at(k, "sensor/rangefinder"),
        test: data_order,
        fix: "list known data keywords, each once, in the order MuJoCo gives",
    },
    Check {
        name: "sensor-contact-num",
        on: |k| on::at(k, "sensor/contact"),
        test: |at| {
            (at.int("num")? <= 0).then_some(())?;
            found("num", "'num' must be positive in sensor")
        },
        fix: "give num 1 or more",
    },
    Check {
        name: "sensor-insidesite-camera-enclosed",
        on: |k| on::at(k, "sensor/insidesite"),
        test: |at| {
            (at.str("objtype")? == "camera" && at.str("enclosed")? == "true").then_some(())?;
            found("enclosed", "camera is not supported in enclosed insidesite sensor")
        },
        fix: "use a body, geom or site in an enclosed insidesite sensor",
    },
    Check {
        name: "sensor-distance-objects",
        on: geom_distance,
        test: distance_objects,
        fix: "name two different objects, neither a height field",
    },
    Check {
        name: "sensor-camera-resolution",
        on: |k| on::at(k, "sensor/rangefinder") || on::at(k, "sensor/camprojection"),
        test: |at| {
            let camera = named(at.e.model, at.e.node, at.e.class, "camera")?;
            let r = camera.get("resolution").map(numbers).unwrap_or_else(|| vec![1.0, 1.0]);
            r.iter().take(2).any(|x| *x <= 0.0).then_some(())?;
            let message = if on::at(at.kind(), "sensor/rangefinder") {
                "rangefinder camera sensor requires positive camera resolution"
            } else {
                "camera projection sensor requires camera resolution"
            };
            found("camera", message)
        },
        fix: "give the camera a positive resolution",
    },
];

/// A value's numbers (an int or float array, or one number).
fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Floats(v) => v.to_vec(),
        Value::Ints(v) => v.iter().map(|i| *i as f64).collect(),
        Value::Float(x) => vec![*x],
        Value::Int(i) => vec![*i as f64],
        _ => Vec::new(),
    }
}

/// `interval`: its period (first number) and phase (second), each 0 when not given.
fn interval(at: &At<'_, '_>) -> Option<Found> {
    let v = at.floats("interval")?;
    let (period, phase) = (v.first().copied().unwrap_or(0.0), v.get(1).copied().unwrap_or(0.0));
    let message = if period < 0.0 {
        "negative interval in sensor"
    } else if phase > 0.0 {
        "positive phase in sensor"
    } else if period > 0.0 && phase <= -period {
        "phase must be greater than -period in sensor"
    } else {
        return None;
    };
    found("interval", message)
}

/// Whether the sensor's data is an axis or a quaternion (a `<user>` sensor's by its
/// `datatype`; a normal's axis is exempt).
fn axis_or_quaternion(at: &At<'_, '_>) -> bool {
    let k = at.kind();
    if on::at(k, "sensor/user") {
        return matches!(at.str("datatype"), Some("axis" | "quaternion"));
    }
    ["framequat", "ballquat", "framexaxis", "frameyaxis", "framezaxis"]
        .iter()
        .any(|t| on::at(k, &format!("sensor/{t}")))
}

/// A `<user>` sensor's `dim`: not negative, 3 for an axis, 4 for a quaternion.
fn user_dim(at: &At<'_, '_>) -> Option<Found> {
    let dim = at.int("dim")?;
    let message = match at.str("datatype") {
        _ if dim < 0 => "sensor dim must be non-negative in sensor",
        Some("axis") if dim != 3 => "datatype AXIS requires dim=3 in sensor",
        Some("quaternion") if dim != 4 => "datatype QUATERNION requires dim=4 in sensor",
        _ => return None,
    };
    found("dim", message)
}

/// A joint sensor's joint of a type it cannot read (its type its own or its
/// classes').
fn joint_kind(at: &At<'_, '_>) -> Option<Found> {
    let is = |tags: &[&str]| tags.iter().any(|t| on::at(at.kind(), &format!("sensor/{t}")));
    let ball = if is(&["jointpos", "jointvel", "jointactuatorfrc"]) {
        false
    } else if is(&["ballquat", "ballangvel"]) {
        true
    } else {
        return None;
    };
    let j = named(at.e.model, at.e.node, at.e.class, "joint")?;
    let ty = joint_type(j.model, j.node, j.class);
    match (ball, ty) {
        (false, JointType::Hinge | JointType::Slide) | (true, JointType::Ball) => None,
        (false, _) => found("joint", "joint must be slide or hinge in sensor"),
        (true, _) => found("joint", "joint must be ball in sensor"),
    }
}

/// The keywords of `data`, in the order MuJoCo requires.
const CONTACT_DATA: [&str; 9] =
    ["found", "force", "torque", "dist", "pos", "normal", "tangent", "linvel", "angvel"];
const RAY_DATA: [&str; 6] = ["dist", "dir", "origin", "point", "normal", "depth"];

/// `data`'s first fault, as MuJoCo's reader finds it: a keyword said twice, one it
/// does not know (each in the order written), then the keywords out of its order.
fn data_order(at: &At<'_, '_>) -> Option<Found> {
    let contact = on::at(at.kind(), "sensor/contact");
    let keys: &[&str] = if contact { &CONTACT_DATA } else { &RAY_DATA };
    let mut positions: Vec<usize> = Vec::new();
    let words: Vec<&str> = at.str("data")?.split_whitespace().collect();
    for (n, w) in words.iter().enumerate() {
        if words[..n].contains(w) {
            // MuJoCo's reader refuses it first: the `keyword-twice` check says so.
            return None;
        }
        match keys.iter().position(|k| k == w) {
            Some(p) => positions.push(p),
            None => return found("data", format!("invalid keyword: '{w}'")),
        }
    }
    positions.windows(2).any(|w| w[1] <= w[0]).then_some(())?;
    found("data", format!("data attributes must be in order: {}", keys.join(", ")))
}

/// A sensor between two bodies or geoms.
fn geom_distance(k: ElementKind) -> bool {
    ["sensor/distance", "sensor/normal", "sensor/fromto"].iter().any(|p| on::at(k, p))
}

/// A geom-distance sensor's two objects: the same one twice, or a height field.
fn distance_objects(at: &At<'_, '_>) -> Option<Found> {
    let (model, node) = (at.e.model, at.e.node);
    let object = |body: &'static str, geom: &'static str| {
        [body, geom].into_iter().find_map(|a| {
            let i = node.kind().attr_index(a)?;
            Some((a, i, effective(model, node, at.e.class, a)?))
        })
    };
    let (first, second) = (object("body1", "geom1"), object("body2", "geom2"));
    if let (Some((a, i, x)), Some((b, j, y))) = (first, second) {
        let r: (Ref<'_>, Ref<'_>) = ((model, node, i, x), (model, node, j, y));
        if a[..4] == b[..4] && same(r.0, r.1) {
            return found_element("1st body/geom must be different from 2nd body/geom");
        }
    }
    let hfield = |attr: &str| {
        named(model, node, at.e.class, attr)
            .is_some_and(|g: Target<'_>| g.get("type").and_then(Value::as_str) == Some("hfield"))
    };
    (hfield("geom1") || hfield("geom2")).then_some(())?;
    found_element("height fields are not supported in geom distance sensors")
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    /// A model with hinge `j`, ball `ba`, site `s`, geoms `g` and `h` (a height
    /// field), camera `c`, and `sensor` in `<sensor>`.
    fn with(sensor: &str) -> String {
        format!(
            r#"<mujoco><asset><hfield name="hf" nrow="2" ncol="2" size="1 1 1 1"/></asset><worldbody>
            <body name="b"><joint name="j"/><geom name="g" size=".1"/><site name="s"/></body>
            <body name="b2"><joint name="ba" type="ball"/><geom size=".1"/></body>
            <geom name="h" type="hfield" hfield="hf"/><geom name="g2" size=".1"/><camera name="c"/>
            </worldbody><sensor>{sensor}</sensor></mujoco>"#
        )
    }

    fn pairs(rule: &str, pairs: &[(&str, &str)]) {
        let texts: Vec<(String, String)> = pairs.iter().map(|(a, b)| (with(a), with(b))).collect();
        let refs: Vec<(&str, &str)> = texts.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs(rule, &refs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_sensor_s_own_values_are_judged_as_mujoco_judges_them() {
        let jp = |a: &str| format!(r#"<jointpos joint="j" {a}/>"#);
        let p = |rule: &str, bad: &str, good: &str| pairs(rule, &[(&jp(bad), &jp(good))]);
        p("sensor-noise-negative", r#"noise="-1""#, r#"noise="-0""#);
        p("sensor-cutoff-negative", r#"cutoff="-1""#, r#"cutoff="1""#);
        p("sensor-interval", r#"interval="-1""#, r#"interval="2""#);
        p("sensor-interval", r#"interval="0 1e-300""#, r#"interval="0 -5""#);
        p("sensor-interval", r#"interval="0.5 -0.5""#, r#"interval="0.5 -0.4999""#);
        p("sensor-nsample-large", r#"nsample="16777217""#, r#"nsample="16777216""#);
        p("sensor-delay-without-history", r#"delay="1""#, r#"delay="1" nsample="1""#);
        pairs(
            "sensor-cutoff-axis-or-quaternion",
            &[
                (
                    r#"<framequat objtype="site" objname="s" cutoff="1"/>"#,
                    r#"<framepos objtype="site" objname="s" cutoff="1"/>"#,
                ),
                (
                    r#"<framexaxis objtype="site" objname="s" cutoff="1"/>"#,
                    r#"<normal geom1="g" geom2="g2" cutoff="1"/>"#,
                ),
                (r#"<ballquat joint="ba" cutoff="1"/>"#, r#"<ballangvel joint="ba" cutoff="1"/>"#),
                (
                    r#"<user dim="4" datatype="quaternion" objtype="joint" objname="j" cutoff="1"/>"#,
                    r#"<user dim="4" datatype="quaternion" objtype="joint" objname="j" cutoff="0"/>"#,
                ),
            ],
        );
        let user = |a: &str| format!(r#"<user objtype="joint" objname="j" {a}/>"#);
        for (bad, good) in [
            (r#"dim="-1""#, r#"dim="0""#),
            (r#"dim="2" datatype="axis""#, r#"dim="3" datatype="axis""#),
            (r#"dim="3" datatype="quaternion""#, r#"dim="4" datatype="quaternion""#),
        ] {
            pairs("sensor-user-dim", &[(&user(bad), &user(good))]);
        }
        pairs(
            "sensor-data",
            &[
                (
                    r#"<contact site="s" data="force found"/>"#,
                    r#"<contact site="s" data="found force torque dist pos normal tangent"/>"#,
                ),
                (
                    r#"<rangefinder site="s" data="dir dist"/>"#,
                    r#"<rangefinder site="s" data="dist dir origin point normal depth"/>"#,
                ),
                (r#"<contact site="s" data="force nope"/>"#, r#"<contact site="s" data="found"/>"#),
            ],
        );
        pairs(
            "sensor-contact-num",
            &[(r#"<contact site="s" num="0"/>"#, r#"<contact site="s" num="1"/>"#)],
        );
        pairs(
            "sensor-insidesite-camera-enclosed",
            &[(
                r#"<insidesite objtype="camera" objname="c" site="s" enclosed="true"/>"#,
                r#"<insidesite objtype="camera" objname="c" site="s" enclosed="false"/>"#,
            )],
        );
    }

    #[test]
    fn a_sensor_s_objects_are_judged_by_their_own_values() {
        pairs(
            "sensor-joint-type",
            &[
                (r#"<jointpos joint="ba"/>"#, r#"<ballquat joint="ba"/>"#),
                (r#"<jointactuatorfrc joint="ba"/>"#, r#"<jointvel joint="j"/>"#),
                (r#"<ballangvel joint="j"/>"#, r#"<jointpos joint="j"/>"#),
            ],
        );
        pairs(
            "sensor-distance-objects",
            &[
                (r#"<distance geom1="g" geom2="g"/>"#, r#"<distance geom1="g" geom2="g2"/>"#),
                (r#"<normal body1="b" body2="b"/>"#, r#"<distance body1="b" geom2="g"/>"#),
                (r#"<distance geom1="h" geom2="g"/>"#, r#"<fromto geom1="g2" geom2="g"/>"#),
            ],
        );
        let camera = |res: &str| {
            format!(
                r#"<mujoco><worldbody><camera name="c" {res}/></worldbody><sensor><rangefinder camera="c"/></sensor></mujoco>"#
            )
        };
        let (bad, good) = (camera(r#"resolution="0 4""#), camera(""));
        assert_pairs("sensor-camera-resolution", &[(&bad, &good)]);
        let (bad, good) = (camera(r#"resolution="4 -1""#), camera(r#"resolution="4 4""#));
        assert_pairs("sensor-camera-resolution", &[(&bad, &good)]);
        let projection = |res: &str| {
            format!(
                r#"<mujoco><worldbody><site name="s"/><camera name="c" {res}/></worldbody>
                <sensor><camprojection site="s" camera="c"/></sensor></mujoco>"#
            )
        };
        let (bad, good) = (projection(r#"resolution="-1 4""#), projection(""));
        assert_pairs("sensor-camera-resolution", &[(&bad, &good)]);
    }

    /// A joint's type given by the class in force where it is (a `childclass`).
    #[test]
    fn a_joint_s_type_given_by_its_class_counts() {
        let text = |ty: &str| {
            format!(
                r#"<mujoco><default><default class="k"><joint type="{ty}"/></default></default><worldbody>
                <body childclass="k"><joint name="j"/><geom size=".1"/></body></worldbody>
                <sensor><jointpos joint="j"/></sensor></mujoco>"#
            )
        };
        assert_pairs("sensor-joint-type", &[(&text("ball"), &text("slide"))]);
    }
}
