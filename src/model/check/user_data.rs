//! Rule *user data fits* ([`ProblemKind::Refused`]): an element's `user` numbers (its
//! own, else its classes') are at most its kind's `<size nuser_…>` of the model as
//! written (its merged settings; the last `<size>` giving it wins; -1, the default,
//! sizes it to the longest). MuJoCo refuses more ("user has more values than
//! nuser_tendon in tendon").

use crate::model::Model;
use crate::model::layout::effective;
use crate::model::settings;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// The kinds judged: the `<size>` attribute that bounds them and MuJoCo's name of
/// the kind in its message.
const KINDS: [(&str, &str); 2] = [("nuser_tendon", "tendon"), ("nuser_sensor", "sensor")];

/// The rule, with the bounds of the model as written (`None`: automatic).
pub(super) struct UserData {
    bounds: [Option<usize>; KINDS.len()],
}

impl UserData {
    /// The rule for `model` as written.
    pub(super) fn new(model: &Model) -> UserData {
        let size = ElementKind::ROOT.child("size");
        let mut bounds = [None; KINDS.len()];
        if let Ok(sections) = settings::merged(model) {
            for s in sections.iter().filter(|n| Some(n.kind()) == size) {
                for (bound, (attr, _)) in bounds.iter_mut().zip(KINDS) {
                    let v = s.kind().attr_index(attr).and_then(|i| s.attr(i));
                    if let Some(Value::Int(n)) = v {
                        *bound = usize::try_from(*n).ok();
                    }
                }
            }
        }
        UserData { bounds }
    }
}

/// Which of [`KINDS`] an element is, if any.
fn which(kind: ElementKind) -> Option<usize> {
    if kind.is(Role::Tendon) {
        Some(0)
    } else if super::values::on::in_section(kind, "sensor") {
        Some(1)
    } else {
        None
    }
}

impl<'m> Rule<'m> for UserData {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let Some(k) = which(e.node.kind()) else { return };
        let Some(bound) = self.bounds[k] else { return };
        let n = match effective(e.model, e.node, e.class, "user") {
            Some(Value::Floats(v)) => v.len(),
            Some(Value::Ints(v)) => v.len(),
            Some(Value::Float(_) | Value::Int(_)) => 1,
            _ => return,
        };
        let (attr, what) = KINDS[k];
        if n > bound {
            out.push(ProblemKind::Refused {
                rule: "user-data-length",
                attribute: Some("user"),
                mujoco: format!("user has more values than {attr} in {what}"),
                fix: "give user at most as many numbers as <size> allows, or raise that",
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::check::tests::kinds_of;

    fn found(text: &str) -> usize {
        let m = Model::from_xml_str(text).unwrap();
        kinds_of(&m, UserData::new(&m)).len()
    }

    /// Each case's verdict is MuJoCo 4.0.0's.
    #[test]
    fn user_data_is_bounded_by_the_last_size_that_gives_it() {
        let with = |size: &str, tendon_user: &str, sensor_user: &str| {
            format!(
                r#"<mujoco>{size}<worldbody><body name="b"><joint name="j"/><geom size=".1"/></body></worldbody>
                <tendon><fixed {tendon_user}><joint joint="j" coef="1"/></fixed></tendon>
                <sensor><jointpos joint="j" {sensor_user}/></sensor></mujoco>"#
            )
        };
        let refused = [
            (r#"<size nuser_tendon="1"/>"#, r#"user="1 2""#, ""),
            (r#"<size nuser_sensor="0"/>"#, "", r#"user="1""#),
            (r#"<size nuser_sensor="2"/><size nuser_sensor="1"/>"#, "", r#"user="1 2""#),
        ];
        for (size, t, s) in refused {
            assert_eq!(found(&with(size, t, s)), 1, "{size} {t} {s}");
        }
        let compiled = [
            (r#"<size nuser_tendon="1"/>"#, r#"user="1""#, r#"user="1 2""#),
            (r#"<size nuser_sensor="-1"/>"#, "", r#"user="1 2 3""#),
            (r#"<size nuser_sensor="1"/><size nuser_sensor="2"/>"#, "", r#"user="1 2""#),
        ];
        for (size, t, s) in compiled {
            assert_eq!(found(&with(size, t, s)), 0, "{size} {t} {s}");
        }
        let class = |n: usize| {
            format!(
                r#"<mujoco><size nuser_tendon="{n}"/><default><tendon user="1 2"/></default><worldbody><body>
                <joint name="j"/><geom size=".1"/></body></worldbody>
                <tendon><fixed><joint joint="j" coef="1"/></fixed></tendon></mujoco>"#
            )
        };
        assert_eq!(found(&class(1)), 1);
        assert_eq!(found(&class(2)), 0);
    }
}
