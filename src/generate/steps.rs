//! Carrying out one [`Step`] on a model: one function per step kind, each adding
//! its element under what it picks (named with the builder's prefix and a suffix
//! when taken), or `None` when the step does not apply or would leave more than the
//! allowed problems.

use crate::model::{Element, Loc, Model};
use crate::schema::{ElementKind, Namespace, Role};

use super::builder::{Builder, add_named};
use super::palette::{direction, palette_of, real, with_extras};
use super::pick::{
    any, body_parents, joint_fits, named, not_frame, not_plane, scalar_joint, two, valid, view,
};
use super::recipe::{
    ActuatorKind, AttrDraw, DefaultTag, EqualityKind, GeomRecipe, JointKind, MAX_DEPTH, ObjKind,
    Palette, Pick, SensorKind, Shape, Step, Unit, Word,
};

/// A tetrahedron's vertices, the shape of every generated mesh.
const TETRAHEDRON: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];

/// Where a step runs: the model, its attachment depth, the prefix of the names it
/// adds and how many problems it may leave.
#[derive(Clone, Copy)]
struct At<'a> {
    m: &'a Model,
    depth: u32,
    prefix: &'a str,
    allowed: usize,
    palette: Palette,
}

impl Builder {
    /// Carries out one step on `m`; `None` when it does not apply or would leave
    /// more than `allowed` problems.
    pub(super) fn step(
        &mut self,
        m: &Model,
        step: &Step,
        depth: u32,
        prefix: &str,
        allowed: usize,
    ) -> Option<Model> {
        let allowed = self.allowed(allowed);
        let at = At { m, depth, prefix, allowed, palette: self.palette };
        match step {
            Step::Body { parent, name, pos, geom, free, childclass, extras } => {
                body(at, *parent, *name, pos, geom, *free, *childclass, extras)
            }
            Step::Geom { parent, geom } => geom_step(at, *parent, geom),
            Step::Site { parent, name, pos, extras } => site(at, *parent, *name, pos, extras),
            Step::Joint { body, name, kind, axis, range, class, extras } => {
                joint(at, *body, *name, *kind, axis, *range, *class, extras)
            }
            Step::Camera { parent, name, extras } => {
                camera_or_light(at, "camera", *parent, *name, extras)
            }
            Step::Light { parent, name, extras } => {
                camera_or_light(at, "light", *parent, *name, extras)
            }
            Step::Class { parent, name, defaults } => class(at, *parent, *name, defaults),
            Step::Material { name, extras } => material(at, *name, extras),
            Step::Mesh { name, scale } => mesh(at, *name, scale),
            Step::Actuator { kind, name, joint, extras } => {
                actuator(at, *kind, *name, *joint, extras)
            }
            Step::Sensor { kind, name, target, extras } => {
                sensor(at, *kind, *name, *target, extras)
            }
            Step::Tendon { name, joints } => tendon(at, *name, joints),
            Step::Equality { kind, name, first, second } => {
                equality(at, *kind, *name, *first, *second)
            }
            Step::Exclude { first, second } => {
                let bodies = named(m, Namespace::Body, not_frame);
                contact(at, ["exclude", "body1", "body2"], &bodies, *first, *second)
            }
            Step::Pair { first, second } => {
                let geoms = named(m, Namespace::Geom, not_plane);
                contact(at, ["pair", "geom1", "geom2"], &geoms, *first, *second)
            }
            Step::Frame { parent, pos, euler } => frame_step(at, *parent, pos, euler),
            Step::Attach { at: place, child, frame } => {
                if depth + 1 > MAX_DEPTH {
                    return None;
                }
                let child = self.model(child, depth + 1, "");
                self.children.push(child.clone());
                self.attach(m, *place, &child, frame, depth, prefix, allowed)
            }
            Step::AttachAgain { at: place, child, frame } => {
                let child = child.of(&self.children)?.clone();
                self.attach(m, *place, &child, frame, depth, prefix, allowed)
            }
        }
    }
}

