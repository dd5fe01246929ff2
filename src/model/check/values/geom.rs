//! The checks of a geom's own values (MuJoCo's `mjCGeom::Compile` and `checksize`).

use super::{At, Check, Found, found, on};

/// The numbers of `size` a geom type must have positive (MuJoCo's `mjGEOMINFO`); a
/// plane's third alone; a mesh, height field or SDF's none (MuJoCo sizes them).
fn sized(ty: &str) -> usize {
    match ty {
        "sphere" => 1,
        "capsule" | "cylinder" => 2,
        "ellipsoid" | "box" => 3,
        _ => 0,
    }
}

/// A geom's type, its own or its classes' (`sphere` when none).
fn geom_type<'m>(at: &At<'_, 'm>) -> &'m str {
    at.str("type").unwrap_or("sphere")
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "geom-size-positive",
        on: on::geom,
        test: size_positive,
        fix: "give each size the geom's type reads a positive value",
    },
    Check {
        name: "geom-size-nan",
        on: on::geom,
        test: |at| {
            // A mesh's or height field's size MuJoCo sets itself.
            if at.has("mesh") || geom_type(at) == "hfield" {
                return None;
            }
            at.floats("size")?.iter().any(|x| x.is_nan()).then_some(())?;
            found("size", "nan size in geom")
        },
        fix: "give the size numbers, not nan",
    },
    Check {
        name: "geom-condim",
        on: on::geom,
        test: |at| {
            let c = at.int("condim")?;
            (![1, 3, 4, 6].contains(&c)).then_some(())?;
            found("condim", "invalid condim in geom")
        },
        fix: "use condim 1, 3, 4 or 6",
    },
    Check {
        name: "geom-fromto-type",
        on: on::geom,
        test: |at| {
            at.has("fromto").then_some(())?;
            let ty = geom_type(at);
            (!matches!(ty, "capsule" | "cylinder" | "box" | "ellipsoid")).then_some(())?;
            found("fromto", "fromto requires capsule, cylinder, box or ellipsoid in geom")
        },
        fix: "give it type capsule, cylinder, box or ellipsoid, or a pos instead of fromto",
    },
    Check {
        name: "geom-fromto-and-pos",
        on: on::geom,
        test: |at| {
            at.has("fromto").then_some(())?;
            at.floats("pos")?.iter().any(|x| *x != 0.0).then_some(())?;
            found("pos", "both pos and fromto defined in geom")
        },
        fix: "remove pos: fromto places the geom",
    },
    Check {
        name: "geom-fromto-too-close",
        on: on::geom,
        test: |at| {
            let f = at.floats("fromto").filter(|f| f.len() == 6)?;
            let len =
                ((f[0] - f[3]).powi(2) + (f[1] - f[4]).powi(2) + (f[2] - f[5]).powi(2)).sqrt();
            (len / 2.0 < 1e-14).then_some(())?;
            found("fromto", "fromto points too close in geom")
        },
        fix: "give fromto two distinct points",
    },
    Check {
        name: "geom-mesh-missing",
        on: on::geom,
        test: |at| {
            (matches!(geom_type(at), "mesh" | "sdf") && !at.has("mesh")).then_some(())?;
            found("type", format!("mesh geom '{}' must have valid meshid", at.name()))
        },
        fix: "give the geom a mesh, or another type",
    },
    Check {
        name: "geom-hfield-missing",
        on: on::geom,
        test: |at| {
            ((geom_type(at) == "hfield") != at.has("hfield")).then_some(())?;
            found("hfield", format!("hfield geom '{}' must have valid hfieldid", at.name()))
        },
        fix: "give an hfield geom its hfield, and an hfield only to an hfield geom",
    },
    Check {
        name: "geom-mesh-shellinertia",
        on: on::geom,
        test: |at| {
            (matches!(geom_type(at), "mesh" | "sdf") && at.has("mesh")).then_some(())?;
            (at.str("shellinertia")? == "true").then_some(())?;
            found("shellinertia", "for mesh geoms, inertia should be specified in the mesh asset")
        },
        fix: "remove shellinertia; set the mesh asset's inertia instead",
    },
];

