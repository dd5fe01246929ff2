//! Rule *what MuJoCo computes of a body's content* ([`ProblemKind::Refused`]): the
//! checks that need more than one element's values: a geom's mass and density (whether
//! MuJoCo infers its body's inertia from it), an inertial's principal moments after
//! the compiler's bounds, a body's sleep policy (whether it starts a kinematic tree),
//! and a sphere, capsule or cylinder inside a frame scaled unevenly.
//!
//! Each check is narrower than MuJoCo's where MuJoCo's own computation would be
//! needed (a mesh's volume, a shape rotated against its frame's scale, content of a
//! scaled frame): there it says nothing.

use crate::schema::Role;

use super::ProblemKind;
use super::values::orient::ORIENTATIONS;
use super::values::{At, Settings, numbers, on};
use super::walk::{BodyFacts, Event, Rule};
use crate::model::Model;

/// What an open element gives its content.
#[derive(Clone, Copy)]
struct Open {
    /// The body facts of the element (its own for a body, its body's otherwise).
    body: BodyFacts,
    /// The body it is in, or is, has an `<inertial>` (MuJoCo's explicit inertial).
    explicit_inertial: bool,
    /// It is, or is inside, a frame with a `scale` or `massscale`.
    scaled: bool,
    /// The product of the scales of the frames it is inside (or is), per axis.
    scale: [f64; 3],
    /// No element since the scale became uneven rotates its content.
    aligned: bool,
    /// How many frames it is inside (or is) whose own scale is uneven.
    uneven_frames: usize,
}

impl Open {
    const ROOT: Open = Open {
        body: BodyFacts::WORLD,
        explicit_inertial: false,
        scaled: false,
        scale: [1.0; 3],
        aligned: true,
        uneven_frames: 0,
    };
}

/// The rule: the open elements' facts, and the model's settings.
pub(super) struct Bodies {
    settings: Settings,
    open: Vec<Open>,
}

impl Bodies {
    /// The rule for `model` as written (its merged settings).
    pub(super) fn new(model: &Model) -> Bodies {
        Bodies { settings: Settings::of(model), open: Vec::new() }
    }
}

/// A finding of check `rule` on `attribute`.
fn refused(
    rule: &'static str,
    attribute: Option<&'static str>,
    mujoco: &str,
    fix: &'static str,
) -> ProblemKind {
    ProblemKind::Refused { rule, attribute, mujoco: mujoco.into(), fix }
}

/// Whether the element gives itself a rotation (any orientation attribute of its
/// own other than the identity quaternion).
fn rotates(at: &At<'_, '_>) -> bool {
    ORIENTATIONS.iter().any(|a| match at.own(a).and_then(numbers) {
        Some(q) if *a == "quat" => q != [1.0, 0.0, 0.0, 0.0],
        Some(_) => true,
        None => false,
    })
}

/// Whether `s`'s largest number is more than 5% above its smallest (MuJoCo 4.0.0
/// lets shapes through up to about 3.6%).
fn uneven(s: &[f64; 3]) -> bool {
    let (lo, hi) =
        (s.iter().copied().fold(f64::INFINITY, f64::min), s.iter().copied().fold(0.0, f64::max));
    hi > lo * 1.05
}

