//! Every reference kind MuJoCo declares, through every edit that can break a
//! reference: for each reference attribute of MuJoCo's own schema
//! (`schema/mjcf-schema-facts.tsv`, derived from MuJoCo's `src/xml/mjcf.schema`: the
//! `ref<…>` attributes of every element outside default classes), a model where an
//! element of that kind refers to a target, and the target
//! - renamed: the reference follows (the written model names the new name);
//! - removed with its referrers ([`Referrers::Cascade`]): nothing dangles;
//! - taken in a part ([`Model::part`] of the body holding every target): nothing
//!   dangles;
//! - attached twice (the whole model, at two sites of a host): every copy's
//!   reference names its own copy's target;
//!
//! and MuJoCo 4.0.0 compiles the original and every result. The kinds that need what
//! this test cannot build (a plugin library, skin or flex data, MuJoCo's own `<attach>`
//! of another model) are listed with the reason and the test that covers them, if any.

use crate::support;

use mjcf::{Attrs, Model, Namespace, ProblemKind, Referrers};
use support::mujoco;

/// The model every case extends: a target of every namespace in the body `base`.
const BASE: &str = r#"<mujoco model="m">
  <default><default class="cls"/></default>
  <asset>
    <texture name="tex" type="2d" builtin="checker" width="8" height="8" rgb1="1 1 1" rgb2="0 0 0"/>
    <material name="mat" texture="tex"/>
    <hfield name="hf" nrow="3" ncol="3" size="1 1 1 0.1"/>
    <mesh name="me" builtin="sphere" params="1"/>
    {asset}
  </asset>
  <worldbody>
    <body name="base">
      <body name="b1" pos="0 0 1">
        <joint name="hinge1" range="-1 1"/>
        <geom name="g1" size=".1"/>
        <site name="s1" pos="0 .1 0"/>
        <body name="b2" pos="0 0 .3">
          <joint name="hinge2" range="-1 1"/>
          <geom name="g2" size=".1"/>
          <geom size=".05" pos="0 0 .1"/>
          <site name="s2" pos=".1 0 0"/>
          <site name="s3" pos="-.1 0 0"/>
          <camera name="cam" resolution="8 8"/>
          {body}
        </body>
        <body name="b3" pos=".3 0 0"><joint name="ball" type="ball"/><geom size=".1"/></body>
      </body>
    </body>
    {world}
  </worldbody>
  <contact>{contact}</contact>
  <equality>{equality}</equality>
  <tendon>
    <fixed name="t1" limited="true" range="-1 1"><joint joint="hinge1" coef="1"/></fixed>
    <fixed name="t2" limited="true" range="-1 1"><joint joint="hinge2" coef="1"/></fixed>
    {tendon}
  </tendon>
  <actuator><motor name="a1" joint="hinge1"/><motor name="a2" joint="hinge2"/>{actuator}</actuator>
  <sensor>{sensor}</sensor>
</mujoco>"#;

/// The kinds not built here, with the reason.
const NOT_BUILT: &[(&str, &str)] = &[
    ("@instance", "a plugin instance needs a plugin library"),
    ("actuator/plugin", "a plugin actuator needs a plugin library"),
    (
        "equality/flex",
        "a flex equality needs a flex (deformables: the refusals catalog's next round)",
    ),
    ("deformable/", "a flex or skin needs vertex data"),
    ("composite/", "a composite's elements are MuJoCo's to make"),
    ("skin/bone@body", "a skin needs vertex data"),
    ("asset/skin@material", "a skin needs vertex data"),
    ("flexcomp@material", "a flexcomp is MuJoCo's to expand"),
    ("attach@", "MuJoCo's <attach> names into another model (tests/check_expansions.rs)"),
];

/// The target each namespace's references name.
fn target(ns: &str, element: &str) -> &'static str {
    match ns {
        "body" => "b2",
        "joint" if matches!(element, "ballquat" | "ballangvel" | "orientation") => "ball",
        "joint" => "hinge2",
        "geom" => "g2",
        "site" => "s2",
        "tendon" => "t2",
        "actuator" => "a2",
        "mesh" => "me",
        "material" => "mat",
        "texture" => "tex",
        "hfield" => "hf",
        "camera" => "cam",
        "default" => "cls",
        other => panic!("no target of namespace {other}"),
    }
}

