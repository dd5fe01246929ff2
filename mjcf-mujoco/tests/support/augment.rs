//! Generated scenes with more of what rebuilds carry: actuators (with an activation),
//! a mocap body and an equality.

use mjcf::{Event, Model, element};

/// The full name of the first named hinge or slide joint of a body.
fn first_joint(m: &Model) -> Option<String> {
    m.walk().find_map(|ev| match ev {
        Event::Enter(e)
            if e.tag() == "joint"
                && e.identifier().is_some()
                && matches!(e.string("type"), None | Some("hinge" | "slide"))
                && e.parent().is_some_and(|p| p.tag() == "body" || p.is_frame()) =>
        {
            e.full_name()
        }
        _ => None,
    })
}

/// The full name of the first named body with a joint.
fn first_moving_body(m: &Model) -> Option<String> {
    m.walk().find_map(|ev| match ev {
        Event::Enter(e)
            if e.tag() == "body"
                && e.identifier().is_some()
                && e.children().any(|c| matches!(c.tag(), "joint" | "freejoint")) =>
        {
            e.full_name()
        }
        _ => None,
    })
}

/// `m` with a general actuator and a motor on its first named hinge or slide joint
/// (generated scenes have few actuators).
pub(crate) fn with_actuators(mut m: Model) -> Model {
    let Some(joint) = first_joint(&m) else { return m };
    let act = m.actuator();
    let general = element!(
        "general",
        name = "extra_general",
        joint = joint.as_str(),
        gainprm = [1.0],
        biasprm = [0.0, -1.0, -0.1]
    );
    let motor = element!("motor", name = "extra_motor", joint = joint.as_str(), gear = [1.0]);
    let before = m.clone();
    if m.add_mut(&act, general).is_err() || m.add_mut(&act, motor).is_err() {
        return before;
    }
    m
}

/// [`with_actuators`], plus an actuator with an activation (an integrator), a mocap
/// body and an equality connecting it to the first named moving body (active or
/// not, as `active` says).
#[allow(dead_code)]
pub(crate) fn with_state(m: Model, active: bool) -> Model {
    let mut m = with_actuators(m);
    let before = m.clone();
    let w = m.worldbody();
    let add = |m: &mut Model| -> Result<(), mjcf::EditError> {
        let mocap = m.add_mut(
            &w,
            element!("body", name = "extra_mocap", mocap = true, pos = [0.3, 0.2, 1.0]),
        )?;
        m.add_mut(
            &mocap,
            element!("geom", type = "sphere", size = [0.05], contype = 0, conaffinity = 0),
        )?;
        if let Some(joint) = first_joint(m) {
            let act = m.actuator();
            m.add_mut(
                &act,
                element!(
                    "general",
                    name = "extra_integrator",
                    joint = joint.as_str(),
                    dyntype = "integrator",
                    gainprm = [0.5]
                ),
            )?;
        }
        if let Some(body) = first_moving_body(m) {
            let eq = m.section("equality").expect("the equality section");
            m.add_mut(
                &eq,
                element!(
                    "connect",
                    name = "extra_tie",
                    body1 = "extra_mocap",
                    body2 = body.as_str(),
                    anchor = [0, 0, 0],
                    active = active
                ),
            )?;
        }
        Ok(())
    };
    if add(&mut m).is_err() {
        return before;
    }
    m
}