impl<'m> Rule<'m> for Bodies {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let parent = self.open.last().copied().unwrap_or(Open::ROOT);
        let at = At { e, settings: &self.settings };
        let k = e.node.kind();
        let mut me = Open { body: e.body, ..parent };
        if e.is_body {
            me.explicit_inertial = e.node.children().iter().any(|c| c.kind().is(Role::Inertial));
            sleep(&at, &parent, out);
        }
        if on::frame(k) && (at.has("scale") || at.has("massscale")) {
            me.scaled = true;
        }
        if on::frame(k) || e.is_body || k.is(Role::Replicate) || k.is(Role::Attach) {
            let own = at.floats("scale").filter(|_| on::frame(k)).unwrap_or(vec![1.0]);
            let s = |i: usize| own.get(i).or(own.first()).copied().unwrap_or(1.0);
            me.scale = [parent.scale[0] * s(0), parent.scale[1] * s(1), parent.scale[2] * s(2)];
            me.uneven_frames += usize::from(uneven(&[s(0), s(1), s(2)]));
            // A frame's scale applies in its own axes: its own rotation, or one with
            // no uneven scale above, turns nothing against an uneven scale.
            me.aligned = parent.uneven_frames == 0 || (parent.aligned && !rotates(&at));
        }
        if on::geom(k) {
            geom_mass(&at, &parent, out);
            scaled_shape(&at, &parent, out);
        }
        if on::inertial(k) && !parent.scaled {
            triangle(&at, out);
        }
        self.open.push(me);
    }

    fn leave(&mut self, _: &Event<'m>, _: &mut Vec<ProblemKind>) {
        self.open.pop();
    }
}

/// `sleep policy only allowed for movable root bodies`: a sleep policy other than
/// `auto` on a body that does not start a kinematic tree (it has no joints, or a body
/// above it moves), static bodies included where the compiler fuses them.
fn sleep(at: &At<'_, '_>, parent: &Open, out: &mut Vec<ProblemKind>) {
    let Some(policy) = at.str("sleep") else { return };
    let body = at.e.body;
    let root = body.moves && !parent.body.welded_to_moving;
    if policy == "auto" || root {
        return;
    }
    out.push(refused(
        "body-sleep-policy",
        Some("sleep"),
        "sleep policy only allowed for movable root bodies",
        "set sleep only on a body with joints whose parent does not move",
    ));
}

/// A primitive geom's volume as MuJoCo computes it, where its sizes are its own (not
/// set by `fromto` or a mesh) and its inertia is its volume's (not its shell's).
fn volume(at: &At<'_, '_>) -> Option<f64> {
    if at.has("mesh") || at.has("fromto") || at.str("shellinertia") == Some("true") {
        return None;
    }
    let s = at.floats("size").unwrap_or_default();
    let v = |i: usize| s.get(i).copied().unwrap_or(0.0);
    let pi = std::f64::consts::PI;
    Some(match at.str("type").unwrap_or("sphere") {
        "sphere" => 4.0 / 3.0 * pi * v(0).powi(3),
        "capsule" => pi * v(0) * v(0) * (4.0 / 3.0 * v(0) + 2.0 * v(1)),
        "cylinder" => pi * v(0) * v(0) * 2.0 * v(1),
        "ellipsoid" => 4.0 / 3.0 * pi * v(0) * v(1) * v(2),
        "box" => 8.0 * v(0) * v(1) * v(2),
        _ => return None,
    })
}

/// `mass, inertia or density are negative in geom`: a geom of a body (not the world)
/// whose mass MuJoCo infers (the body has no `<inertial>`, or the compiler's
/// `inertiafromgeom` is `true`; its group in `inertiagrouprange`) with a negative
/// density its mass does not replace (no mass, or a mass over no volume), or a
/// negative mass over a volume.
fn geom_mass(at: &At<'_, '_>, parent: &Open, out: &mut Vec<ProblemKind>) {
    let s = at.settings;
    let group = at.int("group").unwrap_or(0);
    let infers = !parent.body.world
        && (!parent.explicit_inertial || s.inertiafromgeom == "true")
        && (s.inertiagrouprange[0]..=s.inertiagrouprange[1]).contains(&group);
    if !infers || parent.scaled {
        return;
    }
    let density = at.float("density").unwrap_or(1000.0);
    let negative = match at.float("mass").filter(|m| !m.is_nan()) {
        Some(0.0) => false,
        Some(m) if m < 0.0 => density < 0.0 || volume(at).is_some_and(|v| v > 1e-12),
        // Over no volume MuJoCo keeps the density given.
        Some(_) => density < 0.0 && volume(at).is_some_and(|v| v < 0.9e-14),
        None => density < 0.0,
    };
    if negative {
        out.push(refused(
            "geom-mass-negative",
            Some("mass"),
            "mass, inertia or density are negative in geom",
            "give the geom a positive mass or density",
        ));
    }
}

