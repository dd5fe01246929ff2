//! Work that grows with the input grows about linearly (issue 19 item 9): each test
//! is sized so that the linear work takes about a second in a debug build, where the
//! quadratic work it replaced would take minutes (the numbers are in each test). The
//! bound on the comparisons one suggestion makes is counted in `src/suggest.rs`.

use mjcf::{Model, Namespace, ProblemKind, WriteOptions};

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

/// A model whose site `s` lies under `n` nested `open`...`close` elements, inside two
/// bodies that set child classes: `far` (outermost) and `near`, whose site defaults
/// place a site at `9 9 9` and `1 2 3`.
fn site_under(n: usize, open: &str, close: &str) -> Model {
    let mut xml = String::from(
        r#"<mujoco model="deep"><default><default class="far"><site pos="9 9 9"/></default>
           <default class="near"><site pos="1 2 3"/></default></default>
           <worldbody><body name="top" childclass="far"><body name="mid" childclass="near">"#,
    );
    xml.push_str(&open.repeat(n));
    xml.push_str(r#"<site name="s"/>"#);
    xml.push_str(&close.repeat(n));
    xml.push_str("</body></body></worldbody></mujoco>");
    Model::from_xml_str(&xml).unwrap()
}

/// Attaching at a site under 100,000 nested `<frame>`s, bodies or `<replicate>`s, in
/// the model itself or in a model attached to it: the class in force for the site
/// (which places the frame where MuJoCo places the site) is found in one walk down
/// the site's path. Each ancestor was looked up from the root (O(depth²): 1.6 s at
/// 10,000 nested frames and 11 s at 20,000 in a debug build; this test did not end
/// within 90 s).
#[test]
fn attach_at_a_site_under_100_000_nested_frames_bodies_or_replicates_is_linear() {
    const N: usize = 100_000;
    let robot = Model::new("robot");
    for (open, close) in [
        ("<frame>", "</frame>"),
        ("<body>", "</body>"),
        (r#"<replicate count="1">"#, "</replicate>"),
    ] {
        let deep = site_under(N, open, close);
        let site = deep.find(Namespace::Site, "s").unwrap();
        let (placed, a) = deep.attach(&site, &robot).unwrap();
        // The nearest child class places it.
        assert_eq!(placed.floats(a.frame(), "pos").unwrap(), [1.0, 2.0, 3.0], "{open}");
        // The same site, seen through an attachment.
        let (outer, _) = Model::new("outer").attach_to_world(&deep).unwrap();
        let site = outer.find(Namespace::Site, "deep/s").unwrap();
        let (placed, a) = outer.attach(&site, &robot).unwrap();
        assert_eq!(placed.floats(a.frame(), "pos").unwrap(), [1.0, 2.0, 3.0], "{open}");
        assert_eq!(placed.get(a.frame()).unwrap().full_name().as_deref(), Some("deep/robot/"));
    }
}

/// A site `N` attachments deep (`m{N-1}` holds `m{N-2}`, ..., `m0` holds `leaf`, whose
/// worldbody holds the site): it is found by its scoped name, named, listed among its
/// parent's children and attached at, each in time linear in the levels (debug build,
/// 20,000 levels: about 0.2 s each). Finding hashed the rest of the name at every
/// level as a possible literal name, and naming or listing made an instance per
/// level, each copying its parent's frame list and prefix and scanning the prefix
/// for characters to escape: quadratic (this test took 120 s, 3.5 s now).
#[test]
fn a_site_20_000_attachments_deep_is_found_named_and_attached_at_in_linear_time() {
    const N: usize = 20_000;
    let mut m = Model::from_xml_str(
        r#"<mujoco model="leaf"><worldbody><site name="s" pos="1 2 3"/></worldbody></mujoco>"#,
    )
    .unwrap();
    for i in 0..N {
        m = Model::new(&format!("m{i}")).attach_to_world(&m).unwrap().0;
    }
    // Relative to the outermost model, `m{N-1}`.
    let scoped: String = (0..N - 1).rev().map(|i| format!("m{i}/")).collect::<String>() + "leaf/s";
    let site = m.find(Namespace::Site, &scoped).unwrap();
    let view = m.get(&site).unwrap();
    assert_eq!(view.full_name().as_deref(), Some(scoped.as_str()));
    assert_eq!(view.scope(), scoped.strip_suffix("/s").unwrap());
    let siblings: Vec<_> =
        view.parent().unwrap().children().filter_map(|c| c.full_name()).collect();
    assert_eq!(siblings, std::slice::from_ref(&scoped));
    let (placed, a) = m.attach(&site, &Model::new("robot")).unwrap();
    assert_eq!(placed.floats(a.frame(), "pos").unwrap(), [1.0, 2.0, 3.0]);
    let frame = placed.get(a.frame()).unwrap().full_name().unwrap();
    assert_eq!(frame, scoped.replace("leaf/s", "leaf/robot/"));
}
