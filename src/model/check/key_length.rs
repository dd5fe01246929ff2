//! Rule *a key is no longer than the model* ([`ProblemKind::KeyLength`]).

use std::collections::HashMap;

use crate::model::Model;
use crate::model::pose::floats;
use crate::schema::Role;
use crate::write_options::WriteOptions;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// Keys with more values than MuJoCo takes (it refuses them: "invalid qpos size";
/// fewer it pads). Written with [`WriteOptions::merge_keyframes`], each model's key
/// is held to its own joints and actuators; without, every key to the composed
/// model's.
pub(super) struct KeyLength<'m> {
    model: &'m Model,
    merge: bool,
    /// Per instance (or, for the composed model, under `usize::MAX`): qpos, qvel, act,
    /// ctrl, mocap bodies; counted from the layout at the first key.
    sizes: Option<HashMap<usize, [usize; 5]>>,
}

impl<'m> KeyLength<'m> {
    /// The rule for `model` written with `options`.
    pub(super) fn new(model: &'m Model, options: &WriteOptions) -> KeyLength<'m> {
        KeyLength { model, merge: options.merge_keyframes, sizes: None }
    }

    /// The sizes of `model`'s layout, per instance with `merge`, else for the whole:
    /// counted, not listed, so `<replicate>` counts of any size cost nothing here.
    fn sizes(model: &Model, merge: bool) -> HashMap<usize, [usize; 5]> {
        let layout = model.layout_sizes();
        if merge {
            return layout.per_inst;
        }
        let mut sum = [0usize; 5];
        for n in layout.per_inst.values() {
            for (s, n) in sum.iter_mut().zip(n) {
                *s = s.saturating_add(*n);
            }
        }
        HashMap::from([(usize::MAX, sum)])
    }
}

impl<'m> Rule<'m> for KeyLength<'m> {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        if !e.node.kind().is(Role::Key) {
            return;
        }
        let (model, merge) = (self.model, self.merge);
        let sizes = self.sizes.get_or_insert_with(|| KeyLength::sizes(model, merge));
        let n =
            sizes.get(&if self.merge { e.inst } else { usize::MAX }).copied().unwrap_or_default();
        let fields = [
            ("qpos", n[0]),
            ("qvel", n[1]),
            ("act", n[2]),
            ("ctrl", n[3]),
            ("mpos", n[4].saturating_mul(3)),
            ("mquat", n[4].saturating_mul(4)),
        ];
        for (attribute, expected) in fields {
            if let Some(found) =
                floats(e.node, attribute).map(<[f64]>::len).filter(|f| *f > expected)
            {
                out.push(ProblemKind::KeyLength { attribute, expected, found });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::check::tests::kinds_of;

    #[test]
    fn a_key_longer_than_the_model_is_reported_per_attribute_and_a_shorter_one_is_not() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody><body><joint/><geom size="1"/></body></worldbody>
               <keyframe><key qpos="1 2" qvel="1"/><key qpos="1"/></keyframe></mujoco>"#,
        )
        .unwrap();
        let rule = KeyLength::new(&m, &WriteOptions::default());
        assert_eq!(
            kinds_of(&m, rule),
            [ProblemKind::KeyLength { attribute: "qpos", expected: 1, found: 2 }]
        );
    }
}
