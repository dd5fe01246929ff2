//! MuJoCo judges the refusal pairs of `mjcf-mujoco/refusals` (each `case` of
//! `catalog.tsv`: `refused.xml`, which MuJoCo 4.0.0 refuses with that row's message,
//! and `twin.xml`, a near twin it compiles), and the pairs measure the crate: on the
//! refused model, does mjcf's reader refuse it or `check()` report a problem (with
//! MuJoCo's message, or of the kind that stands for it), and on the twin does neither
//! object (a false alarm).

use crate::support;

use std::path::{Path, PathBuf};

use mjcf::{ErrorKind, Model, ProblemKind};
use mjcf_mujoco::Error;
use support::mujoco;

/// The folder of the catalog and its cases.
fn refusals_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("refusals")
}

/// The catalog's pairs: (message, case), a row naming any number of cases.
fn pairs() -> Vec<(String, String)> {
    let text = std::fs::read_to_string(refusals_dir().join("catalog.tsv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (message, case) = (col("message"), col("case"));
    lines
        .map(|l| l.split('\t').collect::<Vec<_>>())
        .filter(|f| f.len() > case)
        .flat_map(|f| {
            let m = f[message].to_string();
            f[case].split_whitespace().map(move |c| (m.clone(), c.to_string())).collect::<Vec<_>>()
        })
        .collect()
}

/// Whether the crate's `text` holds `message` as [`holds`] says, MuJoCo's numeric ids
/// (`(id = %d)`, `id = %d, `) left out: the crate names elements by name, and the
/// numbers MuJoCo gives them in compiling are not its to know.
fn crate_holds(text: &str, message: &str) -> bool {
    holds(text, &message.replace(" (id = %d)", "").replace("id = %d, ", ""))
}

/// Whether `text` holds `message`'s pieces between its printf specifiers, in order.
fn holds(text: &str, message: &str) -> bool {
    let mut rest = text;
    for piece in printf_pieces(message) {
        match rest.find(piece.as_str()) {
            Some(i) => rest = &rest[i + piece.len()..],
            None => return false,
        }
    }
    true
}

/// A printf format's literal pieces (`size %d must be positive` → `size `,
/// ` must be positive`).
fn printf_pieces(format: &str) -> Vec<String> {
    let mut pieces = vec![String::new()];
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            pieces.last_mut().unwrap().push(c);
            continue;
        }
        while chars.next_if(|c| c.is_ascii_digit() || *c == '-' || *c == '.').is_some() {}
        chars.next();
        pieces.push(String::new());
    }
    pieces.retain(|p| !p.is_empty());
    pieces
}

/// MuJoCo's message each kind of [`ProblemKind`] stands for (its docs name it).
fn kind_message(kind: &ProblemKind) -> &'static [&'static str] {
    match kind {
        ProblemKind::DanglingReference { .. } => &[
            "not found",
            "unknown",
            "unrecognized name",
            "unrecognized object",
            "missing transmission target",
            "could not find",
        ],
        ProblemKind::MissingRequired { .. } | ProblemKind::RemovedReference { .. } => {
            &["required attribute missing", "missing transmission target"]
        }
        ProblemKind::MasslessMovingBody => {
            &["mass and inertia of moving bodies must be larger than mjMINVAL"]
        }
        ProblemKind::TooManyDofs { .. } => &["more than 6 dofs in body"],
        ProblemKind::RotationAfterBall => &["ball followed by rotation in body"],
        ProblemKind::KeyLength { .. } => &[
            "invalid qpos size",
            "invalid qvel size",
            "invalid act size",
            "invalid ctrl size",
            "invalid mpos size",
            "invalid mquat size",
        ],
        ProblemKind::ArrayTooShort { .. } => &["does not have enough data"],
        ProblemKind::ArrayNotMultiple { .. } => &["must be a multiple of"],
        ProblemKind::FreeJointNotTopLevel => &["free joint can only be used on top level"],
        ProblemKind::PlaneInMovingBody => &["plane only allowed in static bodies"],
        ProblemKind::MocapNotFixedChildOfWorld => &["is not a fixed child of world"],
        _ => &[],
    }
}

/// MuJoCo's messages each kind of the reader's [`ErrorKind`] stands for.
fn read_error_message(kind: &ErrorKind) -> &'static [&'static str] {
    match kind {
        ErrorKind::InvalidChild { .. } => {
            &["unrecognized element", "World body cannot have", "cannot be a direct child"]
        }
        ErrorKind::UnknownAttribute { .. } => {
            &["unrecognized attribute", "World body cannot have attributes"]
        }
        ErrorKind::DuplicateChild(_) => &["unique element"],
        ErrorKind::DuplicateIdentifier { .. } => &["repeated name", "repeated default class name"],
        ErrorKind::MissingRequired { .. } => &["required attribute missing"],
        ErrorKind::RootClassRenamed(_) => &["top-level default class 'main' cannot be renamed"],
        ErrorKind::InvalidValue { .. } => &[
            "bad format",
            "has too much data",
            "does not have enough data",
            "invalid keyword",
            "number is too large",
        ],
        ErrorKind::UnknownName { .. } => &["could not find", "not found", "unknown"],
        _ => &[],
    }
}

