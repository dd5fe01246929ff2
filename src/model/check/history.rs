//! Rule *history needs time steps* ([`ProblemKind::Refused`]): a sensor that keeps a
//! history (`nsample` above 0) needs the model's `<option timestep>`
//! positive (its merged settings; the last `<option>` giving it wins; 0.002 by
//! default). MuJoCo refuses it ("history buffers require positive timestep, got 0").
//! An actuator's history is the actuators rule's, in MuJoCo's order of its checks.

use crate::model::Model;
use crate::model::settings;
use crate::schema::ElementKind;
use crate::value::Value;

use super::ProblemKind;
use super::values::on;
use super::walk::{Event, Rule};

/// The rule, with the time step of the model as written.
pub(super) struct History {
    timestep: f64,
}

impl History {
    /// The rule for `model` as written.
    pub(super) fn new(model: &Model) -> History {
        let mut timestep = 0.002;
        if let Ok(sections) = settings::merged(model) {
            for s in sections.iter().filter(|n| n.kind() == ElementKind::OPTION) {
                match s.kind().attr_index("timestep").and_then(|i| s.attr(i)) {
                    Some(Value::Float(t)) => timestep = *t,
                    Some(Value::Int(t)) => timestep = *t as f64,
                    _ => {}
                }
            }
        }
        History { timestep }
    }
}

impl<'m> Rule<'m> for History {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        // A nan time step passes, as in MuJoCo.
        if self.timestep > 0.0 || self.timestep.is_nan() {
            return;
        }
        let kind = e.node.kind();
        let judged = on::in_section(kind, "sensor");
        let own = kind.attr_index("nsample").and_then(|i| e.node.attr(i));
        if judged && matches!(own, Some(Value::Int(n)) if *n > 0) {
            out.push(ProblemKind::Refused {
                rule: "history-timestep",
                attribute: Some("nsample"),
                mujoco: format!("history buffers require positive timestep, got {}", self.timestep),
                fix: "give <option timestep> a positive value, or keep no history (nsample 0)",
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::check::tests::kinds_of;

    /// Each case's verdict is MuJoCo 4.0.0's.
    #[test]
    fn a_history_needs_a_positive_time_step() {
        let found = |options: &str, sections: &str| {
            let text = format!(
                r#"<mujoco>{options}<worldbody><body name="b"><joint name="j"/><geom size=".1"/></body>
                </worldbody>{sections}</mujoco>"#
            );
            let m = Model::from_xml_str(&text).unwrap();
            kinds_of(&m, History::new(&m)).len()
        };
        let zero = r#"<option timestep="0"/>"#;
        let sensor = r#"<sensor><jointpos joint="j" nsample="2"/></sensor>"#;
        let motor = r#"<actuator><motor joint="j" nsample="2" delay="0.01"/></actuator>"#;
        assert_eq!(found(zero, sensor), 1);
        // An actuator's is the actuators rule's: said once, there.
        assert_eq!(found(zero, motor), 0);
        assert_eq!(found(r#"<option timestep="-1"/>"#, sensor), 1);
        assert_eq!(found(r#"<option timestep="0.01"/><option timestep="0"/>"#, sensor), 1);
        assert_eq!(found(r#"<option timestep="0"/><option timestep="0.01"/>"#, sensor), 0);
        assert_eq!(found(r#"<option timestep="0.002"/>"#, motor), 0);
        assert_eq!(found(r#"<option timestep="nan"/>"#, sensor), 0);
        assert_eq!(found(zero, r#"<sensor><jointpos joint="j" interval="0.1"/></sensor>"#), 0);
        assert_eq!(found(zero, r#"<actuator><motor joint="j" nsample="-1"/></actuator>"#), 0);
    }
}
