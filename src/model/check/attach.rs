//! Rule *an `<attach>` attaches what MuJoCo can* ([`ProblemKind::Refused`]): MuJoCo's
//! own `<attach>` (of an asset model's body or frame, or of this model's: a
//! self-attach), as MuJoCo 4.0.0's XML reader and `mjs_attach` refuse it: a
//! self-attach that names nothing, a name the attached copy would take already taken
//! (the element before the `<attach>` is refused as such; one after it as a repeated
//! name), a body or frame the part lacks, and a key of the part longer than the part;
//! and an asset `<model>` whose file MuJoCo's XML reader refuses (MuJoCo reads it
//! whether or not an `<attach>` takes from it).

use crate::model::Model;
use crate::model::pose::floats;
use crate::model::tree::Node;
use crate::schema::{Namespace, Role};
use crate::value::{Reference, Value};

use super::ProblemKind;
use super::expansion::{attached_part, named_by_expansion, part_file};
use super::values::Values;
use super::walk::{Event, Rule, run};

/// The rule.
pub(super) struct Attach;

/// A finding of this rule: `rule`, MuJoCo's `mujoco`, `fix`.
fn refused(
    rule: &'static str,
    attribute: &'static str,
    mujoco: String,
    fix: &'static str,
) -> ProblemKind {
    ProblemKind::Refused { rule, attribute: Some(attribute), mujoco, fix }
}

/// The name a reference holds: as written, or its element's.
fn name_of<'m>(m: &'m Model, v: &'m Value) -> Option<&'m str> {
    match v {
        Value::Reference(Reference::Name(n)) => Some(n.as_str()),
        Value::Reference(Reference::Element(id)) => m.node_by_id(*id)?.identifier(),
        v => v.as_str(),
    }
}

impl<'m> Rule<'m> for Attach {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let (m, node) = (e.model, e.node);
        let kind = node.kind();
        if kind.is(Role::AssetModel) {
            if let Some(part) = part_file(node) {
                let mut rules: Vec<Box<dyn Rule<'_> + '_>> = vec![Box::new(Values::reader(&part))];
                out.extend(run(&part, &mut rules).into_iter().map(|p| p.kind));
            }
            return;
        }
        if !kind.is(Role::Attach) {
            return;
        }
        let attr = |name: &str| kind.attr_index(name).and_then(|i| node.attr(i));
        let prefix = attr("prefix").and_then(Value::as_str).unwrap_or("");
        // What is attached: a body, else a frame (MuJoCo's schema refuses both).
        let child = match (attr("body"), attr("frame")) {
            (Some(b), _) => name_of(m, b).map(|n| (Namespace::Body, "body", n)),
            (None, Some(f)) => name_of(m, f).map(|n| (Namespace::Frame, "frame", n)),
            (None, None) => None,
        };
        let Some(model) = attr("model") else {
            let Some((ns, attribute, name)) = child else {
                out.push(ProblemKind::Refused {
                    rule: "self-attach-nothing",
                    attribute: None,
                    mujoco: "either 'body' or 'frame' attribute must be specified for self-attach"
                        .into(),
                    fix: "name the body or frame of this model to attach",
                });
                return;
            };
            let copy = format!("{prefix}{name}");
            if m.find(ns, &copy).is_some() {
                out.push(refused(
                    "self-attach-name-taken",
                    attribute,
                    format!("cannot self-attach: element {copy} already exists"),
                    "give a prefix that makes the copy's name new",
                ));
            }
            return;
        };
        if let Some((ns, attribute, name)) = child.filter(|c| !c.2.is_empty()) {
            if m.find(ns, &format!("{prefix}{name}")).is_some() {
                out.push(refused(
                    "attach-name-taken",
                    attribute,
                    format!("cannot attach: element {name} already exists with prefix {prefix}"),
                    "give a prefix that makes the attached names new",
                ));
            }
        }
        let Some(part) = attached_part(m, Some(model)) else { return };
        if let Some((ns, attribute, name)) = child {
            let found = part.find(ns, name).is_some()
                || ns == Namespace::Body && name == "world"
                || named_by_expansion(&part, ns, name);
            if !found {
                let asset = name_of(m, model).unwrap_or("");
                out.push(refused(
                    "attach-unknown-child",
                    attribute,
                    format!("could not find {attribute} '{name}' in model asset '{asset}'"),
                    "name a body or frame of the asset model's file",
                ));
            }
        }
        out.extend(long_keys(&part));
    }
}