/// What an actuator of tag `element` needs besides its transmission.
fn actuator_extra(element: &str) -> &'static str {
    match element {
        "dcmotor" => r#"motorconst="1" resistance="1""#,
        "adhesion" | "damper" => r#"ctrlrange="0 1""#,
        // A slider-crank's length barely changes over the joint's range: MuJoCo
        // cannot compute a muscle's length range from it.
        "muscle" => r#"lengthrange=".1 .5""#,
        _ => "",
    }
}

/// The snippet that makes an element `element` (of section or parent `parent`) refer
/// with `attr` to `t`, and the place it goes (`asset`, `body`, `world`, `contact`, ...).
fn referrer(parent: &str, element: &str, attr: &str, t: &str) -> Option<(&'static str, String)> {
    let a = format!(r#"{attr}="{t}""#);
    let in_class = attr == "class" || attr == "childclass";
    Some(match (parent, element) {
        ("(world)body", "body") => ("world", format!(r#"<body {a}><geom size=".05"/></body>"#)),
        ("(world)body", "frame") => ("world", format!(r#"<frame {a}><geom size=".05"/></frame>"#)),
        ("(world)body", "replicate") => (
            "world",
            format!(r#"<replicate count="2" offset=".2 0 0" {a}><geom size=".05"/></replicate>"#),
        ),
        ("(world)body", "joint") => ("body", format!("<joint {a}/>")),
        ("(world)body", "geom") => match attr {
            "hfield" => ("world", format!(r#"<geom type="hfield" {a}/>"#)),
            "mesh" => ("world", format!(r#"<geom type="mesh" {a}/>"#)),
            _ => ("world", format!(r#"<geom size=".05" {a}/>"#)),
        },
        ("(world)body", "site") => ("world", format!("<site {a}/>")),
        ("(world)body", "camera" | "light") if attr == "target" => {
            ("world", format!(r#"<{element} mode="targetbody" {a}/>"#))
        }
        ("(world)body", "camera" | "light") => ("world", format!("<{element} {a}/>")),
        ("asset", "mesh") => {
            ("asset", format!(r#"<mesh name="me9" builtin="sphere" params="1" {a}/>"#))
        }
        ("asset", "material") => ("asset", format!(r#"<material name="mat9" {a}/>"#)),
        ("material", "layer") => {
            ("asset", format!(r#"<material name="mat9"><layer role="rgb" {a}/></material>"#))
        }
        ("contact", "pair") if in_class => {
            ("contact", format!(r#"<pair geom1="g1" geom2="g2" {a}/>"#))
        }
        ("contact", "pair" | "exclude") => {
            let (kind, other) = if element == "pair" { ("geom", "g1") } else { ("body", "b1") };
            let first = attr.ends_with('1');
            let (x, y) = if first { (t, other) } else { (other, t) };
            ("contact", format!(r#"<{element} {kind}1="{x}" {kind}2="{y}"/>"#))
        }
        ("equality", "connect" | "weld") => {
            let anchor = if element == "connect" { r#"anchor="0 0 0""# } else { "" };
            let attrs = match attr {
                "body1" => format!("{a} {anchor}"),
                "body2" => format!(r#"body1="b1" {a} {anchor}"#),
                "site1" => format!(r#"{a} site2="s1""#),
                "site2" => format!(r#"site1="s1" {a}"#),
                _ => format!(r#"body1="b2" {anchor} {a}"#),
            };
            ("equality", format!("<{element} {attrs}/>"))
        }
        ("equality", "joint" | "tendon") => {
            let kind = element;
            match attr {
                "class" => ("equality", format!(r#"<{kind} {kind}1="{}" {a}/>"#, target(kind, ""))),
                a1 if a1.ends_with('1') => ("equality", format!(r#"<{kind} {a}/>"#)),
                _ => {
                    let first = if kind == "joint" { "hinge1" } else { "t1" };
                    ("equality", format!(r#"<{kind} {kind}1="{first}" {a}/>"#))
                }
            }
        }
        ("tendon", "fixed") => {
            ("tendon", format!(r#"<fixed {a}><joint joint="hinge2" coef="1"/></fixed>"#))
        }
        ("tendon", "spatial") => {
            ("tendon", format!(r#"<spatial {a}><site site="s1"/><site site="s2"/></spatial>"#))
        }
        ("fixed", "joint") => ("tendon", format!(r#"<fixed><joint {a} coef="1"/></fixed>"#)),
        ("spatial", "site") => {
            ("tendon", format!(r#"<spatial><site {a}/><site site="s1"/></spatial>"#))
        }
        ("spatial", "geom") => {
            let geom = if attr == "geom" { a.clone() } else { format!(r#"geom="g2" {a}"#) };
            (
                "tendon",
                format!(r#"<spatial><site site="s1"/><geom {geom}/><site site="s3"/></spatial>"#),
            )
        }
        ("actuator", "plugin") => return None,
        ("actuator", _) => {
            let extra = actuator_extra(element);
            let transmission = match attr {
                "class" if element == "adhesion" => r#"body="b2""#.to_string(),
                "class" if element == "orientation" => r#"joint="ball""#.to_string(),
                "class" => r#"joint="hinge2""#.to_string(),
                "refsite" => format!(r#"site="s1" {a}"#),
                "cranksite" => format!(r#"{a} slidersite="s1" cranklength=".1""#),
                "slidersite" => format!(r#"cranksite="s1" {a} cranklength=".1""#),
                "site" if element == "orientation" => format!(r#"{a} refsite="s1""#),
                _ => a.clone(),
            };
            let class = if attr == "class" { a.clone() } else { String::new() };
            ("actuator", format!("<{element} {transmission} {class} {extra}/>"))
        }
        ("sensor", _) => {
            let pair = |kind: &str, other: &str| {
                if attr.ends_with('1') {
                    format!(r#"{a} {kind}2="{other}""#)
                } else {
                    format!(r#"{kind}1="{other}" {a}"#)
                }
            };
            let attrs = match (element, attr) {
                ("camprojection", "site") => format!(r#"{a} camera="cam""#),
                ("camprojection", "camera") => format!(r#"site="s1" {a}"#),
                ("insidesite", _) => format!(r#"{a} objtype="body" objname="b1""#),
                ("tactile", "geom") => format!(r#"{a} mesh="me""#),
                ("tactile", "mesh") => format!(r#"geom="g2" {a}"#),
                (_, "geom1" | "geom2") => pair("geom", "g1"),
                (_, "body1" | "body2") => pair("body", "b1"),
                (_, "subtree1" | "subtree2") => pair("subtree", "b1"),
                _ => a.clone(),
            };
            ("sensor", format!("<{element} {attrs}/>"))
        }
        _ => return None,
    })
}

/// `BASE` with `snippet` at `place`.
fn model_text(place: &str, snippet: &str) -> String {
    let mut text = BASE.to_string();
    for p in ["asset", "body", "world", "contact", "equality", "tendon", "actuator", "sensor"] {
        text = text.replace(&format!("{{{p}}}"), if p == place { snippet } else { "" });
    }
    text
}

/// The namespace of a facts type name.
fn namespace(ns: &str) -> Namespace {
    Namespace::from_name(ns).unwrap_or_else(|| panic!("namespace {ns}"))
}

/// What dangles in `m`, as `check()` says it.
fn dangling(m: &Model) -> Vec<String> {
    m.check()
        .into_iter()
        .filter(|p| {
            matches!(
                p.kind,
                ProblemKind::DanglingReference { .. }
                    | ProblemKind::RemovedReference { .. }
                    | ProblemKind::MissingRequired { .. }
            )
        })
        .map(|p| p.to_string())
        .collect()
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn every_reference_kind_survives_rename_remove_part_and_attach_twice() {
    let mujoco = mujoco();
    let facts = include_str!("../../schema/mjcf-schema-facts.tsv");
    let mut kinds = std::collections::BTreeSet::new();
    for line in facts.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let [parent, element, attr, ty, ..] = f[..] else { continue };
        let Some(ns) = ty.strip_prefix("ref<").and_then(|t| t.strip_suffix('>')) else { continue };
        if parent != "default" {
            kinds.insert((parent, element, attr, ns));
        }
    }
    assert!(kinds.len() > 190, "{} reference kinds", kinds.len());
    let (mut judged, mut skipped, mut failures) = (0, Vec::new(), Vec::new());
    for (parent, element, attr, ns) in kinds {
        let label = format!("{parent}/{element}@{attr}");
        if let Some((_, why)) = NOT_BUILT.iter().find(|(k, _)| label.contains(k)) {
            skipped.push(format!("{label}: {why}"));
            continue;
        }
        let t = target(ns, element);
        let Some((place, snippet)) = referrer(parent, element, attr, t) else {
            failures.push(format!("{label}: no referrer built"));
            continue;
        };
        if let Err(e) = judge(&mujoco, &label, ns, t, &model_text(place, &snippet)) {
            failures.push(format!("{label}: {e}\n  {snippet}"));
        }
        judged += 1;
    }
    eprintln!("{judged} reference kinds judged; not built:\n  {}", skipped.join("\n  "));
    assert!(failures.is_empty(), "{} failed:\n{}", failures.len(), failures.join("\n"));
    assert!(judged >= 150, "{judged} judged");
}

/// The four edits of one reference kind, each judged.
fn judge(
    mujoco: &mjcf_mujoco::MuJoCo,
    label: &str,
    ns: &str,
    t: &str,
    text: &str,
) -> Result<(), String> {
    let compile = |m: &Model, what: &str| {
        mujoco.compile(m).map(|_| ()).map_err(|e| format!("{what}: MuJoCo refuses: {e}"))
    };
    let no_dangling = |m: &Model, what: &str| match dangling(m).as_slice() {
        [] => Ok(()),
        d => Err(format!("{what}: {}", d.join("; "))),
    };
    let m = Model::from_xml_str(text).map_err(|e| format!("read: {e}"))?;
    compile(&m, "original")?;
    let loc = m.find(namespace(ns), t).ok_or("no target")?;
    // Renamed (`name`, a class's `class`): the reference follows.
    let kind = m.element(&loc).ok_or("no target")?.kind();
    let id = kind.identifier().map(|i| kind.attr(i).name).ok_or("no identifier")?;
    let renamed = m
        .set(&loc, Attrs::new().set(id, format!("{t}_renamed")))
        .map_err(|e| format!("rename: {e}"))?;
    let xml = renamed.to_xml_string().map_err(|e| e.to_string())?;
    let attr = label.rsplit('@').next().unwrap_or_default();
    if !xml.contains(&format!(r#"{attr}="{t}_renamed""#)) {
        return Err(format!("rename: no {attr}=\"{t}_renamed\" in\n{xml}"));
    }
    no_dangling(&renamed, "rename")?;
    compile(&renamed, "rename")?;
    // Removed with what refers to it.
    let removed = m.remove_with(&loc, Referrers::Cascade).map_err(|e| format!("remove: {e}"))?;
    no_dangling(&removed.model, "remove")?;
    compile(&removed.model, "remove")?;
    // Taken in a part.
    let part = m.part("base").map_err(|e| format!("part: {e}"))?;
    no_dangling(&part.model, "part")?;
    compile(&part.model, "part")?;
    // Attached twice.
    let mut host = Model::new("host");
    let w = host.worldbody();
    let s0 = host.add_mut(&w, mjcf::element!("site", name = "s0")).map_err(|e| e.to_string())?;
    let s1 = host
        .add_mut(&w, mjcf::element!("site", name = "s1", pos = [2.0, 0.0, 0.0]))
        .map_err(|e| e.to_string())?;
    host.attach_mut(&s0, &m).map_err(|e| format!("attach: {e}"))?;
    host.attach_mut(&s1, &m).map_err(|e| format!("attach twice: {e}"))?;
    no_dangling(&host, "attach twice")?;
    let xml = host.to_xml_string().map_err(|e| e.to_string())?;
    for scope in ["m/", "m_1/"] {
        if ns != "default" && !xml.contains(&format!(r#"{attr}="{scope}{t}""#)) {
            return Err(format!("attach twice: no {attr}=\"{scope}{t}\""));
        }
    }
    compile(&host, "attach twice")
}
