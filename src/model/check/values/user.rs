//! The checks of an element's `user` numbers against `<size nuser_*>` (MuJoCo's
//! `Compile` of bodies, joints, geoms, sites, cameras, tendons and sensors; an
//! actuator's is the actuators rule's, in MuJoCo's order of its checks).

use crate::schema::{ElementKind, Role};

use super::{At, Check, Found, found, numbers, on};

/// The `size` setting each kind's `user` is held to, and MuJoCo's name of the kind.
fn limit_of(k: ElementKind) -> Option<(&'static str, &'static str)> {
    if on::body(k) {
        Some(("nuser_body", "body"))
    } else if on::joint(k) {
        Some(("nuser_jnt", "joint"))
    } else if on::geom(k) {
        Some(("nuser_geom", "geom"))
    } else if on::site(k) {
        Some(("nuser_site", "site"))
    } else if on::camera(k) {
        Some(("nuser_cam", "camera"))
    } else if on::tendon(k) {
        Some(("nuser_tendon", "tendon"))
    } else if on::in_section(k, "sensor") {
        Some(("nuser_sensor", "sensor"))
    } else {
        None
    }
}

pub(crate) const CHECKS: &[Check] = &[Check {
    name: "user-too-long",
    on: |k| limit_of(k).is_some(),
    test: too_long,
    fix: "give user at most as many numbers as the size's nuser_ setting, or raise it",
}];

/// `user has more values than nuser_geom in geom`: the `user` numbers MuJoCo holds
/// (the element's own when it gives any, else its nearest class's: an array given
/// replaces the class's whole) outnumber a `nuser_*` set (-1, the default, sizes it
/// to the longest).
fn too_long(at: &At<'_, '_>) -> Option<Found> {
    let (setting, what) = limit_of(at.kind())?;
    // An attachment frame written as a frame has no user numbers.
    if at.kind().is(Role::Body) && !at.e.is_body {
        return None;
    }
    let n = at.settings.nuser(setting);
    if n < 0 {
        return None;
    }
    let len = at
        .levels()
        .into_iter()
        .filter_map(|l| l.attr(l.kind().attr_index("user")?).and_then(numbers))
        .find(|v| !v.is_empty())
        .map_or(0, |v| v.len());
    (len as i64 > n).then_some(())?;
    let message = match what {
        "geom" => format!("user has more values than {setting} in geom '{}'", at.name()),
        _ => format!("user has more values than {setting} in {what}"),
    };
    found("user", message)
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn user_numbers_must_fit_the_size_setting() {
        let m = |size: &str, body: &str| {
            format!("<mujoco><size {size}/><worldbody>{body}</worldbody></mujoco>")
        };
        let pairs = [
            (m(r#"nuser_body="1""#, r#"<body user="1 2"/>"#), m(r#"nuser_body="-1""#, r#"<body user="1 2"/>"#)),
            (
                m(r#"nuser_jnt="0""#, r#"<body><joint user="1"/><geom size=".1"/></body>"#),
                m(r#"nuser_jnt="1""#, r#"<body><joint user="1"/><geom size=".1"/></body>"#),
            ),
            (m(r#"nuser_geom="1""#, r#"<geom size=".1" user="1 2"/>"#), m(r#"nuser_geom="2""#, r#"<geom size=".1" user="1 2"/>"#)),
            (m(r#"nuser_site="0""#, r#"<site user="1"/>"#), m(r#"nuser_site="0""#, "<site/>")),
            (m(r#"nuser_cam="1""#, r#"<camera user="1 2"/>"#), m(r#"nuser_cam="1""#, r#"<camera user="1"/>"#)),
            // A class's numbers count unless the element gives its own.
            (
                r#"<mujoco><size nuser_jnt="0"/><default><joint user="1"/></default><worldbody><body><joint/><geom size=".1"/></body></worldbody></mujoco>"#.into(),
                r#"<mujoco><size nuser_jnt="1"/><default><joint user="1 2"/></default><worldbody><body><joint user="3"/><geom size=".1"/></body></worldbody></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("user-too-long", &pairs);
    }

    /// Tendons and sensors, by their own numbers or a class's; the last
    /// `<size>` giving a setting wins. Each verdict is MuJoCo 4.0.0's.
    #[test]
    fn tendon_and_sensor_user_numbers_must_fit_too() {
        let with = |size: &str, defaults: &str, tendon: &str, actuator: &str, sensor: &str| {
            format!(
                r#"<mujoco>{size}<default>{defaults}</default><worldbody><body name="b"><joint name="j"/><geom size=".1"/></body></worldbody>
                <tendon><fixed {tendon}><joint joint="j" coef="1"/></fixed></tendon>
                <actuator><motor joint="j" {actuator}/></actuator>
                <sensor><jointpos joint="j" {sensor}/></sensor></mujoco>"#
            )
        };
        let pairs = [
            (
                with(r#"<size nuser_tendon="1"/>"#, "", r#"user="1 2""#, "", ""),
                with(r#"<size nuser_tendon="1"/>"#, "", r#"user="1""#, "", ""),
            ),
            (
                with(r#"<size nuser_sensor="0"/>"#, "", "", "", r#"user="1""#),
                with(r#"<size nuser_sensor="-1"/>"#, "", "", "", r#"user="1 2 3""#),
            ),
            (
                with(
                    r#"<size nuser_sensor="2"/><size nuser_sensor="1"/>"#,
                    "",
                    "",
                    "",
                    r#"user="1 2""#,
                ),
                with(
                    r#"<size nuser_sensor="1"/><size nuser_sensor="2"/>"#,
                    "",
                    "",
                    "",
                    r#"user="1 2""#,
                ),
            ),
            (
                with(r#"<size nuser_tendon="1"/>"#, r#"<tendon user="1 2"/>"#, "", "", ""),
                with(r#"<size nuser_tendon="2"/>"#, r#"<tendon user="1 2"/>"#, "", "", ""),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("user-too-long", &pairs);
    }
}
