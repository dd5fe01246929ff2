//! Rule *a moving body has mass* ([`ProblemKind::MasslessMovingBody`]).

use crate::model::tree::Node;
use crate::schema::Role;
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// A body with joints of its own, with no mass of its own nor of bodies welded below
/// it (below it, with no joint between): MuJoCo refuses it ("mass and inertia of
/// moving bodies must be larger than mjMINVAL").
#[derive(Default)]
pub(super) struct MasslessMovingBody {
    /// Per open body: it, or something welded below it, has mass.
    massive: Vec<bool>,
}

/// Whether `node` gives the body it is in mass: an inertial with a mass above 0, or
/// a geom (MuJoCo gives geoms a density) that does not set its mass to 0.
pub(super) fn gives_mass(node: &Node) -> bool {
    let kind = node.kind();
    let mass = || node.attr(kind.attr_index("mass").unwrap_or(0)).and_then(Value::as_float);
    match kind.role() {
        Some(Role::Inertial) => mass().is_some_and(|x| x > 0.0),
        Some(Role::Geom) => mass() != Some(0.0),
        _ => false,
    }
}

impl<'m> Rule<'m> for MasslessMovingBody {
    fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
        if e.is_body {
            self.massive.push(false);
        } else if gives_mass(e.node) {
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
    use crate::schema::Namespace;

    fn node<'m>(m: &'m Model, ns: Namespace, name: &str) -> &'m Node {
        let loc = m.find(ns, name).expect("the element exists");
        m.node_by_id(loc.id()).expect("its node")
    }

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
        assert!(gives_mass(inertial("a")));
        assert!(!gives_mass(inertial("b")));
        assert!(gives_mass(node(&m, Namespace::Geom, "dense")));
        assert!(!gives_mass(node(&m, Namespace::Geom, "weightless")));
        assert!(!gives_mass(node(&m, Namespace::Site, "s")));
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