/// `size 1 must be positive in geom`, `plane size(3) must be positive`: the numbers
/// (a nan passes here, as in MuJoCo, to be refused as `nan size in geom`)
/// the type reads, as MuJoCo holds them (its classes' with its own over them; zero
/// where none is given), unless MuJoCo sizes the geom itself (a mesh, or a mesh
/// fitted with a primitive type) or `fromto` gives the length.
fn size_positive(at: &At<'_, '_>) -> Option<Found> {
    let ty = geom_type(at);
    if at.has("mesh") && !matches!(ty, "plane" | "hfield") {
        return None;
    }
    let size = at.floats("size").unwrap_or_default();
    let value = |i: usize| size.get(i).copied().unwrap_or(0.0);
    if ty == "plane" {
        return (value(2) <= 0.0).then(|| found("size", "plane size(3) must be positive"))?;
    }
    let fromto = at.has("fromto");
    (0..sized(ty))
        // With fromto, MuJoCo sets a capsule's or cylinder's length, a box's or
        // ellipsoid's second and third sizes.
        .filter(|i| !(fromto && (*i == 1 || *i == 2)))
        .find(|i| value(*i) <= 0.0)
        .and_then(|i| found("size", format!("size {i} must be positive in geom")))
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn world(body: &str) -> String {
        format!("<mujoco><worldbody>{body}</worldbody></mujoco>")
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn sizes_must_be_positive_where_the_type_reads_them() {
        let pairs = [
            (world("<geom/>"), world(r#"<geom size="1"/>"#)),
            (world(r#"<geom type="box" size="1 0 1"/>"#), world(r#"<geom type="box" size="1 1 1"/>"#)),
            (world(r#"<geom type="capsule" size="1 -1"/>"#), world(r#"<geom type="capsule" size="1 1 -1"/>"#)),
            (world(r#"<geom type="plane" size="1 1"/>"#), world(r#"<geom type="plane" size="0 0 1"/>"#)),
            (
                world(r#"<geom type="capsule" fromto="0 0 0 0 0 1"/>"#),
                world(r#"<geom type="capsule" fromto="0 0 0 0 0 1" size=".1"/>"#),
            ),
            (
                r#"<mujoco><default><geom size="0"/></default><worldbody><geom/></worldbody></mujoco>"#.into(),
                r#"<mujoco><default><geom size="1"/></default><worldbody><geom/></worldbody></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><default><geom type="box" size="1 1 0"/></default><worldbody><geom size="2"/></worldbody></mujoco>"#.into(),
                r#"<mujoco><default><geom type="box" size="1 1 1"/></default><worldbody><geom size="2"/></worldbody></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("geom-size-positive", &pairs);
    }

    #[test]
    fn condim_and_fromto_are_judged_as_mujoco_judges_them() {
        let (bad, good) =
            (world(r#"<geom size="1" condim="2"/>"#), world(r#"<geom size="1" condim="4"/>"#));
        assert_pairs("geom-condim", &[(&bad, &good)]);
        let f = r#"fromto="0 0 0 0 0 1" size=".1""#;
        let (bad, good) = (
            world(&format!(r#"<geom type="sphere" {f}/>"#)),
            world(&format!(r#"<geom type="box" {f}/>"#)),
        );
        assert_pairs("geom-fromto-type", &[(&bad, &good)]);
        let (bad, good) = (
            world(&format!(r#"<geom type="capsule" {f} pos="0 0 1e-300"/>"#)),
            world(&format!(r#"<geom type="capsule" {f} pos="0 0 0"/>"#)),
        );
        assert_pairs("geom-fromto-and-pos", &[(&bad, &good)]);
        let (bad, good) = (
            world(r#"<geom type="capsule" fromto="0 0 0 0 0 0" size=".1"/>"#),
            world(r#"<geom type="capsule" fromto="0 0 0 0 0 1e-6" size=".1"/>"#),
        );
        assert_pairs("geom-fromto-too-close", &[(&bad, &good)]);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn mesh_and_hfield_geoms_need_their_asset() {
        let assets = r#"<asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/><hfield name="h" nrow="2" ncol="2" size="1 1 1 1"/></asset>"#;
        let m = |body: &str| format!("<mujoco>{assets}<worldbody>{body}</worldbody></mujoco>");
        let (bad, good) = (m(r#"<geom type="sdf"/>"#), m(r#"<geom mesh="m"/>"#));
        assert_pairs("geom-mesh-missing", &[(&bad, &good)]);
        let (bad, good) = (
            m(r#"<geom type="box" size="1 1 1" hfield="h"/>"#),
            m(r#"<geom type="hfield" hfield="h"/>"#),
        );
        assert_pairs("geom-hfield-missing", &[(&bad, &good)]);
        let (bad, good) = (
            format!(
                r#"<mujoco>{assets}<default><geom shellinertia="true"/></default><worldbody><geom type="mesh" mesh="m"/></worldbody></mujoco>"#
            ),
            m(r#"<geom type="box" mesh="m" shellinertia="true"/>"#),
        );
        assert_pairs("geom-mesh-shellinertia", &[(&bad, &good)]);
    }
}
