//! Work that grows with the input grows about linearly (issue 19 item 9): each test
//! is sized so that the linear work takes about a second in a debug build, where the
//! quadratic work it replaced would take minutes (the numbers are in each test). The
//! bound on the comparisons one suggestion makes is counted in `src/suggest.rs`.

use mjcf::{Model, ProblemKind, WriteOptions};

/// `check` with 10,000 references that name nothing, from 10,000 unnamed motors, in a
/// model of 10,000 named joints: each suggestion compares its word with a bounded
/// number of names (it compared with all 10,000: 10^8 edit distances), and each
/// problem names its motor as written (an automatic name was counted over the whole
/// model for each: 10,000 · 40,000 elements visited).
#[test]
fn check_with_10_000_dangling_references_is_linear() {
    const N: usize = 10_000;
    let mut xml = String::from("<mujoco model=\"big\"><worldbody>");
    for i in 0..N {
        xml.push_str(&format!(
            r#"<body name="b{i}"><joint name="joint_{i:05}"/><geom size="0.1"/></body>"#
        ));
    }
    xml.push_str("</worldbody><actuator>");
    for i in 0..N {
        // A typo at the start of the name (`jiont`).
        xml.push_str(&format!(r#"<motor joint="jiont_{i:05}"/>"#));
    }
    xml.push_str("</actuator></mujoco>");
    let m = Model::from_xml_str(&xml).unwrap();
    let problems = m.check();
    assert_eq!(problems.len(), N);
    for (i, p) in problems.iter().enumerate() {
        assert_eq!(p.path, format!("//unnamed_actuator_{i}"));
        let ProblemKind::DanglingReference { suggestions, .. } = &p.kind else {
            panic!("{p}");
        };
        assert_eq!(
            suggestions.first().map(|s| s.as_str()),
            Some(format!("joint_{i:05}").as_str()),
            "{p}"
        );
    }
}

/// Composed keyframes for 50,000 key names: each name is found again by a hash (it
/// was looked for among the names so far: 1.25 · 10^9 comparisons).
#[test]
fn merge_keyframes_with_50_000_key_names_is_linear() {
    const N: usize = 50_000;
    let mut xml = String::from(
        r#"<mujoco model="keys"><worldbody><body name="b"><joint name="j"/><geom size="0.1"/></body></worldbody><keyframe>"#,
    );
    for i in 0..N {
        xml.push_str(&format!(r#"<key name="k{i}" qpos="{i}"/>"#));
    }
    xml.push_str("</keyframe></mujoco>");
    let m = Model::from_xml_str(&xml).unwrap();
    let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let out = m.to_xml_string_with(&merged).unwrap();
    assert_eq!(out.matches("<key ").count(), N);
    assert!(out.contains(r#"<key name="k49999" qpos="49999"/>"#), "the last key, in place");
}
