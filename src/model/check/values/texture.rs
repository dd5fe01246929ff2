//! The checks of a texture's and a height field's own values (MuJoCo's
//! `mjCTexture::Compile`, `mjCHField::Compile` and its reader, as MuJoCo 4.0.0 words
//! them). What a file holds (an image's size) is not judged here.

use super::{At, Check, Found, found, found_element};
use crate::schema::Role;

/// The files of a cube texture given one per face.
const CUBE_FILES: &[&str] =
    &["fileright", "fileleft", "fileup", "filedown", "filefront", "fileback"];

/// The widest cube texture MuJoCo takes (its six faces' height must fit an `int`).
const CUBE_WIDTH_LIMIT: i64 = i32::MAX as i64 / 6;

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "texture-builtin-size",
        on: |k| k.is(Role::Texture),
        test: builtin_size,
        fix: "give a builtin texture a positive width (and a 2d one a positive height)",
    },
    Check {
        name: "texture-builtin-channels",
        on: |k| k.is(Role::Texture),
        test: |at| {
            compiled(at)?;
            builtin(at)?;
            (at.int("nchannel").unwrap_or(3) != 3).then_some(())?;
            found("nchannel", "builtin textures must have 3 channels")
        },
        fix: "give a builtin texture nchannel 3 (or leave it out)",
    },
    Check {
        name: "texture-source",
        on: |k| k.is(Role::Texture),
        test: source,
        fix: "give the texture a builtin, a file, or (cube and skybox) files per face",
    },
    Check {
        name: "hfield-elevation-length",
        on: |k| k.is(Role::Hfield),
        test: |at| {
            let (nrow, ncol) = manual_dims(at)?;
            let elevation = at.own_floats("elevation").filter(|e| !e.is_empty())?;
            (elevation.len() as i128 != i128::from(nrow) * i128::from(ncol)).then_some(())?;
            found("elevation", "elevation data length must match nrow*ncol")
        },
        fix: "give elevation nrow*ncol numbers",
    },
    Check {
        name: "hfield-dimensions",
        on: |k| k.is(Role::Hfield),
        test: |at| {
            let (nrow, ncol) = manual_dims(at)?;
            (nrow < 2 || ncol < 2).then_some(())?;
            found_element("hfield dimensions must be at least 2")
        },
        fix: "give nrow and ncol at least 2",
    },
    Check {
        name: "hfield-size",
        on: |k| k.is(Role::Hfield),
        test: |at| {
            // nan passes, as in MuJoCo.
            at.own_floats("size")?.iter().any(|x| *x <= 0.0).then_some(())?;
            found("size", "size parameter is not positive in hfield")
        },
        fix: "give all four sizes positive values",
    },
    Check {
        name: "hfield-not-specified",
        on: |k| k.is(Role::Hfield),
        test: |at| {
            at.own("file").is_none().then_some(())?;
            let (nrow, ncol) = (at.own_int("nrow").unwrap_or(0), at.own_int("ncol").unwrap_or(0));
            (nrow < 1 || ncol < 1).then_some(())?;
            found_element("hfield not specified")
        },
        fix: "give the height field a file, or nrow and ncol",
    },
];

/// A height field's `nrow` and `ncol` when it is given by them (no file, both
/// positive): MuJoCo then reads its elevation.
fn manual_dims(at: &At<'_, '_>) -> Option<(i64, i64)> {
    at.own("file").is_none().then_some(())?;
    let (nrow, ncol) = (at.own_int("nrow")?, at.own_int("ncol")?);
    (nrow > 0 && ncol > 0).then_some((nrow, ncol))
}

/// A texture's type, its own or its classes' (`cube` when none).
fn texture_type<'m>(at: &At<'_, 'm>) -> &'m str {
    at.str("type").unwrap_or("cube")
}

