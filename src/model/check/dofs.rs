//! Rules on a body's joints: *at most 6 degrees of freedom per body*
//! ([`ProblemKind::TooManyDofs`]) and *no rotation after a ball joint*
//! ([`ProblemKind::RotationAfterBall`]). A body's joints are its own children and
//! those inside its `<frame>`s, in order; an attachment frame written as a body is a
//! body.

use crate::model::layout::{JointType, joint_type};
use crate::schema::Role;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// The joints of one body, as these rules see them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct BodyJoints {
    /// The degrees of freedom of its joints.
    pub(super) dofs: usize,
    /// One of its joints is a ball joint.
    ball: bool,
    /// A hinge or ball joint follows a ball joint.
    pub(super) rotation_after_ball: bool,
}

impl BodyJoints {
    /// A joint of type `ty` is added after those seen so far.
    pub(super) fn add(&mut self, ty: JointType) {
        self.dofs += ty.nv();
        self.rotation_after_ball |= self.ball && matches!(ty, JointType::Ball | JointType::Hinge);
        self.ball |= ty == JointType::Ball;
    }
}

/// The joints of every open body, innermost last.
#[derive(Default)]
pub(super) struct Joints {
    open: Vec<BodyJoints>,
}

impl Joints {
    /// Gathers `e`'s joint (entered) into its body; when `e` is a body being left,
    /// returns its joints.
    fn step(&mut self, e: &Event<'_>, entering: bool) -> Option<BodyJoints> {
        if e.is_body {
            return if entering {
                self.open.push(BodyJoints::default());
                None
            } else {
                self.open.pop()
            };
        }
        if entering && matches!(e.node.kind().role(), Some(Role::Joint | Role::Freejoint)) {
            if let Some(top) = self.open.last_mut() {
                top.add(joint_type(e.model, e.node, e.class));
            }
        }
        None
    }
}

/// Rule *at most 6 degrees of freedom per body*: MuJoCo refuses more ("more than 6
/// dofs in body").
#[derive(Default)]
pub(super) struct TooManyDofs(Joints);

impl<'m> Rule<'m> for TooManyDofs {
    fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
        self.0.step(e, true);
    }

    fn leave(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if let Some(j) = self.0.step(e, false).filter(|j| j.dofs > 6) {
            out.push(ProblemKind::TooManyDofs { dofs: j.dofs });
        }
    }
}

/// Rule *no rotation after a ball joint*: MuJoCo refuses a hinge or ball joint after a
/// ball joint in one body ("ball followed by rotation in body").
#[derive(Default)]
pub(super) struct RotationAfterBall(Joints);

impl<'m> Rule<'m> for RotationAfterBall {
    fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
        self.0.step(e, true);
    }

    fn leave(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if self.0.step(e, false).is_some_and(|j| j.rotation_after_ball) {
            out.push(ProblemKind::RotationAfterBall);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::model::check::tests::kinds_of;

    #[test]
    fn body_joints_count_degrees_of_freedom_by_joint_type() {
        let mut joints = BodyJoints::default();
        joints.add(JointType::Free);
        assert_eq!(joints.dofs, 6);
        joints.add(JointType::Slide);
        assert_eq!(joints.dofs, 7);
        let mut three = BodyJoints::default();
        for ty in [JointType::Ball, JointType::Slide, JointType::Slide, JointType::Slide] {
            three.add(ty);
        }
        assert_eq!((three.dofs, three.rotation_after_ball), (6, false));
    }

    #[test]
    fn only_a_hinge_or_ball_after_a_ball_is_a_rotation_after_ball() {
        let after_ball = |second: JointType| {
            let mut joints = BodyJoints::default();
            joints.add(JointType::Ball);
            joints.add(second);
            joints.rotation_after_ball
        };
        assert!(after_ball(JointType::Hinge));
        assert!(after_ball(JointType::Ball));
        assert!(!after_ball(JointType::Slide));
        let mut before = BodyJoints::default();
        before.add(JointType::Hinge);
        before.add(JointType::Ball);
        assert!(!before.rotation_after_ball);
    }

    #[test]
    fn joints_inside_a_frame_of_a_body_count_as_the_body_s() {
        let xml = r#"<mujoco><worldbody><body name="b"><freejoint/><frame><joint type="slide"/></frame>
              <frame><joint type="ball"/></frame><joint/><geom size="1"/></body></worldbody></mujoco>"#;
        let m = Model::from_xml_str(xml).unwrap();
        assert_eq!(kinds_of(&m, TooManyDofs::default()), [ProblemKind::TooManyDofs { dofs: 11 }]);
        assert_eq!(kinds_of(&m, RotationAfterBall::default()), [ProblemKind::RotationAfterBall]);
    }
}
