//! Reaching an element by its tag under a parent: the children of default classes,
//! which have no names (`<default class="large_actuator"><position kp="2000"/>`).

use crate::error::{EditError, ErrorKind};
use crate::model::{ElementRef, Loc, Model};

impl<'a> ElementRef<'a> {
    /// The first composed child with tag `tag`, if there is one (a default class's
    /// `<position>`, a body's `<inertial>`).
    ///
    /// Time: that of [`ElementRef::children`].
    pub fn child(&self, tag: &str) -> Option<ElementRef<'a>> {
        self.children().find(|c| c.tag() == tag)
    }
}

impl Model {
    /// The locator of the first child with tag `tag` of the element at `parent`: how
    /// to reach what has no name, such as the `<position>` of a default class
    /// (dm_control's `model.find('default', 'large_actuator').position`).
    ///
    /// Time: O(levels · depth · log n) to locate `parent`, plus that of
    /// [`ElementRef::children`].
    ///
    /// # Errors
    /// [`ErrorKind::NoChild`] when `parent` has no child with that tag;
    /// [`ErrorKind::StaleLocator`] when `parent` is not in this model.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace};
    /// let xml = r#"<mujoco><default><default class="large_actuator">
    ///   <position kp="2000"/></default></default></mujoco>"#;
    /// let mut m = Model::from_xml_str(xml)?;
    /// let class = m.lookup(Namespace::Default, "large_actuator")?;
    /// m.set_attr_mut(&m.child(&class, "position")?, "kp", 3000)?;
    /// assert_eq!(m.float(&m.child(&class, "position")?, "kp")?, 3000.0);
    /// assert!(m.child(&class, "body").is_err()); // a class holds no body
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn child(&self, parent: &Loc, tag: &str) -> Result<Loc, EditError> {
        let element = self.get(parent)?;
        match element.child(tag) {
            Some(child) => Ok(child.loc()),
            None => {
                let kind = ErrorKind::NoChild { parent: element.tag(), tag: tag.into() };
                let name = element.full_name().filter(|n| !n.is_empty());
                let at = match name {
                    Some(n) => format!("{}[name={n}]", element.tag()),
                    None => element.tag().to_string(),
                };
                Err(EditError::new(kind, at))
            }
        }
    }
}
