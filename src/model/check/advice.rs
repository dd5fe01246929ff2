//! Advice: what MuJoCo compiles, but likely not as meant ([`Model::advice`]), kept
//! apart from [`Model::check`], which reports only what MuJoCo refuses.

use std::fmt;

use crate::model::{Loc, Model, Step, Walk};
use crate::schema::ElementKind;
use crate::value::Value;
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
    /// A plugin the model uses (`<extension><plugin plugin="…">`): what MuJoCo refuses
    /// of a plugin depends on the plugin's library (its attributes, its capabilities),
    /// which [`Model::check`] does not know, so it judges nothing of the plugin; MuJoCo
    /// does, when it compiles the model.
    PluginNotJudged {
        /// The plugin's name (`mujoco.elasticity.cable`).
        plugin: String,
    },
}

impl fmt::Display for Advice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            AdviceKind::UncomposedKey => write!(
                f,
                "{}: a key of an attached model, written as it is, sets the composed model's \
                 first joints, not this model's; write with WriteOptions::merge_keyframes",
                self.path
            ),
            AdviceKind::PluginNotJudged { plugin } => write!(
                f,
                "{}: plugin '{plugin}' is not judged by check(), which does not know its \
                 library; compile the model with MuJoCo (mjcf-mujoco) to judge it",
                self.path
            ),
        }
    }
}

impl Model {
    /// What MuJoCo compiles but likely not as meant, for the model written with the
    /// default [`WriteOptions`]: keys of attached models written without
    /// `merge_keyframes` ([`AdviceKind::UncomposedKey`]), each once; and what
    /// [`Model::check`] leaves to MuJoCo: the plugins the model uses
    /// ([`AdviceKind::PluginNotJudged`]). Unlike [`Model::check`], nothing here makes
    /// MuJoCo refuse the model.
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
        let mut out = self.plugins_not_judged();
        if options.merge_keyframes {
            return out;
        }
        // The sizes (counted, never listed: any `<replicate>` count) list each key once.
        let layout = self.layout_sizes();
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

impl Model {
    /// [`AdviceKind::PluginNotJudged`] for each plugin the composed model declares
    /// (`<extension><plugin>`, in every model), each name once.
    fn plugins_not_judged(&self) -> Vec<Advice> {
        let Some(plugin_kind) = ElementKind::EXTENSION.child("plugin") else { return Vec::new() };
        let top = self.name();
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        let mut walk = Walk::new(self);
        while let Some(step) = walk.next() {
            let Step::Enter(item) = step else { continue };
            let node = item.node;
            if node.kind() != plugin_kind {
                continue;
            }
            let i = plugin_kind.attr_index("plugin");
            let Some(name) = i.and_then(|i| node.attr(i)).and_then(Value::as_str) else {
                continue;
            };
            if seen.insert(name.to_string()) {
                let loc = Loc::scoped(walk.insts.list[item.inst].frames.clone(), node.id(), top);
                let path = format!("{}extension/plugin", walk.insts.list[item.inst].names.prefix);
                let plugin = name.to_string();
                out.push(Advice { loc, path, kind: AdviceKind::PluginNotJudged { plugin } });
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plugins_a_model_uses_are_said_to_be_left_to_mujoco() {
        let m = Model::from_xml_str(
            r#"<mujoco><extension><plugin plugin="mujoco.elasticity.cable"/>
               <plugin plugin="mujoco.pid"><instance name="p"/></plugin></extension></mujoco>"#,
        )
        .unwrap();
        let plugins: Vec<String> = m
            .advice()
            .into_iter()
            .filter_map(|a| match a.kind {
                AdviceKind::PluginNotJudged { plugin } => Some(plugin),
                _ => None,
            })
            .collect();
        assert_eq!(plugins, ["mujoco.elasticity.cable", "mujoco.pid"]);
        assert!(m.check().is_empty());
        assert!(Model::new("m").advice().is_empty());
    }
}
