//! Rule *a mocap body is a fixed child of the world* ([`ProblemKind::MocapNotFixedChildOfWorld`]).

use crate::model::layout::effective;
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// A mocap body (`mocap="true"`) whose parent, once composed, is a body rather than
/// the world, or that has joints: MuJoCo refuses it ("mocap body '…' is not a fixed
/// child of world"). `<frame>`s, `<replicate>`s and attachment frames written as
/// `<frame>` are transparent; an attachment frame written as a body is a body, so
/// attaching a model with a mocap top-level body makes this wherever it is attached
/// unless the frame is written as `<frame>` (its model also has a free body).
#[derive(Default)]
pub(super) struct MocapNotFixedChildOfWorld;

impl<'m> Rule<'m> for MocapNotFixedChildOfWorld {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if !e.is_body || e.body.top_level && !e.body.moves {
            return;
        }
        if effective(e.model, e.node, e.class, "mocap").and_then(Value::as_str) == Some("true") {
            out.push(ProblemKind::MocapNotFixedChildOfWorld);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::model::check::tests::kinds_of;

    /// Shapes checked against MuJoCo 4.0.0 (it refuses exactly the `true` ones).
    #[test]
    fn a_mocap_body_is_refused_below_a_body_or_with_a_joint() {
        let cases = [
            (r#"<body><body mocap="true"><geom size="1"/></body></body>"#, true),
            (r#"<body mocap="true"><joint/><geom size="1"/></body>"#, true),
            (r#"<frame><body mocap="true"><geom size="1"/></body></frame>"#, false),
            (r#"<body mocap="true"><geom size="1"/></body>"#, false),
        ];
        for (body, refused) in cases {
            let m = Model::from_xml_str(&format!("<mujoco><worldbody>{body}</worldbody></mujoco>"))
                .unwrap();
            let expected =
                if refused { vec![ProblemKind::MocapNotFixedChildOfWorld] } else { vec![] };
            assert_eq!(kinds_of(&m, MocapNotFixedChildOfWorld), expected, "{body}");
        }
    }
}
