//! The checks of single elements that MuJoCo's XML reader makes as it reads them: a
//! `<text>` without data, text attributes of a fixed number of characters, and
//! keyword lists given a keyword twice, an actuator's `input` that is no input
//! signature. (A file's top-level default class named other than `main`, which
//! MuJoCo's reader refuses, is refused by this crate's reader: decision D16.)

use crate::schema::Role;
use crate::value::Value;

use super::{At, Check, Found, found, found_element, on};
use crate::model::check::actuator_spec::{BadInput, parse_input};

/// The attributes that take a list of keywords, each at most once (MuJoCo's
/// `MapValues`): where they are, and their keywords.
const FLAGS: &[(&[&str], &str, &[&str])] = &[
    (
        &["(world)body/camera", "default/camera"],
        "output",
        &["rgb", "depth", "distance", "normal", "segmentation"],
    ),
    (&["sensor/rangefinder"], "data", &["dist", "dir", "origin", "point", "normal", "depth"]),
    (
        &["sensor/contact"],
        "data",
        &["found", "force", "torque", "dist", "pos", "normal", "tangent", "linvel", "angvel"],
    ),
    (INPUT_AT, "input", INPUTS),
];

/// The elements with an `input` (MuJoCo's `ReadInputSpec`).
const INPUT_AT: &[&str] = &[
    "actuator/general",
    "actuator/orientation",
    "actuator/pid",
    "actuator/dcmotor",
    "default/general",
    "default/orientation",
    "default/pid",
    "default/dcmotor",
];
/// The input tokens (`actuator_spec::INPUT_TOKENS`' names).
const INPUTS: &[&str] = &["pos", "vel", "ff", "voltage", "pressure"];

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "text-empty",
        on: |k| k.is(Role::TextField),
        test: |at| at.own("data").is_none().then(|| found_element("text field cannot be empty"))?,
        fix: "give the text its data (data=\"...\", or one CDATA section)",
    },
    Check {
        name: "texture-gridlayout",
        on: |k| k.is(Role::Texture),
        test: gridlayout,
        fix: "give gridlayout one character per square of gridsize (at most 12)",
    },
    Check {
        name: "compiler-eulerseq-length",
        on: |k| on::at(k, "compiler"),
        test: |at| {
            (own_text(at, "eulerseq")?.len() != 3).then_some(())?;
            found("eulerseq", "attribute 'eulerseq' must have exactly 3 characters")
        },
        fix: "give eulerseq three axes (xyz, XYZ, zyx, ...)",
    },
    Check {
        name: "actuator-input-tokens",
        on: |k| INPUT_AT.iter().any(|p| on::at(k, p)),
        test: input_tokens,
        fix: "give input one of expmap, quat, none, or inputs among pos vel ff voltage pressure in that order",
    },
    Check {
        name: "keyword-twice",
        on: |k| FLAGS.iter().any(|(paths, _, _)| paths.iter().any(|p| on::at(k, p))),
        test: keyword_twice,
        fix: "give each keyword once",
    },
];

/// The element's own value of `attr` as text (its classes aside).
fn own_text<'m>(at: &At<'_, 'm>, attr: &str) -> Option<&'m str> {
    at.e.node.attr(at.kind().attr_index(attr)?).and_then(Value::as_str)
}

/// A texture's `gridlayout`: at most 12 characters, one per square of `gridsize`.
fn gridlayout(at: &At<'_, '_>) -> Option<Found> {
    let layout = own_text(at, "gridlayout")?;
    if layout.len() > 12 {
        return found("gridlayout", "attribute 'gridlayout' may have at most 12 characters");
    }
    let size = at.floats("gridsize").unwrap_or_default();
    let squares = size.first().copied().unwrap_or(1.0) * size.get(1).copied().unwrap_or(1.0);
    (layout.len() as f64 != squares)
        .then(|| found("gridlayout", "gridlayout length must match gridsize"))?
}

/// A keyword given twice in a list of keywords, before any keyword MuJoCo does not
/// know (which it refuses as such first).
fn keyword_twice(at: &At<'_, '_>) -> Option<Found> {
    let kind = at.kind();
    let (_, attr, keywords) =
        FLAGS.iter().find(|(paths, _, _)| paths.iter().any(|p| on::at(kind, p)))?;
    let text = own_text(at, attr)?;
    let mut seen: Vec<&str> = Vec::new();
    for word in text.split_ascii_whitespace() {
        if seen.contains(&word) {
            return found(attr, format!("duplicate keyword: '{word}'"));
        }
        if !keywords.contains(&word) {
            return None;
        }
        seen.push(word);
    }
    None
}

/// An `input` as MuJoCo 4.0.0's reader takes it (`actuator_spec::parse_input`): an
/// unknown token is "invalid keyword", tokens out of canonical order are refused; a
/// repeat is `keyword-twice`'s.
fn input_tokens(at: &At<'_, '_>) -> Option<Found> {
    match parse_input(own_text(at, "input")?) {
        Err(BadInput::Unknown(word)) => found("input", format!("invalid keyword: '{word}'")),
        Err(BadInput::OutOfOrder) => found(
            "input",
            "inputs must be listed in canonical order [pos, vel, ff, voltage, pressure]",
        ),
        Ok(_) | Err(BadInput::Twice) => None,
    }
}

#[cfg(test)]
mod tests {
    /// The repeat check's input tokens are the parser's.
    #[test]
    fn the_input_tokens_are_the_parser_s() {
        let parser: Vec<&str> =
            crate::model::check::actuator_spec::INPUT_TOKENS.iter().map(|(t, _)| *t).collect();
        assert_eq!(super::INPUTS, parser.as_slice());
    }

