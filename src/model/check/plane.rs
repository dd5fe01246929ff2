//! Rule *a plane only in a static body* ([`ProblemKind::PlaneInMovingBody`]).

use crate::model::layout::effective;
use crate::schema::Role;
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// A plane geom (`type="plane"`, its own or its classes') in a body that moves or
/// hangs below a moving body: MuJoCo refuses it ("plane only allowed in static
/// bodies"; static is welded to the world: no joint on the body nor on a body above
/// it; a mocap body is static). Attaching a model with a plane at a site inside a
/// moving body makes this.
#[derive(Default)]
pub(super) struct PlaneInMovingBody;

impl<'m> Rule<'m> for PlaneInMovingBody {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if e.body.is_static() || !e.node.kind().is(Role::Geom) {
            return;
        }
        if effective(e.model, e.node, e.class, "type").and_then(Value::as_str) == Some("plane") {
            out.push(ProblemKind::PlaneInMovingBody);
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
    fn a_plane_is_refused_in_or_below_a_moving_body_and_accepted_in_a_static_one() {
        let plane = r#"<geom type="plane" size="1 1 1"/>"#;
        let cases = [
            (format!(r#"<body><joint/><geom size="1"/>{plane}</body>"#), true),
            (format!(r#"<body><joint/><geom size="1"/><body>{plane}</body></body>"#), true),
            (format!(r#"<body><joint/><geom size="1"/><frame>{plane}</frame></body>"#), true),
            (plane.to_string(), false),
            (format!("<body><body>{plane}</body></body>"), false),
            (format!(r#"<body mocap="true"><body>{plane}</body></body>"#), false),
        ];
        for (body, refused) in cases {
            let m = Model::from_xml_str(&format!("<mujoco><worldbody>{body}</worldbody></mujoco>"))
                .unwrap();
            let expected = if refused { vec![ProblemKind::PlaneInMovingBody] } else { vec![] };
            assert_eq!(kinds_of(&m, PlaneInMovingBody), expected, "{body}");
        }
        let by_class = r#"<mujoco><default><geom type="plane"/></default><worldbody>
            <body><joint/><geom size="1 1 1"/></body></worldbody></mujoco>"#;
        let m = Model::from_xml_str(by_class).unwrap();
        assert_eq!(kinds_of(&m, PlaneInMovingBody), [ProblemKind::PlaneInMovingBody]);
        // By a childclass: refused in a moving body, accepted in a static one.
        let childclass = |joint: &str| {
            format!(
                r#"<mujoco><default><default class="p"><geom type="plane"/></default></default>
                   <worldbody><body childclass="p">{joint}<geom size="1 1 1"/></body></worldbody></mujoco>"#
            )
        };
        let moving = r#"<joint type="slide"/><geom type="sphere" size="1"/>"#;
        let m = Model::from_xml_str(&childclass(moving)).unwrap();
        assert_eq!(kinds_of(&m, PlaneInMovingBody), [ProblemKind::PlaneInMovingBody]);
        assert_eq!(kinds_of(&Model::from_xml_str(&childclass("")).unwrap(), PlaneInMovingBody), []);
    }
}
