//! Applying recipes: the [`Builder`] carries a recipe's steps out one by one (each
//! step kind in `steps`, each edit in `edit`), within the budget of [`MAX_STEPS`].

use crate::error::ErrorKind;
use crate::model::{Element, Event, Loc, Model};
use crate::schema::{Namespace, Role};

use super::palette::direction;
use super::pick::{joint_fits, valid};
use super::recipe::{
    EditRecipe, FrameRecipe, JointKind, MAX_ELEMENTS, MAX_STEPS, ModelRecipe, Palette, Pick, Word,
};
use super::simulate::with_contact_classes;

impl ModelRecipe {
    /// Builds the model of the recipe's [`Palette`], skipping the steps that would
    /// make it invalid (none for [`Palette::Wide`]), and every step after the first
    /// [`MAX_STEPS`], nested recipes included.
    ///
    /// Time: O(s · N) for `s` steps and a composed model of N elements (each step is
    /// checked with [`Model::check`](crate::Model::check)).
    pub fn build(&self) -> Model {
        let m = Builder::new(self.palette).model(self, 0, "");
        if self.palette == Palette::Simulates { with_contact_classes(m) } else { m }
    }
}

impl EditRecipe {
    /// Applies the edits to `base`: the versions, `base` first, then one per edit
    /// that applied (an edit that would make the model invalid, or finds nothing to
    /// edit, makes none). Every version has no more [`Model::check`](crate::Model::check) problems than
    /// `base`.
    ///
    /// Time: O(e · N) for `e` edits and a composed model of N elements.
    ///
    /// # Examples
    /// ```
    /// use mjcf::generate::{Edit, EditRecipe, ModelRecipe, Pick, Word};
    /// let base = mjcf::Model::new("arena");
    /// let robot = ModelRecipe { name: Word(0), ..ModelRecipe::default() };
    /// let edits = EditRecipe {
    ///     edits: vec![
    ///         Edit::Add(mjcf::generate::Step::Attach { at: Pick(0), child: Box::new(robot), frame: Default::default() }),
    ///         Edit::RenameScope { scope: Pick(0), to: Word(1) },
    ///         Edit::Detach { scope: Pick(0) },
    ///     ],
    /// };
    /// let versions = edits.apply(&base);
    /// assert_eq!(versions.len(), 4);
    /// assert_eq!(versions[1].scopes().collect::<Vec<_>>(), ["robot"]);
    /// assert_eq!(versions[2].scopes().collect::<Vec<_>>(), ["arm"]);
    /// assert_eq!(versions[3], base); // detach gives back the model before the attach
    /// ```
    pub fn apply(&self, base: &Model) -> Vec<Model> {
        let mut b = Builder::new(Palette::Valid);
        let mut versions = vec![base.clone()];
        let mut current = base.clone();
        let allowed = base.check().len();
        for edit in &self.edits {
            if b.budget == 0 {
                break;
            }
            b.budget -= 1;
            if let Some(next) = b.edit(&current, edit, allowed) {
                versions.push(next.clone());
                current = next;
            }
        }
        versions
    }
}

const TIMESTEPS: [f64; 4] = [0.002, 0.004, 0.005, 0.01];

pub(super) struct Builder {
    pub(super) budget: usize,
    /// The models `Attach` steps built, for `AttachAgain`.
    pub(super) children: Vec<Model>,
    /// How many `include_copy` sources were built (their name prefixes).
    pub(super) copies: usize,
    /// The outermost recipe's palette, for every model built.
    pub(super) palette: Palette,
}

impl Builder {
    pub(super) fn new(palette: Palette) -> Builder {
        Builder { budget: MAX_STEPS, children: Vec::new(), copies: 0, palette }
    }

    /// How many problems a step may leave: none beyond `allowed`, but any number in
    /// the wide palette (whose models `check` is judged on).
    pub(super) fn allowed(&self, allowed: usize) -> usize {
        if self.palette == Palette::Wide { usize::MAX } else { allowed }
    }