/// `a sphere can only be scaled uniformly`, `this shape can only be scaled equally
/// across its axis`: a sphere inside one frame scaled unevenly (others even), or in
/// frames whose scales, multiplied, are uneven with nothing rotating content between
/// them; a capsule or cylinder whose scales across its axis differ, with nothing
/// rotating it against them.
fn scaled_shape(at: &At<'_, '_>, parent: &Open, out: &mut Vec<ProblemKind>) {
    let s = parent.scale;
    if !uneven(&s) || at.has("mesh") {
        return;
    }
    let turned = ORIENTATIONS[1..].iter().any(|a| at.has(a))
        || at.floats("quat").is_some_and(|q| q != [1.0, 0.0, 0.0, 0.0])
        || at.has("fromto");
    let aligned = parent.aligned && !turned;
    match at.str("type").unwrap_or("sphere") {
        "sphere" if parent.uneven_frames == 1 || aligned => out.push(refused(
            "geom-scale-sphere",
            None,
            // MuJoCo adds its advice only for a sphere aligned with the scale.
            if aligned {
                "a sphere can only be scaled uniformly; use an ellipsoid instead"
            } else {
                "a sphere can only be scaled uniformly"
            },
            "use an ellipsoid, or scale the frame the same along every axis",
        )),
        "capsule" | "cylinder" if aligned && uneven(&[s[0], s[1], s[1]]) => out.push(refused(
            "geom-scale-axis",
            None,
            "this shape can only be scaled equally across its axis",
            "scale the frame the same along the two axes across the shape's axis",
        )),
        _ => {}
    }
}

/// `inertia must satisfy A + B >= C`: an inertial's principal moments (its
/// `diaginertia`, or its `fullinertia`'s eigenvalues), each raised to the compiler's
/// `boundinertia`, break the triangle inequality, unless the compiler balances them
/// or takes the body's inertia from its geoms.
fn triangle(at: &At<'_, '_>, out: &mut Vec<ProblemKind>) {
    let s = at.settings;
    if s.balanceinertia || s.inertiafromgeom == "true" {
        return;
    }
    let moments = match super::values::inertial::fullinertia(at) {
        Some(full) => {
            let eig = super::values::inertial::eigenvalues(&full);
            // Refused for its eigenvalues already.
            if eig[2] < 1e-14 {
                return;
            }
            eig
        }
        None => {
            let d = at.floats("diaginertia").unwrap_or_default();
            let v = |i: usize| d.get(i).copied().unwrap_or(0.0);
            [v(0), v(1), v(2)]
        }
    };
    // As C++'s std::max(moment, bound): a nan stays.
    let i = moments.map(|m| if m < s.boundinertia { s.boundinertia } else { m });
    if i[0] + i[1] < i[2] || i[0] + i[2] < i[1] || i[1] + i[2] < i[0] {
        out.push(refused(
            "inertia-triangle",
            Some("diaginertia"),
            "inertia must satisfy A + B >= C; use 'balanceinertia' to fix",
            "give principal moments where any two add up to at least the third",
        ));
    }
}

#[cfg(test)]
mod tests {
    use crate::model::Model;
    use crate::model::check::ProblemKind;
    use crate::model::check::tests::kinds_of;

    use super::Bodies;