/// Adds a body under a picked body (or the worldbody), with a geom (and a freejoint
/// when `free` and directly in the outermost worldbody).
#[allow(clippy::too_many_arguments)] // the fields of `Step::Body`, beside where it runs
fn body(
    at: At<'_>,
    parent: Pick,
    name: Option<Word>,
    pos: &[Unit; 3],
    geom: &GeomRecipe,
    free: bool,
    childclass: Option<Pick>,
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, depth, prefix, allowed, palette: pal } = at;
    let p = parent.of(&body_parents(m))?.clone();
    let kind = view(m, &p)?.1.child_of_role(Role::Body)?;
    let gkind = kind.child_of_role(Role::Geom)?;
    // Directly in the worldbody of the outermost model: an attached model's
    // worldbody is a frame in the composed model (the wide palette frees bodies of
    // attached models too).
    let top = p == m.worldbody() && (depth == 0 || pal == Palette::Wide);
    let scoped = p.is_scoped();
    let class = if scoped {
        None
    } else {
        childclass.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned())
    };
    let pos: Vec<f64> = pos.iter().map(|u| real(-1000, 1000, *u)).collect();
    let g = geom_element(m, gkind, geom, (false, scoped, pal), None);
    let make = |n: Option<&str>| {
        let mut el = Element::new("body");
        if let Some(n) = n {
            el = el.attr("name", n);
        }
        el = el.attr("pos", pos.clone());
        let mut taken = vec!["pos"];
        if let Some(c) = &class {
            el = el.attr("childclass", c.as_str());
            taken.push("childclass");
        }
        el = with_extras(el, kind, palette_of("body", false, at.palette), extras, &taken)
            .child(g.clone());
        if free && top { el.child(Element::new("freejoint")) } else { el }
    };
    add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// The geom a recipe describes, as an element of `kind`: its shape and size (a plane
/// only `in_world`, a mesh only where one is named), its class and material (not in
/// an attached model, `scoped`), its palette attributes.
fn geom_element(
    m: &Model,
    kind: ElementKind,
    g: &GeomRecipe,
    (in_world, scoped, pal): (bool, bool, Palette),
    name: Option<&str>,
) -> Element {
    // Simulating: no geom smaller than 0.05 (a light body on a stiff joint diverges).
    let lo = if pal == Palette::Simulates { 50 } else { 20 };
    let size = |n: usize| -> Vec<f64> { g.size[..n].iter().map(|u| real(lo, 300, *u)).collect() };
    let mut el = Element::new("geom");
    let mut taken = vec!["type", "size"];
    let meshes = if scoped { Vec::new() } else { named(m, Namespace::Mesh, any) };
    el = match g.shape {
        Shape::Plane if in_world => el.attr("type", "plane").attr("size", size(3)),
        Shape::Box | Shape::Plane => el.attr("type", "box").attr("size", size(3)),
        Shape::Capsule => el.attr("type", "capsule").attr("size", size(2)),
        Shape::Cylinder => el.attr("type", "cylinder").attr("size", size(2)),
        Shape::Ellipsoid => el.attr("type", "ellipsoid").attr("size", size(3)),
        Shape::Mesh(i) if !meshes.is_empty() => {
            el.attr("type", "mesh").attr("mesh", i.of(&meshes).map_or("", String::as_str))
        }
        Shape::Sphere | Shape::Mesh(_) => el.attr("size", size(1)),
    };
    if !scoped {
        if let Some(c) = g.class.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned()) {
            el = el.attr("class", c);
            taken.push("class");
        }
        if let Some(mat) =
            g.material.and_then(|c| c.of(&named(m, Namespace::Material, any)).cloned())
        {
            el = el.attr("material", mat);
            taken.push("material");
        }
    }
    if let Some(n) = name {
        el = el.attr("name", n);
    }
    with_extras(el, kind, palette_of("geom", false, pal), &g.extras, &taken)
}

