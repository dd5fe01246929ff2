//! The check of numbers MuJoCo's XML reader cannot hold ("number is too large in
//! attribute 'group'"): an integer beyond a C `int` (MuJoCo reads every integer
//! attribute as one), and a number beyond a C `float` in the attributes MuJoCo keeps
//! as `float` (colours, lights, the visual settings, ...; the others it keeps as
//! `double`, which any finite number fits). Judged on the element's own values, in
//! default classes too (MuJoCo reads those alike).

use std::collections::HashSet;
use std::sync::OnceLock;

use crate::schema::ElementKind;
use crate::value::Value;

use super::{At, Check, Found, found, on};

/// The attributes MuJoCo 4.0.0 keeps as `float`: where, and which (each refused at
/// `1e39` by MuJoCo 4.0.0 with "number is too large"). Those of meshes, skins and
/// flexes are not listed (not probed).
const FLOATS: &[(&[&str], &[&str])] = &[
    (
        &[
            "(world)body/geom",
            "default/geom",
            "(world)body/site",
            "default/site",
            "tendon/spatial",
            "default/tendon",
        ],
        &["rgba"],
    ),
    (
        &["asset/material", "default/material"],
        &[
            "rgba",
            "emission",
            "specular",
            "shininess",
            "reflectance",
            "metallic",
            "roughness",
            "texrepeat",
        ],
    ),
    (
        &["(world)body/camera", "default/camera"],
        &["focal", "focalpixel", "principal", "principalpixel", "sensorsize"],
    ),
    (
        &["(world)body/light", "default/light"],
        &[
            "ambient",
            "attenuation",
            "bulbradius",
            "cutoff",
            "diffuse",
            "exponent",
            "intensity",
            "range",
            "softness",
            "specular",
        ],
    ),
    (&["visual/global"], &["azimuth", "elevation", "fovy", "glow", "ipd", "linewidth", "realtime"]),
    (&["visual/headlight"], &["ambient", "diffuse", "specular"]),
    (
        &["visual/map"],
        &[
            "actuatortendon",
            "alpha",
            "fogend",
            "fogstart",
            "force",
            "haze",
            "shadowclip",
            "shadowscale",
            "stiffness",
            "stiffnessrot",
            "torque",
            "zfar",
            "znear",
        ],
    ),
    (
        &["visual/rgba"],
        &[
            "actuator",
            "actuatornegative",
            "actuatorpositive",
            "bv",
            "bvactive",
            "camera",
            "com",
            "connect",
            "constraint",
            "contactforce",
            "contactfriction",
            "contactgap",
            "contactpoint",
            "contacttorque",
            "crankbroken",
            "fog",
            "force",
            "frustum",
            "haze",
            "inertia",
            "joint",
            "light",
            "rangefinder",
            "selectpoint",
            "slidercrank",
        ],
    ),
    (
        &["visual/scale"],
        &[
            "actuatorlength",
            "actuatorwidth",
            "camera",
            "com",
            "connect",
            "constraint",
            "contactheight",
            "contactwidth",
            "forcewidth",
            "framelength",
            "framewidth",
            "frustum",
            "jointlength",
            "jointwidth",
            "light",
            "selectpoint",
            "slidercrank",
        ],
    ),
];

/// [`FLOATS`] as (kind index, attribute index), gathered once.
fn floats() -> &'static HashSet<(usize, usize)> {
    static FLOAT_ATTRS: OnceLock<HashSet<(usize, usize)>> = OnceLock::new();
    FLOAT_ATTRS.get_or_init(|| {
        let mut out = HashSet::new();
        for kind in ElementKind::all() {
            for (paths, attrs) in FLOATS {
                if paths.iter().any(|p| on::at(kind, p)) {
                    out.extend(
                        attrs.iter().filter_map(|a| Some((kind.index(), kind.attr_index(a)?))),
                    );
                }
            }
        }
        out
    })
}

pub(crate) const CHECKS: &[Check] = &[Check {
    name: "number-too-large",
    on: |_| true,
    test: too_large,
    fix: "give a number MuJoCo can hold (an integer within ±2147483647; a colour, light \
          or visual setting within ±3.4e38)",
}];

/// The first of the element's own attributes holding a number MuJoCo cannot hold.
fn too_large(at: &At<'_, '_>) -> Option<Found> {
    let kind = at.kind();
    let int = |i: &i64| i32::try_from(*i).is_err();
    let float = |x: &f64| x.is_finite() && (*x as f32).is_infinite();
    let (i, _) = at.e.node.attrs().iter().find(|(i, v)| match v {
        Value::Int(n) => int(n),
        Value::Ints(ns) => ns.iter().any(int),
        Value::Float(x) => float(x) && floats().contains(&(kind.index(), *i as usize)),
        Value::Floats(xs) => {
            xs.iter().any(float) && floats().contains(&(kind.index(), *i as usize))
        }
        _ => false,
    })?;
    let attr = kind.attr(*i as usize).name;
    found(attr, format!("number is too large in attribute '{attr}'"))
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;
    use super::*;

    #[test]
    fn every_float_attribute_listed_is_an_attribute_of_its_elements() {
        for (paths, attrs) in FLOATS {
            for path in *paths {
                let kinds: Vec<ElementKind> =
                    ElementKind::all().filter(|k| on::at(*k, path)).collect();
                assert!(!kinds.is_empty(), "{path}");
                for k in kinds {
                    for a in *attrs {
                        assert!(k.attr_index(a).is_some(), "{path} {a}");
                    }
                }
            }
        }
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_number_beyond_what_mujoco_holds_is_too_large() {
        let w = |body: &str| format!("<mujoco><worldbody>{body}</worldbody></mujoco>");
        let pairs: Vec<(String, String)> = vec![
            (w(r#"<geom size=".1" group="99999999999"/>"#), w(r#"<geom size=".1" group="5"/>"#)),
            (w(r#"<geom size=".1" group="2147483648"/>"#), w(r#"<geom size=".1" group="2147483647"/>"#)),
            (w(r#"<geom size=".1" group="-2147483649"/>"#), w(r#"<geom size=".1" group="-2147483648"/>"#)),
            (
                r#"<mujoco><default><geom contype="4294967296"/></default></mujoco>"#.into(),
                r#"<mujoco><default><geom contype="4294967"/></default></mujoco>"#.into(),
            ),
            (
                w(r#"<camera resolution="10 3000000000"/>"#),
                w(r#"<camera resolution="10 30000"/>"#),
            ),
            (w(r#"<geom size=".1" rgba="1e39 1 1 1"/>"#), w(r#"<geom size="1e39" rgba="3e38 1 1 1"/>"#)),
            (
                r#"<mujoco><visual><map znear="1e39"/></visual></mujoco>"#.into(),
                r#"<mujoco><visual><map znear="1e38"/></visual><statistic extent="1e300"/></mujoco>"#.into(),
            ),
            (
                r#"<mujoco><default><light intensity="-1e39"/></default></mujoco>"#.into(),
                r#"<mujoco><default><light intensity="-1e38"/></default></mujoco>"#.into(),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("number-too-large", &pairs);
    }
}
