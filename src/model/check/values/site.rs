//! The checks of a site's own values (MuJoCo 4.0.0's `mjCSite::Compile`).

use super::{At, Check, found, on};

/// A site's type, its own or its classes' (`sphere` when none).
fn site_type<'m>(at: &At<'_, 'm>) -> &'m str {
    at.str("type").unwrap_or("sphere")
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "site-type",
        on: on::site,
        test: |at| {
            matches!(site_type(at), "hfield" | "plane").then_some(())?;
            found("type", "hfields and planes not allowed in site")
        },
        fix: "give the site another type",
    },
    Check {
        name: "site-mesh-missing",
        on: on::site,
        test: |at| {
            (site_type(at) == "mesh" && !at.has("mesh")).then_some(())?;
            found("type", format!("mesh site '{}' must have valid meshid", at.name()))
        },
        fix: "give the site a mesh, or another type",
    },
    Check {
        name: "site-mesh-type",
        on: on::site,
        test: |at| {
            (at.has("mesh") && site_type(at) != "mesh").then_some(())?;
            found("mesh", "mesh can only be specified for mesh sites")
        },
        fix: "give the site type mesh, or remove its mesh",
    },
    Check {
        name: "site-fromto-type",
        on: on::site,
        test: |at| {
            at.floats("fromto")?.first().is_some_and(|x| !x.is_nan()).then_some(())?;
            let ty = site_type(at);
            (!matches!(ty, "capsule" | "cylinder" | "box" | "ellipsoid")).then_some(())?;
            found("fromto", "fromto requires capsule, cylinder, box or ellipsoid in site")
        },
        fix: "give it type capsule, cylinder, box or ellipsoid, or a pos instead of fromto",
    },
];

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_sites_type_mesh_and_fromto_are_judged_as_mujoco_judges_them() {
        let mesh = r#"<asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset>"#;
        let m = |body: &str| format!("<mujoco>{mesh}<worldbody>{body}</worldbody></mujoco>");
        let (bad, good) = (m(r#"<site type="plane"/>"#), m(r#"<site type="box"/>"#));
        assert_pairs("site-type", &[(&bad, &good)]);
        let (bad, good) = (
            "<mujoco><default><site type=\"hfield\"/></default><worldbody><site/></worldbody></mujoco>".to_string(),
            "<mujoco><default><site type=\"hfield\"/></default></mujoco>".to_string(),
        );
        assert_pairs("site-type", &[(&bad, &good)]);
        let (bad, good) = (m(r#"<site type="mesh"/>"#), m(r#"<site type="mesh" mesh="m"/>"#));
        assert_pairs("site-mesh-missing", &[(&bad, &good)]);
        let (bad, good) = (m(r#"<site type="sdf" mesh="m"/>"#), m(r#"<site type="sdf"/>"#));
        assert_pairs("site-mesh-type", &[(&bad, &good)]);
        let (bad, good) = (
            m(r#"<site size=".1" fromto="0 0 0 0 0 1"/>"#),
            m(r#"<site type="ellipsoid" size=".1" fromto="0 0 0 0 0 1"/>"#),
        );
        assert_pairs("site-fromto-type", &[(&bad, &good)]);
    }
}
