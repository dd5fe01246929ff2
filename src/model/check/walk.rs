//! The one walk [`Model::check`] makes: it enters and leaves every element of the
//! composed model once, works out where each element lands once MuJoCo compiles the
//! written model (which body it is in, whether that body is at the world's top
//! level, moves, or hangs below a moving body), and feeds every rule the same
//! [`Event`]s. A rule reports problems of the element entered or left; the walk names
//! the element (locator and full name) and says each distinct problem once.

use std::collections::HashSet;

use crate::model::cursor::{Step, Walk};
use crate::model::frame::frame_keeps_bodies_top_level;
use crate::model::layout::ClassesInForce;
use crate::model::tree::{ElementId, Node};
use crate::model::{Loc, Model};
use crate::schema::Role;

use super::{Problem, ProblemKind, problem_path};

/// What a rule is told of an element the walk enters or leaves.
#[derive(Clone, Copy)]
pub(crate) struct Event<'m> {
    /// The element's own model (the outermost, or an attached one).
    pub(crate) model: &'m Model,
    /// Its instance in the walk (0: the outermost model; one per attachment).
    pub(crate) inst: usize,
    /// The element.
    pub(crate) node: &'m Node,
    /// The default class in force for it (its own, a `childclass` above, its
    /// model's root class).
    pub(crate) class: Option<ElementId>,
    /// It is written as a body: a `<body>`, or an attachment frame written as one
    /// (an attachment frame written as MuJoCo's `<frame>` is not).
    pub(crate) is_body: bool,
    /// The body it is in (itself, for a body; `<frame>`s and `<replicate>`s are
    /// transparent), as MuJoCo compiles it; the world's facts outside any body.
    pub(crate) body: BodyFacts,
}

/// Where a body (or the world) lands in the compiled model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct BodyFacts {
    /// It is the world.
    pub(crate) world: bool,
    /// Its parent is the world (`<frame>`s, `<replicate>`s and attachment frames
    /// written as `<frame>` between them are transparent): a top-level body.
    pub(crate) top_level: bool,
    /// It has joints of its own (its children, or inside its `<frame>`s).
    pub(crate) moves: bool,
    /// It or a body above it moves: it is not welded to the world (MuJoCo's
    /// "static": weld id 0).
    pub(crate) welded_to_moving: bool,
}

impl BodyFacts {
    /// The world's facts.
    pub(crate) const WORLD: BodyFacts =
        BodyFacts { world: true, top_level: false, moves: false, welded_to_moving: false };

    /// A body's facts, its own joints `moves`, its parent's `parent`, `top_level`
    /// whether its parent's content is at the world's top level.
    pub(crate) fn child(parent: &BodyFacts, top_level: bool, moves: bool) -> BodyFacts {
        BodyFacts {
            world: false,
            top_level,
            moves,
            welded_to_moving: moves || parent.welded_to_moving,
        }
    }

    /// Not welded to the world: it, or a body above it, moves.
    pub(crate) fn is_static(&self) -> bool {
        !self.welded_to_moving
    }
}

/// A rule of [`Model::check`]: fed every element entered and left, it says what
/// MuJoCo refuses of that element. Rules keep what they need between events.
pub(crate) trait Rule<'m> {
    /// The walk enters `e`'s element; problems pushed are that element's.
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let _ = (e, out);
    }

    /// The walk leaves `e`'s element (after its content); problems pushed are that
    /// element's.
    fn leave(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let _ = (e, out);
    }
}

/// An element open in the walk: its event, and what its content inherits.
struct Open<'m> {
    event: Event<'m>,
    /// Its content is at MuJoCo's world level (the outermost worldbody; a `<frame>`,
    /// `<replicate>` or attachment frame written as `<frame>` there).
    world_level: bool,
    /// The writer's notion for its children: they are written in the world (the
    /// outermost worldbody, a `<frame>` there): an attachment frame among them is
    /// written as `<frame>` if it keeps its bodies top level.
    writer_world: bool,
}

/// Whether `node`, a body or an attachment frame written as a body, has joints of its
/// own: among its children or inside its `<frame>`s.
fn has_own_joints(node: &Node) -> bool {
    node.children().iter().any(|c| match c.kind().role() {
        Some(Role::Joint | Role::Freejoint) => true,
        Some(Role::Frame) if c.attached().is_none() => has_own_joints(c),
        _ => false,
    })
}

