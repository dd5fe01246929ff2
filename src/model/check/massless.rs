//! Rule *a moving body has mass* ([`ProblemKind::MasslessMovingBody`]).

use crate::model::Model;
use crate::model::tree::Node;
use crate::schema::{Namespace, Role};
use crate::value::{Reference, Value};

use super::ProblemKind;
use super::expansion::attached_part;
use super::walk::{Event, Rule};

/// A body with joints of its own, with no mass of its own nor of bodies welded below
/// it (below it, with no joint between): MuJoCo refuses it ("mass and inertia of
/// moving bodies must be larger than mjMINVAL").
#[derive(Default)]
pub(super) struct MasslessMovingBody {
    /// Per open body: it, or something welded below it, has mass.
    massive: Vec<bool>,
}

/// Whether `node` (of the model `m`) gives the body it is in mass: an inertial with a
/// mass above 0, a geom (MuJoCo gives geoms a density) that does not set its mass to
/// 0, or an `<attach>` whose part brings a body welded to it (attached with no joint)
/// that has mass, its own or welded below it (a part that cannot be read on its own
/// counts as giving mass: what it holds is unknown).
pub(super) fn gives_mass(m: &Model, node: &Node) -> bool {
    let kind = node.kind();
    let mass = || node.attr(kind.attr_index("mass").unwrap_or(0)).and_then(Value::as_float);
    match kind.role() {
        Some(Role::Inertial) => mass().is_some_and(|x| x > 0.0),
        Some(Role::Geom) => mass() != Some(0.0),
        Some(Role::Attach) => attach_gives_mass(m, node),
        _ => false,
    }
}

/// [`gives_mass`] for an `<attach>`: the attached body (its `body`, else the part's
/// worldbody, whose bodies it brings) has mass welded to it.
fn attach_gives_mass(m: &Model, attach: &Node) -> bool {
    let kind = attach.kind();
    let attr = |name: &str| kind.attr_index(name).and_then(|i| attach.attr(i));
    let Some(part) = attached_part(m, attr("model")) else { return true };
    let top = match attr("body") {
        Some(Value::Reference(Reference::Name(n))) => part.find(Namespace::Body, n),
        Some(v) => v.as_str().and_then(|n| part.find(Namespace::Body, n)),
        None => Some(part.worldbody()),
    };
    let Some(top) = top.and_then(|loc| part.node_by_id(loc.id())) else { return true };
    if !top.kind().is(Role::Body) {
        return welded_mass(&part, top);
    }
    // A body that moves on its own (a joint of its own) gives the frame no mass.
    !moves(top) && (top.children().iter().any(|c| gives_mass(&part, c)) || welded_mass(&part, top))
}

/// Whether the body `b` has a joint (or a freejoint) of its own.
fn moves(b: &Node) -> bool {
    b.children().iter().any(|j| matches!(j.kind().role(), Some(Role::Joint | Role::Freejoint)))
}

/// Whether a body welded below `node` (a child body without joints, or one inside a
/// frame, and so on down) has mass of its own.
fn welded_mass(m: &Model, node: &Node) -> bool {
    node.children().iter().any(|c| match c.kind().role() {
        Some(Role::Body) if !moves(c) => {
            c.children().iter().any(|g| gives_mass(m, g)) || welded_mass(m, c)
        }
        Some(Role::Frame) => c.children().iter().any(|g| gives_mass(m, g)) || welded_mass(m, c),
        _ => false,
    })
}

impl<'m> Rule<'m> for MasslessMovingBody {
    fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
        if e.is_body {
            self.massive.push(false);
        } else if gives_mass(e.model, e.node) {
            if let Some(top) = self.massive.last_mut() {
                *top = true;
            }
        }
    }

    fn leave(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if !e.is_body {
            return;
        }
        let massive = self.massive.pop().unwrap_or(true);
        if e.body.moves && !massive {
            out.push(ProblemKind::MasslessMovingBody);
        }
        // Mass below counts for the parent only through a body that does not move on
        // its own (welded to it).
        if massive && !e.body.moves {
            if let Some(top) = self.massive.last_mut() {
                *top = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::model::check::tests::kinds_of;
    use crate::model::check::tests::node;
    use crate::schema::Namespace;

    #[test]
    fn an_inertial_with_mass_and_a_geom_not_of_mass_0_give_mass() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="a"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body>
                 <body name="b"><inertial pos="0 0 0" mass="0" diaginertia="1 1 1"/></body>
                 <geom name="dense" size="1"/><geom name="weightless" size="1" mass="0"/>
                 <site name="s"/>
               </worldbody></mujoco>"#,
        )
        .unwrap();
        let inertial =
            |body: &str| node(&m, Namespace::Body, body).children().iter().next().unwrap();
        assert!(gives_mass(&m, inertial("a")));
        assert!(!gives_mass(&m, inertial("b")));
        assert!(gives_mass(&m, node(&m, Namespace::Geom, "dense")));
        assert!(!gives_mass(&m, node(&m, Namespace::Geom, "weightless")));
        assert!(!gives_mass(&m, node(&m, Namespace::Site, "s")));
    }

    #[test]
    fn only_a_moving_body_without_mass_of_its_own_or_welded_below_is_massless() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="bare"><joint/></body>
                 <body name="welded"><joint/><body><geom size="1"/></body></body>
                 <body name="jointed_below"><joint/><body><joint/><geom size="1"/></body></body>
                 <body name="still"/>
               </worldbody></mujoco>"#,
        )
        .unwrap();
        let found = kinds_of(&m, MasslessMovingBody::default());
        assert_eq!(found, [ProblemKind::MasslessMovingBody, ProblemKind::MasslessMovingBody]);
    }
}
