//! Advice: what MuJoCo compiles, but likely not as meant ([`Model::advice`]), kept
//! apart from [`Model::check`], which reports only what MuJoCo refuses.

use std::fmt;

use crate::model::{Loc, Model};
use crate::write_options::WriteOptions;

/// A piece of advice [`Model::advice`] gives: what, and on which element.
#[derive(Clone, Debug, PartialEq)]
pub struct Advice {
    /// The element.
    pub loc: Loc,
    /// The element as the writer names it (see [`Problem::path`](crate::Problem)).
    pub path: String,
    /// What it is about.
    pub kind: AdviceKind,
}

/// What [`Model::advice`] can say.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum AdviceKind {
    /// A key of an attached model, written as it is (without
    /// [`WriteOptions::merge_keyframes`]): MuJoCo compiles it, but its values fall on
    /// the composed model's first joints and actuators (the parent's), not on the
    /// attached model's. Write with `merge_keyframes`, which carries each attached
    /// model's key to its own joints and through its attachment frame.
    UncomposedKey,
}

impl fmt::Display for Advice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            AdviceKind::UncomposedKey => write!(
                f,
                "{}: a key of an attached model, written as it is, sets the composed model's \
                 first joints, not this model's; write with WriteOptions::merge_keyframes",
                self.path
            ),
        }
    }
}

impl Model {
    /// What MuJoCo compiles but likely not as meant, for the model written with the
    /// default [`WriteOptions`]: keys of attached models written without
    /// `merge_keyframes` ([`AdviceKind::UncomposedKey`]), each once. Unlike
    /// [`Model::check`], nothing here makes MuJoCo refuse the model.
    ///
    /// Time: O(N) for a composed model of N elements.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{AdviceKind, Model, WriteOptions, element};
    /// let mut robot = Model::new("robot");
    /// let b = robot.add_mut(&robot.worldbody(), element!("body", name = "b"))?;
    /// robot.add_mut(&b, element!("joint"))?;
    /// robot.add_mut(&b, element!("geom", size = [0.1]))?;
    /// robot.add_mut(&robot.section("keyframe").unwrap(), element!("key", name = "home", qpos = [0.5]))?;
    /// let (scene, _) = Model::new("arena").attach_to_world(&robot)?;
    /// assert!(scene.check().is_empty()); // MuJoCo compiles it
    /// let advice = scene.advice();
    /// assert_eq!(advice.len(), 1);
    /// assert_eq!(advice[0].kind, AdviceKind::UncomposedKey);
    /// let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    /// assert!(scene.advice_with(&merged).is_empty());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn advice(&self) -> Vec<Advice> {
        self.advice_with(&WriteOptions::default())
    }

    /// [`Model::advice`] for the model as it will be written with `options`.
    ///
    /// Time: as [`Model::advice`].
    pub fn advice_with(&self, options: &WriteOptions) -> Vec<Advice> {
        if options.merge_keyframes {
            return Vec::new();
        }
        // The sizes (counted, never listed: any `<replicate>` count) list each key once.
        let layout = self.layout_sizes();
        let mut out: Vec<Advice> = Vec::new();
        for (inst, _, loc) in &layout.keys {
            if *inst == 0 {
                continue;
            }
            let path =
                self.element(loc).and_then(|e| e.full_name()).unwrap_or_else(|| "key".into());
            out.push(Advice { loc: loc.clone(), path, kind: AdviceKind::UncomposedKey });
        }
        out
    }
}
