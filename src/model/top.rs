//! Adding at the top level without naming the section: as MuJoCo's `MjSpec` has
//! `spec.add_actuator()`, `spec.add_sensor()`, `spec.add_material()`.

use crate::error::{EditError, ErrorKind};
use crate::model::{Element, Loc, Model};
use crate::schema::{ElementKind, Role};

impl Model {
    /// The top-level section that takes an element of tag `tag`: `worldbody` for
    /// bodies, geoms, sites, lights, cameras and frames, `actuator` for motors,
    /// `sensor` for sensors, `asset` for meshes, materials and textures, and so on.
    /// The default classes are never chosen (add to [`Model::default_class`] for
    /// that), nor a section for what a body takes and the worldbody does not
    /// (`joint`, `freejoint`, `inertial`: `<equality>` has a `<joint>` child, a
    /// constraint).
    ///
    /// Time: O(1) (a scan of the schema's fixed list of sections).
    ///
    /// # Errors
    /// [`ErrorKind::NoSection`] when no section, or more than one, takes the tag
    /// (a `<joint>` belongs in a body: add it there with [`Model::add`]).
    pub fn section_for(&self, tag: &str) -> Result<Loc, EditError> {
        let refuse = || EditError::new(ErrorKind::NoSection { tag: tag.into() }, String::new());
        // What a body takes and the worldbody does not (`joint`, `freejoint`,
        // `inertial`) belongs in a body, even where a section has a child of that tag
        // (`<equality><joint>` is a constraint, not a joint).
        let world = ElementKind::WORLDBODY;
        let body = world.child_of_role(Role::Body).ok_or_else(refuse)?;
        if body.child(tag).is_some() && world.child(tag).is_none() {
            return Err(refuse());
        }
        let mut sections = ElementKind::ROOT
            .spec()
            .children
            .iter()
            .filter(|s| !s.is(Role::DefaultClass) && s.child(tag).is_some());
        match (sections.next(), sections.next()) {
            (Some(section), None) => Ok(self.must_section(section.tag())),
            _ => Err(refuse()),
        }
    }

    /// [`Model::add`] into the section that takes the element's tag
    /// ([`Model::section_for`]): `m.add_top(element!("motor", joint = "hip"))` is
    /// `m.add(&m.actuator(), element!("motor", joint = "hip"))`. Returns the new
    /// model and the new element's locator; `self` is unchanged.
    ///
    /// Time: that of [`Model::add`].
    ///
    /// # Errors
    /// [`ErrorKind::NoSection`] when no single section takes the tag; otherwise
    /// those of [`Model::add`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let m = Model::new("m");
    /// let (m, torso) = m.add_top(element!("body", name = "torso"))?;
    /// let (m, motor) = m.add_top(element!("motor", name = "m1"))?;
    /// assert_eq!(m.get(&torso)?.parent().map(|p| p.tag()), Some("worldbody"));
    /// assert_eq!(m.get(&motor)?.parent().map(|p| p.tag()), Some("actuator"));
    /// assert!(m.add_top(element!("joint")).is_err()); // joints go in bodies
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn add_top(&self, element: Element) -> Result<(Model, Loc), EditError> {
        self.add(&self.section_for(element.tag())?, element)
    }

    /// [`Model::add_top`] in place (atomically: on error `self` is unchanged); returns
    /// the new element's locator.
    ///
    /// Time: that of [`Model::add_mut`].
    ///
    /// # Errors
    /// As [`Model::add_top`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut arena = Model::new("arena");
    /// let spawn = arena.add_top_mut(element!("site", name = "spawn", pos = [0, 0, 0.5]))?;
    /// arena.add_top_mut(element!("geom", type = "plane", size = [5, 5, 0.1]))?;
    /// assert_eq!(arena.get(&spawn)?.parent().map(|p| p.tag()), Some("worldbody"));
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn add_top_mut(&mut self, element: Element) -> Result<Loc, EditError> {
        let section = self.section_for(element.tag())?;
        self.add_mut(&section, element)
    }
}
