//! Rule *a free joint only on a top-level body* ([`ProblemKind::FreeJointNotTopLevel`]).

use crate::model::layout::{JointType, joint_type};
use crate::schema::Role;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// A body with a free joint (`<freejoint>`, or `<joint type="free">` by its own
/// type or its classes') whose parent, once composed, is a body rather than the
/// world: MuJoCo refuses it ("free joint can only be used on top level", naming the
/// body, as this rule does). `<frame>`s and `<replicate>`s between the body and the
/// world are transparent, and so is an attachment frame written as MuJoCo's
/// `<frame>`; one written as a body is a body. Attaching a model with free
/// top-level bodies at a site inside a body makes this.
#[derive(Default)]
pub(super) struct FreeJointNotTopLevel {
    /// Per open body: it has a free joint.
    free: Vec<bool>,
}

impl<'m> Rule<'m> for FreeJointNotTopLevel {
    fn enter(&mut self, e: &Event<'m>, _: &mut Vec<ProblemKind>) {
        if e.is_body {
            self.free.push(false);
        } else if matches!(e.node.kind().role(), Some(Role::Joint | Role::Freejoint))
            && joint_type(e.model, e.node, e.class) == JointType::Free
        {
            if let Some(top) = self.free.last_mut() {
                *top = true;
            }
        }
    }

    fn leave(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if e.is_body && self.free.pop() == Some(true) && !e.body.top_level {
            out.push(ProblemKind::FreeJointNotTopLevel);
        }
    }
}

/// What floats at the world's top level of `model` (through `<frame>`s,
/// `<replicate>`s and attachment frames written as `<frame>`): its free joints and
/// its mocap bodies (`true` for a mocap body), which MuJoCo refuses once `model` is
/// attached below a body.
pub(crate) fn top_level_floating(model: &crate::model::Model) -> Vec<(crate::model::Loc, bool)> {
    /// Flags every top-level free joint and mocap body (a problem only to carry its
    /// locator out).
    struct Floating;
    impl<'m> Rule<'m> for Floating {
        fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
            if !e.body.top_level {
                return;
            }
            let role = e.node.kind().role();
            if e.is_body {
                let mocap = crate::model::layout::effective(e.model, e.node, e.class, "mocap");
                if mocap.and_then(crate::value::Value::as_str) == Some("true") {
                    out.push(ProblemKind::MocapNotFixedChildOfWorld);
                }
            } else if matches!(role, Some(Role::Joint | Role::Freejoint))
                && joint_type(e.model, e.node, e.class) == JointType::Free
            {
                out.push(ProblemKind::FreeJointNotTopLevel);
            }
        }
    }
    let mut rules: Vec<Box<dyn Rule<'_> + '_>> = vec![Box::new(Floating)];
    let found = super::walk::run(model, &mut rules).into_iter();
    found.map(|p| (p.loc, p.kind == ProblemKind::MocapNotFixedChildOfWorld)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::model::check::tests::kinds_of;

    /// Shapes checked against MuJoCo 4.0.0 (it refuses exactly the `true` ones).
    #[test]
    fn a_free_joint_is_refused_below_a_body_and_accepted_at_the_world_s_top_level() {
        let cases = [
            (r#"<body><geom size="1"/><body><freejoint/><geom size="1"/></body></body>"#, true),
            (
                r#"<body><frame><body><joint type="free"/><geom size="1"/></body></frame></body>"#,
                true,
            ),
            (r#"<frame><body><freejoint/><geom size="1"/></body></frame>"#, false),
            (
                r#"<replicate count="2" offset="1 0 0"><body><freejoint/><geom size="1"/></body></replicate>"#,
                false,
            ),
            (r#"<body><freejoint/><geom size="1"/></body>"#, false),
        ];
        for (body, refused) in cases {
            let m = Model::from_xml_str(&format!("<mujoco><worldbody>{body}</worldbody></mujoco>"))
                .unwrap();
            let expected = if refused { vec![ProblemKind::FreeJointNotTopLevel] } else { vec![] };
            assert_eq!(kinds_of(&m, FreeJointNotTopLevel::default()), expected, "{body}");
        }
        let by_class = r#"<mujoco><default><joint type="free"/></default><worldbody>
            <body><geom size="1"/><body><joint/><geom size="1"/></body></body></worldbody></mujoco>"#;
        let m = Model::from_xml_str(by_class).unwrap();
        assert_eq!(
            kinds_of(&m, FreeJointNotTopLevel::default()),
            [ProblemKind::FreeJointNotTopLevel]
        );
        // By a childclass: refused on the inner body, accepted on the top-level one.
        let childclass = |inner: &str| {
            format!(
                r#"<mujoco><default><default class="f"><joint type="free"/></default></default>
                   <worldbody><body childclass="f">{inner}<geom size="1"/></body></worldbody></mujoco>"#
            )
        };
        let nested = Model::from_xml_str(&childclass(r#"<body><joint/><geom size="1"/></body>"#));
        let top = Model::from_xml_str(&childclass("<joint/>"));
        let rule = FreeJointNotTopLevel::default;
        assert_eq!(kinds_of(&nested.unwrap(), rule()), [ProblemKind::FreeJointNotTopLevel]);
        assert_eq!(kinds_of(&top.unwrap(), rule()), []);
    }

    #[test]
    fn what_floats_is_the_top_level_free_joints_and_mocap_bodies() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="a"><freejoint name="fa"/><geom size="1"/>
                   <body><freejoint name="deep"/><geom size="1"/></body></body>
                 <frame><body name="b"><joint name="fb" type="free"/><geom size="1"/></body></frame>
                 <body name="m" mocap="true"><geom size="1"/></body>
               </worldbody></mujoco>"#,
        )
        .unwrap();
        let found: Vec<(String, bool)> = top_level_floating(&m)
            .into_iter()
            .map(|(loc, mocap)| (m.full_name(&loc).unwrap(), mocap))
            .collect();
        let expected = [("fa", false), ("fb", false), ("m", true)];
        assert_eq!(found, expected.map(|(n, b)| (n.to_string(), b)));
    }
}
