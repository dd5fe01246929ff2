//! The checks of assets' and custom fields' own values: names MuJoCo needs, a
//! material's texture and layers, a skin's group, a custom numeric's size (MuJoCo's
//! `CheckEmptyNames` and its reader, as MuJoCo 4.0.0 words them).

use super::{At, Check, Found, found, found_element, on};
use crate::schema::{ElementKind, Role};

/// The largest custom numeric MuJoCo 4.0.0 takes.
const NUMERIC_MAX: i64 = 10_000_000;

/// The roles a material's `<layer>` may have (MuJoCo's `texrole_map`).
const LAYER_ROLES: &[&str] =
    &["rgb", "occlusion", "roughness", "metallic", "normal", "opacity", "emissive", "rgba", "orm"];

/// An asset MuJoCo needs named: a mesh, height field, texture or material.
fn named_asset(k: ElementKind) -> bool {
    matches!(k.role(), Some(Role::Mesh | Role::Hfield | Role::Texture | Role::Material))
}

/// A `<material>`: an asset, or a default class's (MuJoCo's reader judges both).
fn material(k: ElementKind) -> bool {
    k.is(Role::Material) || on::default_of(k, "material")
}

/// A material's `<layer>`, in an asset or a default class.
fn layer(k: ElementKind) -> bool {
    k.spec().parent.is_some_and(|p| material(p) && p.child("layer") == Some(k))
}

/// A `<skin>` of `<asset>` or `<deformable>`.
fn skin(k: ElementKind) -> bool {
    on::at(k, "asset/skin") || on::at(k, "deformable/skin")
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "asset-empty-name",
        on: named_asset,
        test: empty_name,
        fix: "give the asset a name (or a file, whose name it then takes)",
    },
    Check {
        name: "material-texture-and-layer",
        on: material,
        test: |at| {
            // Its own texture attribute, even empty; a class's does not count.
            at.own("texture")?;
            (!at.e.node.children().is_empty()).then_some(())?;
            found("texture", "A material with a texture attribute cannot have layer sub-elements")
        },
        fix: "remove the texture attribute and give the texture as a layer with role rgb",
    },
    Check {
        name: "layer-role",
        on: layer,
        test: |at| {
            let role = at.own_str("role")?;
            (!LAYER_ROLES.contains(&role)).then_some(())?;
            found("role", format!("unknown layer role '{role}'"))
        },
        fix: "use a role MuJoCo knows: rgb, occlusion, roughness, metallic, normal, opacity, emissive, rgba or orm",
    },
    Check {
        name: "skin-group",
        on: skin,
        test: |at| {
            let g = at.own_int("group")?;
            (!(0..6).contains(&g)).then_some(())?;
            found("group", "skin group must be between 0 and 5")
        },
        fix: "give the skin a group from 0 to 5",
    },
    Check {
        name: "numeric-size",
        on: |k| on::at(k, "custom/numeric"),
        test: numeric_size,
        fix: "give the numeric a size from 1 to 10,000,000, or data (whose length it then takes)",
    },
];

/// `empty name in mesh` (height field, texture, material): an asset with no name and
/// no file to take one from (a skybox texture needs none), unless the compiler
/// discards it as visual.
fn empty_name(at: &At<'_, '_>) -> Option<Found> {
    if !at.name().is_empty() || at.own("file").is_some() {
        return None;
    }
    let what = match at.kind().role() {
        // MuJoCo drops the visual assets first: every material and texture, and the
        // meshes no collision geom uses (an unnamed one no geom can use).
        Some(Role::Mesh | Role::Texture | Role::Material) if at.settings.discard_visual => {
            return None;
        }
        Some(Role::Mesh) => "mesh",
        Some(Role::Hfield) => "height field",
        Some(Role::Texture) if at.str("type").unwrap_or("cube") == "skybox" => return None,
        Some(Role::Texture) => "texture",
        _ => "material",
    };
    found_element(format!("empty name in {what}"))
}