/// What the crate says of the model at `path`: the reader's error, or `check()`'s
/// problems (only what MuJoCo refuses: advice is `advice()`'s), with the messages
/// each stands for.
fn crate_objections(path: &Path) -> Vec<(String, Vec<&'static str>)> {
    match Model::from_path(path) {
        Err(e) => vec![(e.to_string(), read_error_message(e.kind()).to_vec())],
        Ok(m) => {
            m.check().into_iter().map(|p| (p.to_string(), kind_message(&p.kind).to_vec())).collect()
        }
    }
}

/// The pairs "known" (the crate objects to the refused model with MuJoCo's class of
/// problem) when this was written: the floor, which can only go up.
const KNOWN_FLOOR: usize = 337;

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn every_refusal_pair_is_judged_by_mujoco_and_measures_the_crate() {
    let mujoco = mujoco();
    let pairs = pairs();
    assert!(pairs.len() >= 300, "{} pairs", pairs.len());
    let (mut known, mut other, mut silent) = (Vec::new(), Vec::new(), Vec::new());
    let (mut misjudged, mut false_alarms, mut twice) = (Vec::new(), Vec::new(), Vec::new());
    let mut known_messages = std::collections::BTreeSet::new();
    let messages: std::collections::BTreeSet<&str> =
        pairs.iter().map(|(m, _)| m.as_str()).collect();
    for (message, case) in &pairs {
        let dir = refusals_dir().join("cases").join(case);
        let (refused, twin) = (dir.join("refused.xml"), dir.join("twin.xml"));
        match mujoco.compile_path(&refused) {
            Err(Error::Compile(e)) if holds(&e.message, message) => {}
            Err(e) => misjudged.push(format!("{case}: refused with another message: {e}")),
            Ok(_) => misjudged.push(format!("{case}: MuJoCo compiles refused.xml")),
        }
        if let Err(e) = mujoco.compile_path(&twin) {
            misjudged.push(format!("{case}: MuJoCo refuses twin.xml: {e}"));
        }
        let objections = crate_objections(&refused);
        let right = objections.iter().any(|(text, stands_for)| {
            crate_holds(text, message) || stands_for.iter().any(|m| message.contains(m))
        });
        match (objections.is_empty(), right) {
            (true, _) => silent.push(case.as_str()),
            (false, true) => {
                known.push(case.as_str());
                known_messages.insert(message.as_str());
            }
            (false, false) => other.push(format!("{case}: {}", objections[0].0)),
        }
        // Each distinct problem said once: no two rules report one MuJoCo message.
        if let Ok(m) = Model::from_path(&refused) {
            let mut said = std::collections::HashSet::new();
            for p in m.check() {
                if let ProblemKind::Refused { mujoco, .. } = &p.kind {
                    if !said.insert((p.loc.clone(), mujoco.clone())) {
                        twice.push(format!("{case}: {p}"));
                    }
                }
            }
        }
        let alarms = crate_objections(&twin);
        if !alarms.is_empty() {
            false_alarms.push(format!("{case}: {}", alarms[0].0));
        }
    }
    eprintln!(
        "{} pairs of {} messages: {} known (of {} messages), {} objected to with another message, {} silent, {} false alarms on twins",
        pairs.len(),
        messages.len(),
        known.len(),
        known_messages.len(),
        other.len(),
        silent.len(),
        false_alarms.len()
    );
    eprintln!("objected to with another message:\n  {}", other.join("\n  "));
    eprintln!("silent: {}", silent.join(" "));
    assert!(misjudged.is_empty(), "{}", misjudged.join("\n"));
    assert!(false_alarms.is_empty(), "false alarms:\n{}", false_alarms.join("\n"));
    assert!(twice.is_empty(), "said twice:\n{}", twice.join("\n"));
    assert!(known.len() >= KNOWN_FLOOR, "{} known, the floor is {KNOWN_FLOOR}", known.len());
}

#[test]
fn a_message_is_held_when_its_pieces_appear_in_order() {
    assert_eq!(
        printf_pieces("size %d must be positive in geom"),
        ["size ", " must be positive in geom"]
    );
    assert!(holds(
        "Error: size 1 must be positive in geom\nElement",
        "size %d must be positive in geom"
    ));
    assert!(!holds("must be positive in geom size 1", "size %d must be positive in geom"));
    assert!(holds("repeated name 'g' in geom", "repeated name '%s' in %s"));
    assert!(crate_holds(
        "tendon 't': path cannot be empty",
        "tendon '%s' (id = %d): path cannot be empty"
    ));
    assert!(crate_holds(
        "fovy too large in camera 'c' (value = 180)",
        "fovy too large in camera '%s' (id = %d, value = %d)"
    ));
}