/// The keys of the part longer than the part (all of it, whatever is attached):
/// MuJoCo refuses them as it attaches ("Keyframe 'k' has invalid qpos size, got 2,
/// should be 1"; a shorter key it pads). Not judged for a part that MuJoCo expands
/// further (an `<attach>`, a composite, a flexcomp of its own): its sizes are not
/// known here.
fn long_keys(part: &Model) -> Vec<ProblemKind> {
    let root = part.node_by_id(part.root().id());
    if root.is_none_or(expands) {
        return Vec::new();
    }
    let sizes = part.layout_sizes();
    let n = sizes.per_inst.get(&0).copied().unwrap_or_default();
    let room = [
        ("qpos", n[0]),
        ("qvel", n[1]),
        ("act", n[2]),
        ("ctrl", n[3]),
        ("mpos", n[4].saturating_mul(3)),
        ("mquat", n[4].saturating_mul(4)),
    ];
    let mut out = Vec::new();
    for (_, key, _) in &sizes.keys {
        let name = key.identifier().unwrap_or("");
        for (attribute, should) in room {
            let Some(got) = floats(key, attribute).map(<[f64]>::len).filter(|n| *n > should) else {
                continue;
            };
            // MuJoCo quotes the name for qpos alone.
            let key = if attribute == "qpos" { format!("'{name}'") } else { name.to_string() };
            out.push(refused(
                "attach-key-length",
                attribute,
                format!(
                    "Keyframe {key} has invalid {attribute} size, got {got}, should be {should}"
                ),
                "shorten the key in the asset model's file to its model's size",
            ));
        }
    }
    out
}