/// `custom field size must be positive`: a size below 1, or no size and no data to
/// take it from; `custom field size exceeds maximum` past ten million.
fn numeric_size(at: &At<'_, '_>) -> Option<Found> {
    match at.own_int("size") {
        Some(size) if size < 1 => found("size", "custom field size must be positive"),
        Some(size) if size > NUMERIC_MAX => found("size", "custom field size exceeds maximum"),
        Some(_) => None,
        None => {
            let data = at.own_floats("data").unwrap_or_default();
            data.is_empty().then(|| found_element("custom field size must be positive"))?
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn asset(content: &str) -> String {
        format!("<mujoco><asset>{content}</asset></mujoco>")
    }

    /// `content` in the assets of a model whose compiler discards visual assets.
    fn discarding(content: &str) -> String {
        format!(r#"<mujoco><compiler discardvisual="true"/><asset>{content}</asset></mujoco>"#)
    }

    const TEX: &str = r#"<texture name="t" type="2d" builtin="checker" width="8" height="8"/>"#;

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn assets_without_a_name_or_file_are_refused() {
        let v = r#"vertex="0 0 0 1 0 0 0 1 0 0 0 1""#;
        let pairs = [
            (asset(&format!("<mesh {v}/>")), asset(&format!(r#"<mesh name="m" {v}/>"#))),
            (
                asset(r#"<hfield nrow="2" ncol="2" size="1 1 1 1"/>"#),
                asset(r#"<hfield name="h" nrow="2" ncol="2" size="1 1 1 1"/>"#),
            ),
            (
                asset(r#"<texture type="2d" builtin="checker" width="8" height="8"/>"#),
                asset(r#"<texture type="skybox" builtin="checker" width="8" height="8"/>"#),
            ),
            (
                r#"<mujoco><default><texture type="2d"/></default><asset><texture builtin="checker" width="3" height="3"/></asset></mujoco>"#.into(),
                r#"<mujoco><default><texture type="skybox"/></default><asset><texture builtin="checker" width="3" height="3"/></asset></mujoco>"#.into(),
            ),
            (asset("<material/>"), asset(r#"<material name="m"/>"#)),
            (
                discarding(r#"<hfield nrow="2" ncol="2" size="1 1 1 1"/>"#),
                discarding(&format!("<material/><texture type=\"2d\" builtin=\"checker\" width=\"2\" height=\"2\"/><mesh {v}/>")),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("asset-empty-name", &pairs);
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn a_materials_texture_excludes_layers_and_layer_roles_are_mujocos() {
        let layer = r#"<layer texture="t" role="rgb"/>"#;
        let pairs = [
            (
                asset(&format!(r#"{TEX}<material name="m" texture="t">{layer}</material>"#)),
                asset(&format!(r#"{TEX}<material name="m">{layer}</material>"#)),
            ),
            (
                format!(
                    r#"<mujoco><default><material texture="t">{layer}</material></default><asset>{TEX}<material name="m"/></asset></mujoco>"#
                ),
                format!(
                    r#"<mujoco><default><material texture="t"/></default><asset>{TEX}<material name="m">{layer}</material></asset></mujoco>"#
                ),
            ),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("material-texture-and-layer", &pairs);
        let role = |r: &str| {
            asset(&format!(r#"{TEX}<material name="m"><layer texture="t" role="{r}"/></material>"#))
        };
        let in_class = |r: &str| {
            format!(
                r#"<mujoco><default><material><layer texture="t" role="{r}"/></material></default><asset>{TEX}</asset></mujoco>"#
            )
        };
        let pairs = [
            (role("bogus"), role("rgb")),
            (role("RGB"), role("orm")),
            (in_class("bogus"), in_class("rgba")),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("layer-role", &pairs);
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn skin_groups_and_numeric_sizes_are_in_range() {
        let skin = |section: &str, group: i32| {
            format!(
                r#"<mujoco><worldbody><body name="b"><geom size=".1"/></body></worldbody><{section}><skin vertex="0 0 0 1 0 0 0 1 0" face="0 1 2" group="{group}"><bone body="b" bindpos="0 0 0" bindquat="1 0 0 0" vertid="0 1 2" vertweight="1 1 1"/></skin></{section}></mujoco>"#
            )
        };
        let pairs = [
            (skin("deformable", 6), skin("deformable", 5)),
            (skin("deformable", -1), skin("deformable", 0)),
            (skin("asset", 6), skin("asset", 0)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("skin-group", &pairs);
        let numeric = |attrs: &str| {
            format!(r#"<mujoco><custom><numeric name="n" {attrs}/></custom></mujoco>"#)
        };
        let pairs = [
            (numeric(r#"size="0""#), numeric(r#"size="1""#)),
            (numeric(r#"size="-1" data="1""#), numeric(r#"size="501""#)),
            (numeric(""), numeric(r#"data="1 2""#)),
            (numeric(r#"size="10000001""#), numeric(r#"size="10000000""#)),
        ];
        let pairs: Vec<(&str, &str)> =
            pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
        assert_pairs("numeric-size", &pairs);
    }
}