/// Adds a geom to a picked body (a plane only directly in the outermost worldbody).
fn geom_step(at: At<'_>, parent: Pick, geom: &GeomRecipe) -> Option<Model> {
    let At { m, depth, prefix, allowed, palette: pal } = at;
    let p = parent.of(&body_parents(m))?.clone();
    let kind = view(m, &p)?.1.child_of_role(Role::Geom)?;
    // A plane in the outermost worldbody (the wide palette: in an attached one too).
    let top = p == m.worldbody() && (depth == 0 || pal == Palette::Wide);
    let make = |n: Option<&str>| geom_element(m, kind, geom, (top, p.is_scoped(), pal), n);
    add_named(m, &p, make, geom.name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a site to a picked body.
fn site(
    at: At<'_>,
    parent: Pick,
    name: Option<Word>,
    pos: &[Unit; 3],
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let p = parent.of(&body_parents(m))?.clone();
    let kind = view(m, &p)?.1.child_of_role(Role::Site)?;
    let pos: Vec<f64> = pos.iter().map(|u| real(-1000, 1000, *u)).collect();
    let make = |n: Option<&str>| {
        let el = Element::new("site").attr("pos", pos.clone());
        let el = with_extras(el, kind, palette_of("site", false, at.palette), extras, &["pos"]);
        if let Some(n) = n { el.attr("name", n) } else { el }
    };
    add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a joint to a picked body where it fits (no freejoint, at most 6 degrees of
/// freedom).
#[allow(clippy::too_many_arguments)] // the fields of `Step::Joint`, beside where it runs
fn joint(
    at: At<'_>,
    body: Pick,
    name: Option<Word>,
    jk: JointKind,
    axis: &[Unit; 3],
    range: Option<[Unit; 2]>,
    class: Option<Pick>,
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, prefix, allowed, palette: pal, .. } = at;
    // Bodies where the joint fits: no freejoint, at most 6 degrees of freedom (not
    // a `<frame>`).
    let bodies: Vec<Loc> = body_parents(m)
        .into_iter()
        .skip(1)
        .filter(|b| view(m, b).is_some_and(|v| v.1.is(Role::Body)) && joint_fits(m, b, jk))
        .collect();
    let b = body.of(&bodies)?.clone();
    let kind = view(m, &b)?.1.child_of_role(Role::Joint)?;
    let class = if b.is_scoped() {
        None
    } else {
        class.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned())
    };
    let make = |n: Option<&str>| {
        let mut el = Element::new("joint").attr("type", jk.keyword());
        let mut taken = vec!["type", "axis", "range"];
        if pal == Palette::Simulates {
            // Simulating: every joint has armature and damping (the palette's draws
            // may raise them).
            el = el.attr("armature", 0.1).attr("damping", 1.0);
        }
        if jk != JointKind::Ball {
            el = el.attr("axis", direction(*axis));
            if let Some([lo, hi]) = range {
                el = el.attr("range", [real(-1500, -100, lo), real(100, 1500, hi)]);
            }
        }
        if let Some(c) = &class {
            el = el.attr("class", c.as_str());
            taken.push("class");
        }
        if let Some(n) = n {
            el = el.attr("name", n);
        }
        with_extras(el, kind, palette_of("joint", false, at.palette), extras, &taken)
    };
    add_named(m, &b, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a camera or a light (`tag`) to a picked body.
fn camera_or_light(
    at: At<'_>,
    tag: &'static str,
    parent: Pick,
    name: Option<Word>,
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let p = parent.of(&body_parents(m))?.clone();
    let kind = view(m, &p)?.1.child(tag)?;
    let make = |n: Option<&str>| {
        let el =
            with_extras(Element::new(tag), kind, palette_of(tag, false, at.palette), extras, &[]);
        if let Some(n) = n { el.attr("name", n) } else { el }
    };
    add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a default class under the root class or a named class of this model, with
/// geom, joint and site defaults from the palettes.
fn class(
    at: At<'_>,
    parent: Pick,
    name: Word,
    defaults: &[(DefaultTag, AttrDraw)],
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let mut parents = vec![m.default_class()];
    parents.extend(
        m.find_all(Namespace::Default)
            .into_iter()
            .filter(|l| !l.is_scoped() && m.element(l).is_some_and(|e| e.identifier().is_some())),
    );
    let p = parent.of(&parents)?.clone();
    let kind = view(m, &p)?.1.child_of_role(Role::DefaultClass)?;
    let make = |n: Option<&str>| {
        let mut el = Element::new("default").attr("class", n.unwrap_or("x"));
        for t in [DefaultTag::Geom, DefaultTag::Joint, DefaultTag::Site] {
            let draws: Vec<AttrDraw> =
                defaults.iter().filter(|(d, _)| *d == t).map(|(_, a)| *a).collect();
            let Some(ck) = kind.child(t.tag()) else { continue };
            if !draws.is_empty() {
                let child = Element::new(t.tag());
                el = el.child(with_extras(
                    child,
                    ck,
                    palette_of(t.tag(), true, at.palette),
                    &draws,
                    &[],
                ));
            }
        }
        el
    };
    add_named(m, &p, make, Some(name.text()), prefix, allowed).map(|r| r.0)
}

/// Adds a material asset.
fn material(at: At<'_>, name: Word, extras: &[AttrDraw]) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let asset = m.asset();
    let kind = view(m, &asset)?.1.child_of_role(Role::Material)?;
    let make = |n: Option<&str>| {
        let el = Element::new("material").attr("name", n.unwrap_or("x"));
        with_extras(el, kind, palette_of("material", false, at.palette), extras, &[])
    };
    add_named(m, &asset, make, Some(name.text()), prefix, allowed).map(|r| r.0)
}

/// Adds a mesh asset: a scaled tetrahedron.
fn mesh(at: At<'_>, name: Word, scale: &[Unit; 3]) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let asset = m.asset();
    let scale: Vec<f64> = scale.iter().map(|u| real(50, 300, *u)).collect();
    let make = |n: Option<&str>| {
        Element::new("mesh")
            .attr("name", n.unwrap_or("x"))
            .attr("vertex", TETRAHEDRON)
            .attr("scale", scale.clone())
    };
    add_named(m, &asset, make, Some(name.text()), prefix, allowed).map(|r| r.0)
}

/// Adds an actuator on a picked hinge or slide joint.
fn actuator(
    at: At<'_>,
    ak: ActuatorKind,
    name: Option<Word>,
    joint: Pick,
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let joints = named(m, Namespace::Joint, scalar_joint);
    let j = joint.of(&joints)?.clone();
    let section = m.actuator();
    let tag = match ak {
        ActuatorKind::Motor => "motor",
        ActuatorKind::Position => "position",
        ActuatorKind::Velocity => "velocity",
    };
    let kind = view(m, &section)?.1.child(tag)?;
    let make = |n: Option<&str>| {
        let el = Element::new(tag).attr("joint", j.as_str());
        let el = with_extras(el, kind, palette_of(tag, false, at.palette), extras, &["joint"]);
        if let Some(n) = n { el.attr("name", n) } else { el }
    };
    add_named(m, &section, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a sensor on a picked joint, site, or body, geom or site (`framepos`).
fn sensor(
    at: At<'_>,
    sk: SensorKind,
    name: Option<Word>,
    target: Pick,
    extras: &[AttrDraw],
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let section = m.sensor();
    let (tag, attrs): (&str, Vec<(&str, String)>) = match sk {
        SensorKind::JointPos | SensorKind::JointVel => {
            let t = if sk == SensorKind::JointPos { "jointpos" } else { "jointvel" };
            let j = target.of(&named(m, Namespace::Joint, scalar_joint))?.clone();
            (t, vec![("joint", j)])
        }
        SensorKind::Touch | SensorKind::Accelerometer | SensorKind::Gyro => {
            let t = match sk {
                SensorKind::Touch => "touch",
                SensorKind::Accelerometer => "accelerometer",
                _ => "gyro",
            };
            (t, vec![("site", target.of(&named(m, Namespace::Site, any))?.clone())])
        }
        SensorKind::FramePos(obj) => {
            let (objtype, names) = match obj {
                ObjKind::Body => ("body", named(m, Namespace::Body, not_frame)),
                ObjKind::Geom => ("geom", named(m, Namespace::Geom, any)),
                ObjKind::Site => ("site", named(m, Namespace::Site, any)),
            };
            let o = target.of(&names)?.clone();
            ("framepos", vec![("objtype", objtype.to_string()), ("objname", o)])
        }
    };
    let kind = view(m, &section)?.1.child(tag)?;
    let make = |n: Option<&str>| {
        let mut el = Element::new(tag);
        for (k, v) in &attrs {
            el = el.attr(k, v.as_str());
        }
        let el = with_extras(el, kind, palette_of(tag, false, at.palette), extras, &[]);
        if let Some(n) = n { el.attr("name", n) } else { el }
    };
    add_named(m, &section, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a fixed tendon over up to four picked hinge or slide joints (each once).
fn tendon(at: At<'_>, name: Option<Word>, joints: &[(Pick, Unit)]) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let all = named(m, Namespace::Joint, scalar_joint);
    let mut chosen: Vec<(String, f64)> = Vec::new();
    for (j, c) in joints.iter().take(4) {
        let j = j.of(&all)?;
        if !chosen.iter().any(|(k, _)| k == j) {
            chosen.push((j.clone(), real(100, 2000, *c)));
        }
    }
    if chosen.is_empty() {
        return None;
    }
    let section = m.section("tendon")?;
    let make = |n: Option<&str>| {
        let mut el = Element::new("fixed");
        if let Some(n) = n {
            el = el.attr("name", n);
        }
        for (j, c) in &chosen {
            el = el.child(Element::new("joint").attr("joint", j.as_str()).attr("coef", *c));
        }
        el
    };
    add_named(m, &section, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds an equality between two different picked bodies or hinge/slide joints.
fn equality(
    at: At<'_>,
    ek: EqualityKind,
    name: Option<Word>,
    first: Pick,
    second: Pick,
) -> Option<Model> {
    let At { m, prefix, allowed, .. } = at;
    let section = m.section("equality")?;
    let (tag, a, b, names) = match ek {
        EqualityKind::Connect => {
            ("connect", "body1", "body2", named(m, Namespace::Body, not_frame))
        }
        EqualityKind::Weld => ("weld", "body1", "body2", named(m, Namespace::Body, not_frame)),
        EqualityKind::Joint => {
            ("joint", "joint1", "joint2", named(m, Namespace::Joint, scalar_joint))
        }
    };
    let (x, y) = two(&names, first, second)?;
    let anchor = [real(-100, 100, Unit(first.0)), 0.0, 0.0];
    let make = |n: Option<&str>| {
        let mut el = Element::new(tag).attr(a, x).attr(b, y);
        if ek == EqualityKind::Connect {
            el = el.attr("anchor", anchor);
        }
        if let Some(n) = n { el.attr("name", n) } else { el }
    };
    add_named(m, &section, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
}

/// Adds a contact element `[tag, a, b]` (an `exclude` of two bodies, a `pair` of two
/// geoms) between two different `names`, once per pair either way round.
fn contact(
    at: At<'_>,
    [tag, a, b]: [&'static str; 3],
    names: &[String],
    first: Pick,
    second: Pick,
) -> Option<Model> {
    let At { m, allowed, .. } = at;
    let section = m.section("contact")?;
    let (x, y) = two(names, first, second)?;
    // Each pair once, either way round.
    let exists = m.element(&section)?.children().any(|c| {
        c.tag() == tag
            && matches!((c.string(a), c.string(b)), (Some(p), Some(q)) if (p, q) == (x, y) || (p, q) == (y, x))
    });
    if exists {
        return None;
    }
    let el = Element::new(tag).attr(a, x).attr(b, y);
    let (next, _) = m.add(&section, el).ok()?;
    valid(&next, allowed).then_some(next)
}

/// Adds a MuJoCo `<frame>` under a picked body or `<frame>` (or the worldbody).
fn frame_step(at: At<'_>, parent: Pick, pos: &[Unit; 3], euler: &[Unit; 3]) -> Option<Model> {
    let At { m, allowed, .. } = at;
    let p = parent.of(&body_parents(m))?.clone();
    view(m, &p)?.1.child_of_role(Role::Frame)?;
    let pos: Vec<f64> = pos.iter().map(|u| real(-1000, 1000, *u)).collect();
    let euler: Vec<f64> = euler.iter().map(|u| real(-90_000, 90_000, *u)).collect();
    let (next, _) = m.add(&p, Element::new("frame").attr("pos", pos).attr("euler", euler)).ok()?;
    valid(&next, allowed).then_some(next)
}
