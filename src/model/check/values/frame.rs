//! The checks of a `<frame>`'s own scale (MuJoCo 4.0.0's frame `scale`, `scaling`
//! and `massscale`).

use super::{Check, found, on};

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "frame-scale-positive",
        on: on::frame,
        test: |at| {
            let s = at.floats("scale")?;
            s.iter().any(|x| !(x.is_finite() && *x > 0.0)).then_some(())?;
            found("scale", "frame scale must be finite and positive")
        },
        fix: "give scale finite positive numbers",
    },
    Check {
        name: "frame-massscale",
        on: on::frame,
        test: |at| {
            let m = at.float("massscale")?;
            (!(m.is_finite() && m >= 0.0)).then_some(())?;
            found("massscale", "frame massscale must be finite and non-negative")
        },
        fix: "give massscale a finite number, zero or more",
    },
    Check {
        name: "frame-scale-anisotropic",
        on: on::frame,
        test: |at| {
            let s = at.floats("scale")?;
            s.iter().any(|x| *x != s[0]).then_some(())?;
            (at.str("scaling") != Some("geometry")).then_some(())?;
            found("scale", "an anisotropic frame scale requires scaling 'geometry'")
        },
        fix: "give the frame scaling=\"geometry\", or one scale for all axes",
    },
];

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn frame(attrs: &str) -> String {
        format!(
            r#"<mujoco><worldbody><frame {attrs}><geom type="box" size=".1 .1 .1"/></frame></worldbody></mujoco>"#
        )
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_frames_scales_are_judged_as_mujoco_judges_them() {
        let pairs = [
            (frame(r#"scale="0 0 0""#), frame(r#"scale="2 2 2""#)),
            (frame(r#"scale="-1""#), frame(r#"scale="2""#)),
            (frame(r#"scale="inf inf inf""#), frame(r#"scale="1e-300 1e-300 1e-300""#)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("frame-scale-positive", &pairs);
        let pairs = [
            (frame(r#"massscale="-1""#), frame(r#"massscale="0""#)),
            (frame(r#"massscale="nan""#), frame(r#"massscale="-0""#)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("frame-massscale", &pairs);
        let pairs = [
            (frame(r#"scale="1 2 1""#), frame(r#"scale="1 2 1" scaling="geometry""#)),
            (
                frame(r#"scale="1 2 1" scaling="similar""#),
                frame(r#"scale="2 2 2" scaling="similar""#),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("frame-scale-anisotropic", &pairs);
    }
}
