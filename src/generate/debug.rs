//! How recipes print: compactly, as what they pick and the numbers they hold
//! (`#3` for `Pick(3)`, `0.25` for `Unit(250)`, the name a `Word` gives), and a
//! [`ModelRecipe`] in the alternate form (`{:#?}`, what proptest prints for a failing
//! input) with the MJCF text of the model it builds.

use std::fmt;

use super::recipe::{AttrDraw, FrameJoint, ModelRecipe, Pick, Unit, Word};

impl fmt::Debug for Pick {
    /// `#i`: the `i`-th (modulo) of what the step picks from.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}

impl fmt::Debug for Unit {
    /// The number in `[0, 1]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.fraction())
    }
}

impl fmt::Debug for Word {
    /// The element name ([`Word::text`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.text())
    }
}

impl fmt::Debug for AttrDraw {
    /// `attr#i(values; len k)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v: Vec<String> = self.values.iter().map(|u| u.fraction().to_string()).collect();
        write!(f, "attr#{}({}; len {})", self.which.0, v.join(", "), self.len)
    }
}

impl fmt::Debug for FrameJoint {
    /// Its type, name ([`Word::frame_joint_name`]) and axis.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FrameJoint")
            .field("name", &self.name.map(Word::frame_joint_name))
            .field("kind", &self.kind)
            .field("axis", &self.axis)
            .finish()
    }
}

impl fmt::Debug for ModelRecipe {
    /// Its model name, palette, settings and steps; the alternate form adds the MJCF
    /// text of the model it builds.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ModelRecipe")
            .field("name", &self.name.model_name())
            .field("palette", &self.palette)
            .field("settings", &self.settings)
            .field("steps", &self.steps)
            .finish()?;
        if f.alternate() {
            match self.build().to_xml_string() {
                Ok(xml) => write!(f, "\nbuilds:\n{}", xml.trim_end())?,
                Err(e) => write!(f, "\nbuilds a model that does not write: {e}")?,
            }
        }
        Ok(())
    }
}