    use super::super::tests::assert_pairs;

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn what_mujoco_s_reader_refuses_of_one_element_is_found() {
        let custom = |c: &str| format!("<mujoco><custom>{c}</custom></mujoco>");
        let acts = |a: &str| {
            format!(
                r#"<mujoco><worldbody><body><joint name="j"/><joint name="b" type="ball"/><geom size="1"/></body></worldbody><actuator>{a}</actuator></mujoco>"#
            )
        };
        let pairs = [
            (
                "actuator-input-tokens",
                vec![
                    (acts(r#"<general joint="j" input="vel pos"/>"#), acts(r#"<general joint="j" input="pressure"/>"#)),
                    (acts(r#"<general joint="j" input="bogus"/>"#), acts(r#"<general joint="j" input="quat"/>"#)),
                    (acts(r#"<orientation joint="b" input="vel pos"/>"#), acts(r#"<orientation joint="b" input="pos"/>"#)),
                    (acts(r#"<pid joint="j" input="none pos"/>"#), acts(r#"<pid joint="j" input="pos ff"/>"#)),
                    (acts(r#"<dcmotor joint="j" input="ff vel" motorconst="1" resistance="1"/>"#), acts(r#"<dcmotor joint="j" input="vel ff" motorconst="1" resistance="1"/>"#)),
                ],
            ),
            (
                "text-empty",
                vec![
                    (custom(r#"<text name="t" data=""/>"#), custom(r#"<text name="t" data="x"/>"#)),
                    (custom(r#"<text name="t"/>"#), custom(r#"<text name="t" data=" "/>"#)),
                    (custom(r#"<text name="t">abc</text>"#), custom(r#"<text name="t"><![CDATA[a]]></text>"#)),
                    (
                        custom(r#"<text name="t"><![CDATA[]]></text>"#),
                        custom(r#"<text name="t"> <![CDATA[ ]]> </text>"#),
                    ),
                ],
            ),
            (
                "texture-gridlayout",
                vec![
                    (
                        r#"<mujoco><asset><texture name="t" type="cube" builtin="checker" width="8" height="8" gridsize="4 4" gridlayout="................"/></asset></mujoco>"#.to_string(),
                        r#"<mujoco><asset><texture name="t" type="cube" builtin="checker" width="8" height="8" gridsize="3 4" gridlayout=".U..LFRB.D.."/></asset></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><asset><texture name="t" type="cube" builtin="checker" width="8" height="8" gridsize="1 2" gridlayout="R"/></asset></mujoco>"#.to_string(),
                        r#"<mujoco><asset><texture name="t" type="cube" builtin="checker" width="8" height="8" gridlayout="R"/></asset></mujoco>"#.to_string(),
                    ),
                ],
            ),
            (
                "compiler-eulerseq-length",
                vec![
                    (r#"<mujoco><compiler eulerseq="xy"/></mujoco>"#.to_string(), r#"<mujoco><compiler eulerseq="zyx"/></mujoco>"#.to_string()),
                    (r#"<mujoco><compiler eulerseq="xyzx"/></mujoco>"#.to_string(), r#"<mujoco><compiler eulerseq="XYZ"/></mujoco>"#.to_string()),
                ],
            ),
            (
                "keyword-twice",
                vec![
                    (
                        r#"<mujoco><worldbody><camera output="rgb rgb"/></worldbody></mujoco>"#.to_string(),
                        r#"<mujoco><worldbody><camera output="depth rgb"/></worldbody></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><default><camera output="rgb depth rgb"/></default></mujoco>"#.to_string(),
                        r#"<mujoco><default><camera output="rgb depth"/></default></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><worldbody><body><geom size="1"/><site name="s"/></body></worldbody><sensor><contact site="s" data="found linvel linvel"/></sensor></mujoco>"#.to_string(),
                        r#"<mujoco><worldbody><body><geom size="1"/><site name="s"/></body></worldbody><sensor><contact site="s" data="found  force"/></sensor></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><worldbody><body><geom size="1"/><site name="s"/></body></worldbody><sensor><rangefinder site="s" data="dist dist"/></sensor></mujoco>"#.to_string(),
                        r#"<mujoco><worldbody><body><geom size="1"/><site name="s"/></body></worldbody><sensor><rangefinder site="s" data="dist dir"/></sensor></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><worldbody><body><joint name="j"/><geom size="1"/></body></worldbody><actuator><pid joint="j" input="pos vel pos"/></actuator></mujoco>"#.to_string(),
                        r#"<mujoco><worldbody><body><joint name="j"/><geom size="1"/></body></worldbody><actuator><pid joint="j" input="pos vel"/></actuator></mujoco>"#.to_string(),
                    ),
                    (
                        r#"<mujoco><default><pid input="pos pos"/></default></mujoco>"#.to_string(),
                        r#"<mujoco><default><pid input="pos ff"/></default></mujoco>"#.to_string(),
                    ),
                ],
            ),
        ];
        for (rule, pairs) in &pairs {
            let pairs: Vec<(&str, &str)> =
                pairs.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
            assert_pairs(rule, &pairs);
        }
    }

    /// A keyword MuJoCo does not know before the repeat is refused as such, not as a
    /// repeat (MuJoCo 4.0.0: "invalid keyword"); `none` is a keyword only alone.
    #[test]
    fn an_unknown_keyword_before_a_repeat_is_not_a_repeat() {
        let m = |input: &str| {
            format!(
                r#"<mujoco><worldbody><body><joint name="j"/><geom size="1"/></body></worldbody><actuator><dcmotor joint="j" input="{input}"/></actuator></mujoco>"#
            )
        };
        for input in ["none none", "pos none pos", "bogus pos pos"] {
            assert!(!super::super::tests::refused(&m(input)).contains(&"keyword-twice"), "{input}");
        }
    }
}