/// Walks `model` once, feeding each rule of `rules` every element, and gathers what
/// they find, each distinct problem once.
pub(crate) fn run<'m>(model: &'m Model, rules: &mut [Box<dyn Rule<'m> + 'm>]) -> Vec<Problem> {
    let name = model.name();
    let mut problems = Vec::new();
    let mut seen = HashSet::new();
    let mut walk = Walk::new(model);
    let mut open: Vec<Open<'m>> = Vec::new();
    let mut classes = ClassesInForce::default();
    let mut found = Vec::new();
    while let Some(step) = walk.next() {
        let (item, event) = match step {
            Step::Enter(item) => {
                let m = walk.insts.list[item.inst].model;
                let class = classes.enter(m, item.inst, item.node);
                let o = enter(m, item.inst, item.node, class, open.last());
                let event = o.event;
                open.push(o);
                for r in rules.iter_mut() {
                    r.enter(&event, &mut found);
                }
                (item, event)
            }
            Step::Leave(item) => {
                classes.leave();
                let Some(o) = open.pop() else { continue };
                for r in rules.iter_mut() {
                    r.leave(&o.event, &mut found);
                }
                (item, o.event)
            }
        };
        if found.is_empty() {
            continue;
        }
        let loc = Loc::scoped(walk.insts.list[item.inst].frames.clone(), event.node.id(), name);
        let path = problem_path(&walk.insts, &item);
        for kind in found.drain(..) {
            let p = Problem { loc: loc.clone(), path: path.clone(), kind };
            if seen.insert(p.to_string()) {
                problems.push(p);
            }
        }
    }
    problems
}

/// The open element for `node` (of model `m`, instance `inst`, class `class`),
/// entered inside `parent`.
fn enter<'m>(
    m: &'m Model,
    inst: usize,
    node: &'m Node,
    class: Option<ElementId>,
    parent: Option<&Open<'m>>,
) -> Open<'m> {
    let role = node.kind().role();
    let (parent_world, parent_writer_world, parent_body) = parent
        .map_or((false, false, BodyFacts::WORLD), |p| {
            (p.world_level, p.writer_world, p.event.body)
        });
    let attached = node.attached().is_some();
    // The writer's tag: an attachment frame in the world over free bodies is `<frame>`.
    let as_frame = attached && parent_writer_world && frame_keeps_bodies_top_level(node);
    let is_body = role == Some(Role::Body) && !as_frame;
    let outermost_world = inst == 0 && role == Some(Role::Worldbody);
    let transparent = as_frame || matches!(role, Some(Role::Frame | Role::Replicate));
    let world_level = outermost_world || parent_world && transparent;
    let writer_world =
        outermost_world || parent_writer_world && (as_frame || role == Some(Role::Frame));
    let body = if is_body {
        BodyFacts::child(&parent_body, parent_world, has_own_joints(node))
    } else {
        parent_body
    };
    let event = Event { model: m, inst, node, class, is_body, body };
    Open { event, world_level, writer_world }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The facts of the body each joint or geom named in `names` is in.
    fn facts_of(m: &Model) -> Vec<(String, bool, BodyFacts)> {
        struct Spy<'s>(&'s mut Vec<(String, bool, BodyFacts)>);
        impl<'m> Rule<'m> for Spy<'_> {
            fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
                if let Some(n) = e.node.identifier() {
                    self.0.push((n.to_string(), e.is_body, e.body));
                }
            }
        }
        let mut out = Vec::new();
        {
            let mut rules: Vec<Box<dyn Rule<'_> + '_>> = vec![Box::new(Spy(&mut out))];
            run(m, &mut rules);
        }
        out
    }

    #[test]
    fn the_walk_tells_top_level_moving_and_static_bodies_through_frames_and_replicates() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <frame><body name="top"><body name="inner"><geom name="g" size="1"/></body></body></frame>
                 <replicate count="2" offset="1 0 0"><body name="rep"/></replicate>
                 <body name="mover"><frame><joint name="j"/></frame><geom size="1"/>
                   <body name="still"><geom name="h" size="1"/></body></body>
               </worldbody></mujoco>"#,
        )
        .unwrap();
        let facts: std::collections::HashMap<String, (bool, BodyFacts)> =
            facts_of(&m).into_iter().map(|(n, b, f)| (n, (b, f))).collect();
        let top = facts["top"].1;
        assert!(facts["top"].0 && top.top_level && !top.moves && top.is_static());
        assert!(!facts["inner"].1.top_level);
        assert_eq!(facts["g"], (false, facts["inner"].1));
        assert!(facts["rep"].1.top_level);
        let mover = facts["mover"].1;
        assert!(mover.moves && !mover.is_static());
        let still = facts["still"].1;
        assert!(!still.moves && !still.is_static() && !still.top_level);
        assert_eq!(facts["j"].1, mover);
    }
}