    /// The names of the checks this rule finds in `xml`.
    fn refused(xml: &str) -> Vec<&'static str> {
        let m = Model::from_xml_str(xml).unwrap_or_else(|e| panic!("{e}: {xml}"));
        kinds_of(&m, Bodies::new(&m))
            .into_iter()
            .filter_map(|k| match k {
                ProblemKind::Refused { rule, .. } => Some(rule),
                _ => None,
            })
            .collect()
    }

    fn assert_pairs(rule: &str, pairs: &[(String, String)]) {
        for (bad, good) in pairs {
            assert_eq!(refused(bad), [rule], "refused: {bad}");
            assert_eq!(refused(good), Vec::<&str>::new(), "compiled: {good}");
        }
    }

    fn world(body: &str) -> String {
        format!("<mujoco><worldbody>{body}</worldbody></mujoco>")
    }

    fn with(head: &str, body: &str) -> String {
        format!("<mujoco>{head}<worldbody>{body}</worldbody></mujoco>")
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_geoms_negative_mass_counts_where_mujoco_infers_inertia() {
        let pairs = [
            (
                world(r#"<body><geom size=".1" mass="-1"/></body>"#),
                world(r#"<geom size=".1" mass="-1"/>"#),
            ),
            (
                world(r#"<body><geom size=".1" density="-1"/></body>"#),
                world(r#"<body><geom size=".1" density="-1" mass="1"/></body>"#),
            ),
            (
                world(r#"<body><geom size="1e-6" mass="-1" density="-1"/></body>"#),
                world(r#"<body><geom size="1e-6" mass="-1"/></body>"#),
            ),
            (
                world(r#"<body><geom size=".1" density="-1" mass="nan"/></body>"#),
                world(r#"<body><geom size=".1" density="-1" mass="0"/></body>"#),
            ),
            (
                world(r#"<body><frame><geom size=".1" mass="-1"/></frame></body>"#),
                world(
                    r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/><geom size=".1" mass="-1"/></body>"#,
                ),
            ),
            (
                with(
                    r#"<compiler inertiafromgeom="true"/>"#,
                    r#"<body><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/><geom size=".1" mass="-1"/></body>"#,
                ),
                with(
                    r#"<compiler inertiagrouprange="1 5"/>"#,
                    r#"<body><geom size=".1" mass="-1"/></body>"#,
                ),
            ),
            (
                with(
                    r#"<default><geom mass="-1"/></default>"#,
                    r#"<body><geom size=".1"/></body>"#,
                ),
                world(r#"<body><geom size=".1" mass="-1" group="6"/></body>"#),
            ),
            (
                world(r#"<body><geom size="1e-5" mass="1" density="-1"/></body>"#),
                world(r#"<body><geom size="1e-3" mass="1" density="-1"/></body>"#),
            ),
            (
                world(r#"<body><geom type="plane" size="1 1 1" density="-1"/></body>"#),
                world(r#"<body><geom type="plane" size="1 1 1" mass="-1"/></body>"#),
            ),
        ];
        assert_pairs("geom-mass-negative", &pairs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn principal_moments_must_satisfy_the_triangle_inequality_after_the_bound() {
        let i = |attrs: &str| format!(r#"<body><inertial pos="0 0 0" mass="1" {attrs}/></body>"#);
        let pairs = [
            (world(&i(r#"diaginertia="1 1 3""#)), world(&i(r#"diaginertia="1 1 2""#))),
            (world(&i(r#"diaginertia="0 0 1e-300""#)), world(&i(r#"diaginertia="1 1 -3""#))),
            (world(&i(r#"diaginertia="-1e-300 1 3""#)), world(&i(r#"diaginertia="1 nan 3""#))),
            (
                world(&i(r#"fullinertia="2 2 2 1 1 1""#)),
                world(&i(r#"fullinertia="2 2 2 0.5 0.5 0""#)),
            ),
            (
                with(r#"<compiler boundinertia="1"/>"#, &i(r#"diaginertia="0 0 3""#)),
                with(r#"<compiler boundinertia="2"/>"#, &i(r#"diaginertia="1 1 3""#)),
            ),
            (
                with(r#"<compiler inertiafromgeom="false"/>"#, &i(r#"diaginertia="3 1 1""#)),
                with(r#"<compiler balanceinertia="true"/>"#, &i(r#"diaginertia="3 1 1""#)),
            ),
        ];
        assert_pairs("inertia-triangle", &pairs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn only_a_body_starting_a_kinematic_tree_takes_a_sleep_policy() {
        let g = r#"<geom size=".1"/>"#;
        let pairs = [
            (
                world(&format!(r#"<body sleep="never">{g}</body>"#)),
                world(&format!(r#"<body sleep="never"><freejoint/>{g}</body>"#)),
            ),
            (
                world(&format!(
                    r#"<body><joint/>{g}<body sleep="never"><joint/>{g}</body></body>"#
                )),
                world(&format!(r#"<body>{g}<body sleep="never"><joint/>{g}</body></body>"#)),
            ),
            (
                with(
                    r#"<compiler fusestatic="true"/>"#,
                    &format!(r#"<body sleep="never">{g}</body>"#),
                ),
                world(&format!(r#"<body sleep="auto">{g}</body>"#)),
            ),
            (
                world(&format!(r#"<body mocap="true" sleep="never">{g}</body>"#)),
                world(&format!(
                    r#"<frame><body sleep="init"><frame><joint/></frame>{g}</body></frame>"#
                )),
            ),
        ];
        assert_pairs("body-sleep-policy", &pairs);
    }

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn spheres_capsules_and_cylinders_take_only_even_scales() {
        let f = |scale: &str, inner: &str| {
            world(&format!(r#"<frame scale="{scale}" scaling="geometry">{inner}</frame>"#))
        };
        let pairs = [
            (
                f("1 2 1", r#"<geom size=".1"/>"#),
                f("1 2 1", r#"<geom type="ellipsoid" size=".1 .1 .1"/>"#),
            ),
            (
                f("1 1.1 1", r#"<body><geom size=".1"/></body>"#),
                f("1 1.01 1", r#"<geom size=".1"/>"#),
            ),
            (
                world(
                    r#"<frame scale="1 2 1" scaling="geometry"><frame scale="2 1 1" scaling="geometry"><geom size=".1"/></frame></frame>"#,
                ),
                world(
                    r#"<frame scale="1 2 1" scaling="geometry"><frame scale="1 0.5 1" scaling="geometry"><geom size=".1"/></frame></frame>"#,
                ),
            ),
        ];
        assert_pairs("geom-scale-sphere", &pairs);
        // A sphere is scaled unevenly however it or its frames turn; a frame's own
        // rotation does not turn its content against its own scale.
        let turned = |scale: &str, frame: &str, inner: &str| {
            world(&format!(r#"<frame scale="{scale}" scaling="geometry" {frame}>{inner}</frame>"#))
        };
        let pairs = [
            (
                turned("1 1 2", r#"euler="90 0 0""#, r#"<geom size=".1" euler="10 20 30"/>"#),
                turned("1 1 2", r#"euler="90 0 0""#, r#"<geom type="capsule" size=".1 .2"/>"#),
            ),
            (
                turned(
                    "1 2 1",
                    r#"euler="0 0 90""#,
                    r#"<body euler="0 0 30"><geom size=".1"/></body>"#,
                ),
                turned(
                    "1 1 2",
                    "",
                    r#"<body euler="0 0 30"><geom type="capsule" size=".1 .2"/></body>"#,
                ),
            ),
        ];
        assert_pairs("geom-scale-sphere", &pairs);
        let pairs = [
            (
                f("1 2 1", r#"<geom type="capsule" size=".1 .2"/>"#),
                f("2 2 1", r#"<geom type="capsule" size=".1 .2"/>"#),
            ),
            (
                f("1 2 1", r#"<geom type="cylinder" size=".1 .2" quat="1 0 0 0"/>"#),
                f("1 1 2", r#"<geom type="cylinder" size=".1 .2"/>"#),
            ),
        ];
        assert_pairs("geom-scale-axis", &pairs);
        let pairs = [(
            turned("1 2 1", r#"euler="90 0 0""#, r#"<geom type="capsule" size=".1 .2"/>"#),
            turned("2", r#"euler="90 0 0""#, r#"<geom type="capsule" size=".1 .2"/>"#),
        )];
        assert_pairs("geom-scale-axis", &pairs);
    }
}