/// Whether `node` holds an element MuJoCo expands (an `<attach>`, a composite, a
/// flexcomp).
fn expands(node: &Node) -> bool {
    matches!(node.kind().role(), Some(Role::Attach | Role::MakesBodies))
        || node.children().iter().any(expands)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ReadOptions;
    use crate::model::check::tests::kinds_of;

    /// The names of the findings of the rule on `xml`, read with the part `part` as
    /// `part.xml`.
    fn found(xml: &str, part: &str) -> Vec<&'static str> {
        let m = ReadOptions::new()
            .asset("part.xml", part.as_bytes().to_vec())
            .read_str(xml)
            .unwrap_or_else(|e| panic!("{e}: {xml}"));
        kinds_of(&m, Attach)
            .into_iter()
            .filter_map(|k| match k {
                ProblemKind::Refused { rule, .. } => Some(rule),
                _ => None,
            })
            .collect()
    }

    const PART: &str = r#"<mujoco><worldbody><frame name="f"><body name="b"><joint name="j"/><geom size=".1"/></body></frame></worldbody></mujoco>"#;

    fn with_part(body: &str) -> String {
        format!(
            r#"<mujoco><asset><model name="part" file="part.xml"/></asset><worldbody>{body}</worldbody></mujoco>"#
        )
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's: the first refused with the rule's
    /// message (or, for a name taken after the `<attach>`, as a repeated name), the
    /// second compiled.
    #[test]
    fn an_attach_is_refused_as_mujoco_refuses_it() {
        let a = r#"<body name="a"><geom size=".1"/></body>"#;
        let w = |body: String| format!("<mujoco><worldbody>{body}</worldbody></mujoco>");
        let cases: Vec<(&str, String, String)> = vec![
            (
                "self-attach-nothing",
                w(format!(r#"{a}<attach prefix="p-"/>"#)),
                w(format!(r#"{a}<attach body="a" prefix="p-"/>"#)),
            ),
            (
                "self-attach-name-taken",
                w(format!(
                    r#"<body name="p-a"><geom size=".1"/></body>{a}<attach body="a" prefix="p-"/>"#
                )),
                w(format!(
                    r#"<body name="q-a"><geom size=".1"/></body>{a}<attach body="a" prefix="p-"/>"#
                )),
            ),
            (
                "self-attach-name-taken",
                w(format!(
                    r#"{a}<attach body="a" prefix="p-"/><body name="p-a"><geom size=".1"/></body>"#
                )),
                w(format!(r#"{a}<attach body="a" prefix="p-"/><frame name="p-a"/>"#)),
            ),
            (
                "self-attach-name-taken",
                w(format!(r#"{a}<attach body="a" prefix=""/>"#)),
                w(format!(r#"{a}<body name="q"><attach body="a" prefix="p-"/></body>"#)),
            ),
            (
                "attach-name-taken",
                with_part(
                    r#"<body name="p-b"><geom size=".1"/></body><attach model="part" body="b" prefix="p-"/>"#,
                ),
                with_part(r#"<frame name="p-b"/><attach model="part" body="b" prefix="p-"/>"#),
            ),
            (
                "attach-name-taken",
                with_part(r#"<attach model="part" frame="f" prefix="p-"/><frame name="p-f"/>"#),
                with_part(r#"<attach model="part" frame="f" prefix="p-"/><body name="p-f"/>"#),
            ),
            (
                "attach-unknown-child",
                with_part(r#"<attach model="part" body="nope" prefix="p-"/>"#),
                with_part(r#"<attach model="part" body="world" prefix="p-"/>"#),
            ),
            (
                "attach-unknown-child",
                with_part(r#"<attach model="part" frame="b" prefix="p-"/>"#),
                with_part(r#"<attach model="part" frame="f" prefix="p-"/>"#),
            ),
        ];
        for (rule, bad, good) in &cases {
            assert_eq!(found(bad, PART), [*rule], "{bad}");
            assert_eq!(found(good, PART), Vec::<&str>::new(), "{good}");
        }
        // A copy a replicate of the part makes is found.
        let replicated = r#"<mujoco><worldbody><replicate count="2" offset="1 0 0"><body name="b"><joint name="j"/><geom size=".1"/></body></replicate></worldbody></mujoco>"#;
        let (bad, good) = (
            with_part(r#"<attach model="part" body="b2" prefix="p-"/>"#),
            with_part(r#"<attach model="part" body="b1" prefix="p-"/>"#),
        );
        assert_eq!(found(&bad, replicated), ["attach-unknown-child"]);
        assert_eq!(found(&good, replicated), Vec::<&str>::new());
    }

    /// MuJoCo 4.0.0 refuses a key of the part longer than the whole part (not just
    /// the body attached), and takes a shorter one.
    #[test]
    fn a_key_of_the_part_longer_than_the_part_is_refused() {
        let part = |key: &str| {
            format!(
                r#"<mujoco><worldbody><body name="b"><joint name="j"/><joint/><geom size=".1"/></body><body name="c"><joint/><geom size=".1"/></body><body name="m" mocap="true"/></worldbody><actuator><motor joint="j"/></actuator><keyframe><key name="k" {key}/></keyframe></mujoco>"#
            )
        };
        let xml = with_part(r#"<attach model="part" body="b" prefix="p-"/>"#);
        for (bad, good) in [
            (r#"qpos="0 0 0 0""#, r#"qpos="0 0 0""#),
            (r#"qvel="0 0 0 0""#, r#"qvel="0""#),
            (r#"act="0""#, r#"act="""#),
            (r#"ctrl="0 0""#, r#"ctrl="0""#),
            (r#"mpos="0 0 0 0 0 0""#, r#"mpos="0 0 0""#),
            (r#"mquat="1 0 0 0 1 0 0 0""#, r#"mquat="1 0 0 0""#),
        ] {
            assert_eq!(found(&xml, &part(bad)), ["attach-key-length"], "{bad}");
            assert_eq!(found(&xml, &part(good)), Vec::<&str>::new(), "{good}");
        }
    }
}
