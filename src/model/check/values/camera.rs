//! The checks of a camera's and a light's own values (MuJoCo's `mjCCamera::Compile`
//! and `mjCLight::Compile`).

use super::{At, Check, found, on};

/// Whether the camera gives any intrinsic parameter (a non-zero `focal`,
/// `focalpixel`, `principal` or `principalpixel` number; a nan counts, as in MuJoCo).
fn has_intrinsic(at: &At<'_, '_>) -> bool {
    ["focal", "focalpixel", "principal", "principalpixel"]
        .iter()
        .filter_map(|a| at.floats(a))
        .any(|v| v.iter().take(2).any(|x| *x != 0.0))
}

/// Whether the camera has a sensor size (both numbers positive).
fn has_sensorsize(at: &At<'_, '_>) -> bool {
    at.floats("sensorsize").is_some_and(|s| s.len() >= 2 && s[0] > 0.0 && s[1] > 0.0)
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "camera-fovy",
        on: on::camera,
        test: |at| {
            let fovy = at.float("fovy")?;
            (fovy >= 180.0).then_some(())?;
            found("fovy", format!("fovy too large in camera '{}' (value = {fovy})", at.name()))
        },
        fix: "give fovy an angle below 180 degrees",
    },
    Check {
        name: "camera-intrinsic-sensorsize",
        on: on::camera,
        test: |at| {
            (has_intrinsic(at) && !has_sensorsize(at)).then_some(())?;
            let message = format!("focal/principal require sensorsize in camera '{}'", at.name());
            found("sensorsize", message)
        },
        fix: "give the camera a positive sensorsize, or remove focal and principal",
    },
    Check {
        name: "camera-sensorsize-resolution",
        on: on::camera,
        test: |at| {
            has_sensorsize(at).then_some(())?;
            let r = at.floats("resolution").unwrap_or_default();
            // MuJoCo's resolution is 1 1 unless given.
            let value = |i: usize| r.get(i).copied().unwrap_or(1.0);
            (value(0) <= 0.0 || value(1) <= 0.0).then_some(())?;
            let message =
                format!("sensorsize requires positive resolution in camera '{}'", at.name());
            found("resolution", message)
        },
        fix: "give the camera a positive resolution",
    },
    Check {
        name: "light-dir-zero",
        on: on::light,
        test: |at| {
            let dir = at.floats("dir")?;
            let n: f64 = dir.iter().take(3).map(|x| x * x).sum();
            (n < 1e-14).then_some(())?;
            found("dir", "zero direction in light")
        },
        fix: "give the light a non-zero direction",
    },
    Check {
        name: "light-softness",
        on: on::light,
        test: |at| {
            let s = at.float("softness")?;
            (!(0.0..=1.0).contains(&s) && !s.is_nan()).then_some(())?;
            found("softness", "light softness must be in [0, 1]")
        },
        fix: "give softness a value from 0 to 1",
    },
];

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn world(body: &str) -> String {
        format!("<mujoco><worldbody>{body}</worldbody></mujoco>")
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_cameras_field_of_view_and_intrinsics_are_judged_as_mujoco_judges_them() {
        let (bad, good) = (world(r#"<camera fovy="180"/>"#), world(r#"<camera fovy="179.9999"/>"#));
        assert_pairs("camera-fovy", &[(&bad, &good)]);
        let (bad, good) = (
            r#"<mujoco><default><camera fovy="200"/></default><worldbody><camera/></worldbody></mujoco>"#,
            r#"<mujoco><default><camera fovy="200"/></default></mujoco>"#,
        );
        assert_pairs("camera-fovy", &[(bad, good)]);
        let pairs = [
            (
                world(r#"<camera focal="1 1" resolution="10 10"/>"#),
                world(r#"<camera focal="1 1" sensorsize="1 1" resolution="10 10"/>"#),
            ),
            (
                world(r#"<camera principalpixel="0 1" sensorsize="1 0"/>"#),
                world(r#"<camera principalpixel="0 0" sensorsize="1 0"/>"#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("camera-intrinsic-sensorsize", &pairs);
        let pairs = [
            (
                world(r#"<camera sensorsize="1 1" resolution="1 0"/>"#),
                world(r#"<camera sensorsize="1 0"/>"#),
            ),
            // MuJoCo's resolution is 1 1 unless given.
            (
                world(r#"<camera sensorsize="1 1" resolution="0 0"/>"#),
                world(r#"<camera sensorsize="1 1"/>"#),
            ),
            (
                world(r#"<camera sensorsize="1 1" resolution="-1 1"/>"#),
                world(r#"<camera sensorsize="1 1" resolution="1 1"/>"#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("camera-sensorsize-resolution", &pairs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_lights_direction_and_softness_are_judged_as_mujoco_judges_them() {
        let pairs = [
            (world(r#"<light dir="0 0 1e-7"/>"#), world(r#"<light dir="0 0 2e-7"/>"#)),
            (
                "<mujoco><default><light dir=\"0 0 0\"/></default><worldbody><light/></worldbody></mujoco>".into(),
                world(r#"<light dir="nan 0 0"/>"#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("light-dir-zero", &pairs);
        let pairs = [
            (world(r#"<light softness="2"/>"#), world(r#"<light softness="1"/>"#)),
            (world(r#"<light softness="-0.1"/>"#), world(r#"<light softness="nan"/>"#)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("light-softness", &pairs);
    }
}