    /// Builds a recipe's model at attachment depth `depth`; names get `prefix`.
    pub(super) fn model(&mut self, r: &ModelRecipe, depth: u32, prefix: &str) -> Model {
        let mut m = Model::new(r.name.model_name());
        let sim = self.palette == Palette::Simulates;
        if sim {
            // Damping and the joints' springs integrated implicitly.
            if let Some(next) =
                m.section("option").and_then(|o| m.set_attr(&o, "integrator", "implicitfast").ok())
            {
                m = next;
            }
        }
        // Simulating: MuJoCo's default timestep, 0.002.
        if let Some(t) = r.settings.timestep.filter(|_| !sim) {
            let t = TIMESTEPS[usize::from(t) % TIMESTEPS.len()];
            if let Some(next) = m.section("option").and_then(|o| m.set_attr(&o, "timestep", t).ok())
            {
                m = next;
            }
        }
        if let Some(radian) = r.settings.radian {
            let angle = if radian { "radian" } else { "degree" };
            if let Some(next) =
                m.section("compiler").and_then(|c| m.set_attr(&c, "angle", angle).ok())
            {
                m = next;
            }
        }
        for step in &r.steps {
            if self.budget == 0 {
                break;
            }
            self.budget -= 1;
            if let Some(next) = self.step(&m, step, depth, prefix, 0) {
                m = next;
            }
        }
        m
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn attach(
        &self,
        m: &Model,
        at: Pick,
        child: &Model,
        frame: &FrameRecipe,
        depth: u32,
        prefix: &str,
        allowed: usize,
    ) -> Option<Model> {
        let mut places = vec![m.worldbody()];
        places.extend(m.find_all(Namespace::Site));
        let place = at.of(&places)?.clone();
        // The frame goes where the site is: directly in the worldbody, or not.
        let top = self.palette == Palette::Wide
            || depth == 0
                && (place == m.worldbody()
                    || m.element(&place)
                        .and_then(|e| e.parent())
                        .is_some_and(|p| p.kind().is(Role::Worldbody)));
        // Models in other angle conventions are attached converted (decision D17);
        // the generators skip such an attach, as when it was refused, so that a seed
        // keeps giving the models it gave.
        let ours = crate::model::settings::merged(m).ok()?;
        let theirs = crate::model::settings::merged(child).ok()?;
        if crate::compose::angles::Change::between(&ours, &theirs).ok()?.is_some() {
            return None;
        }
        let (mut next, a) = m.attach(&place, child).ok()?;
        let frame_loc = a.frame().clone();
        let inertial = || {
            Element::new("inertial")
                .attr("pos", [0.0, 0.0, 0.0])
                .attr("mass", 0.1)
                .attr("diaginertia", [0.001, 0.001, 0.001])
        };
        if frame.free && top {
            next = next.add(&frame_loc, Element::new("freejoint")).ok()?.0;
            next = next.add(&frame_loc, inertial()).ok()?.0;
        } else if !frame.joints.is_empty() {
            // Joints that fit (at most 6 degrees of freedom, no rotation after a
            // ball joint); any number unnamed.
            let mut added = false;
            for j in frame.joints.iter().take(3) {
                if !joint_fits(&next, &frame_loc, j.kind) {
                    continue;
                }
                let make = |n: Option<&str>| {
                    let mut el = Element::new("joint").attr("type", j.kind.keyword());
                    if self.palette == Palette::Simulates {
                        el = el.attr("armature", 0.1).attr("damping", 1.0);
                    }
                    let el = if j.kind == JointKind::Ball {
                        el
                    } else {
                        el.attr("axis", direction(j.axis))
                    };
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                if let Some((n, _)) = add_named(
                    &next,
                    &frame_loc,
                    make,
                    j.name.map(Word::frame_joint_name),
                    prefix,
                    usize::MAX,
                ) {
                    next = n;
                    added = true;
                }
            }
            if added {
                next = next.add(&frame_loc, inertial()).ok()?.0;
            }
        }
        let small = next.walk().filter(|e| matches!(e, Event::Enter(_))).count() <= MAX_ELEMENTS;
        (small && valid(&next, allowed)).then_some(next)
    }
}

/// Adds `make(name)` under `parent`, named from `word` (with `prefix`, and a
/// suffix when taken; unnamed when `word` is `None`), and checks the result.
pub(super) fn add_named(
    m: &Model,
    parent: &Loc,
    make: impl Fn(Option<&str>) -> Element,
    word: Option<&str>,
    prefix: &str,
    allowed: usize,
) -> Option<(Model, Loc)> {
    let (next, loc) = match word {
        None => m.add(parent, make(None)).ok()?,
        Some(w) => {
            let base = format!("{prefix}{w}");
            let mut found = None;
            for k in 1..=6 {
                let name = if k == 1 { base.clone() } else { format!("{base}_{k}") };
                match m.add(parent, make(Some(&name))) {
                    Ok(r) => {
                        found = Some(r);
                        break;
                    }
                    Err(e) if matches!(e.kind(), ErrorKind::DuplicateIdentifier { .. }) => {}
                    Err(_) => return None,
                }
            }
            found?
        }
    };
    valid(&next, allowed).then_some((next, loc))
}