/// A builtin texture's kind, if it has one.
fn builtin<'m>(at: &At<'_, 'm>) -> Option<&'m str> {
    at.str("builtin").filter(|b| *b != "none")
}

/// Whether MuJoCo compiles the texture: not when the compiler discards visual assets.
fn compiled(at: &At<'_, '_>) -> Option<()> {
    (!at.settings.discard_visual).then_some(())
}

/// `Invalid width (height) of builtin texture`: a builtin texture's width below 1 (or
/// too wide for a cube's six faces), a 2d one's height below 1.
fn builtin_size(at: &At<'_, '_>) -> Option<Found> {
    compiled(at)?;
    builtin(at)?;
    let width = at.int("width").unwrap_or(0);
    let ty = texture_type(at);
    if width < 1 || ty != "2d" && width >= CUBE_WIDTH_LIMIT {
        return found("width", "Invalid width of builtin texture");
    }
    (ty == "2d" && at.int("height").unwrap_or(0) < 1)
        .then(|| found("height", "Invalid height of builtin texture"))?
}

/// A texture with neither a builtin nor a file: a 2d one cannot be made, a cube or
/// skybox needs a file per face, at least one.
fn source(at: &At<'_, '_>) -> Option<Found> {
    compiled(at)?;
    if builtin(at).is_some() || at.own("file").is_some() {
        return None;
    }
    if texture_type(at) == "2d" {
        return found_element("Cannot load 2D texture from separate files, texture");
    }
    CUBE_FILES
        .iter()
        .all(|f| at.own(f).is_none())
        .then(|| found_element("No cubefiles_ defined in cube or skybox texture"))?
}

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    fn asset(content: &str) -> String {
        format!("<mujoco><asset>{content}</asset></mujoco>")
    }

    fn pairs_of(pairs: &[(String, String)]) -> Vec<(&str, &str)> {
        pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect()
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn builtin_textures_need_their_size() {
        let tex = |attrs: &str| asset(&format!(r#"<texture name="t" builtin="checker" {attrs}/>"#));
        let class = |class: &str, own: &str| {
            format!(
                r#"<mujoco><default><texture {class}/></default><asset><texture name="t" {own}/></asset></mujoco>"#
            )
        };
        let pairs = [
            (tex(r#"type="2d" width="0" height="8""#), tex(r#"type="2d" width="8" height="8""#)),
            (tex(r#"type="2d" width="8""#), tex(r#"width="8" height="0""#)),
            (tex(r#"type="skybox" width="0""#), tex(r#"type="skybox" width="8""#)),
            (tex(""), tex(r#"width="1""#)),
            (tex(r#"type="cube" width="357913941""#), tex(r#"type="cube" width="8""#)),
            (
                tex(r#"type="2d" width="0" height="8""#),
                r#"<mujoco><compiler discardvisual="true"/><asset><texture name="t" type="2d" builtin="checker" width="0" height="8"/></asset></mujoco>"#.into(),
            ),
            (
                class(r#"builtin="checker" width="8" height="0" type="2d""#, ""),
                class(r#"builtin="checker" width="8" height="8" type="2d""#, ""),
            ),
            (
                class(r#"builtin="checker" width="8" height="8" type="2d""#, r#"height="0""#),
                class(r#"builtin="checker" width="8" height="0" type="2d""#, r#"height="1""#),
            ),
        ];
        assert_pairs("texture-builtin-size", &pairs_of(&pairs));
    }

    /// Verdicts MuJoCo 4.0.0's; a class's nchannel counts.
    #[test]
    fn builtin_textures_have_three_channels() {
        let tex = |attrs: &str| {
            asset(&format!(r#"<texture name="t" type="2d" width="8" height="8" {attrs}/>"#))
        };
        let pairs = [
            (tex(r#"builtin="checker" nchannel="4""#), tex(r#"builtin="checker" nchannel="3""#)),
            (tex(r#"builtin="flat" nchannel="1""#), tex(r#"builtin="flat""#)),
            (
                r#"<mujoco><default><texture nchannel="4"/></default><asset><texture name="t" type="2d" builtin="checker" width="8" height="8"/></asset></mujoco>"#.into(),
                r#"<mujoco><default><texture nchannel="4"/></default><asset><texture name="t" type="2d" builtin="checker" width="8" height="8" nchannel="3"/></asset></mujoco>"#.into(),
            ),
        ];
        assert_pairs("texture-builtin-channels", &pairs_of(&pairs));
    }

    /// Verdicts MuJoCo 4.0.0's (a file given is not read here).
    #[test]
    fn textures_without_builtin_need_files() {
        let tex = |attrs: &str| asset(&format!(r#"<texture name="t" {attrs}/>"#));
        let pairs = [
            (tex(r#"type="2d""#), tex(r#"type="2d" builtin="checker" width="8" height="8""#)),
            (tex(r#"type="2d" builtin="none""#), tex(r#"type="2d" builtin="flat" width="8" height="8""#)),
            (
                r#"<mujoco><default><texture type="2d"/></default><asset><texture name="t"/></asset></mujoco>"#.into(),
                r#"<mujoco><default><texture type="2d" builtin="gradient" width="2" height="2"/></default><asset><texture name="t"/></asset></mujoco>"#.into(),
            ),
        ];
        assert_pairs("texture-source", &pairs_of(&pairs));
        let pairs = [
            (tex(r#"type="cube""#), tex(r#"type="cube" builtin="checker" width="8""#)),
            (tex(""), tex(r#"type="skybox" builtin="checker" width="8""#)),
            (tex(r#"type="skybox" builtin="none""#), tex(r#"builtin="flat" width="8""#)),
            (
                tex(""),
                r#"<mujoco><compiler discardvisual="true"/><asset><texture name="t"/></asset></mujoco>"#.into(),
            ),
        ];
        assert_pairs("texture-source", &pairs_of(&pairs));
    }

    /// Verdicts MuJoCo 4.0.0's.
    #[test]
    fn height_fields_need_their_data_and_sizes() {
        let h = |attrs: &str| asset(&format!(r#"<hfield name="h" {attrs}/>"#));
        let ok = h(r#"nrow="2" ncol="2" size="1 1 1 1""#);
        let pairs = [
            (
                h(r#"nrow="2" ncol="2" size="1 1 1 1" elevation="1 2 3""#),
                h(r#"nrow="2" ncol="2" size="1 1 1 1" elevation="1 2 3 4""#),
            ),
            (h(r#"nrow="2" ncol="2" size="1 1 1 1" elevation="1 2 3 4 5""#), ok.clone()),
        ];
        assert_pairs("hfield-elevation-length", &pairs_of(&pairs));
        let pairs = [
            (h(r#"nrow="1" ncol="2" size="1 1 1 1""#), ok.clone()),
            (h(r#"nrow="2" ncol="1" size="1 1 1 1""#), h(r#"nrow="2" ncol="3" size="1 1 1 1""#)),
        ];
        assert_pairs("hfield-dimensions", &pairs_of(&pairs));
        let pairs = [
            (h(r#"nrow="2" ncol="2" size="1 1 0 1""#), h(r#"nrow="2" ncol="2" size="1 1 nan 1""#)),
            (h(r#"nrow="2" ncol="2" size="1 1 1 -1""#), ok.clone()),
        ];
        assert_pairs("hfield-size", &pairs_of(&pairs));
        let pairs = [
            (h(r#"size="1 1 1 1""#), ok.clone()),
            (h(r#"nrow="0" ncol="2" size="1 1 1 1" elevation="1 1 1 1""#), ok.clone()),
            (h(r#"nrow="-1" ncol="2" size="1 1 1 1""#), ok),
        ];
        assert_pairs("hfield-not-specified", &pairs_of(&pairs));
    }
}
