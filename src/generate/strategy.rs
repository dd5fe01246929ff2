//! Proptest strategies of recipes, and of the models they build (feature
//! `proptest`).
//!
//! Strategies generate recipes ([`ModelRecipe`], [`EditRecipe`]); proptest shrinks
//! the recipe (fewer steps, smaller picks and numbers), and since applying any recipe
//! gives a valid model, every shrunk case is valid too. The `*_models` strategies
//! build the model from the recipe for properties that need only the model.
//!
//! # Examples
//! ```
//! use mjcf::generate::strategy;
//! use proptest::prelude::*;
//!
//! proptest!(ProptestConfig::with_cases(16), |(m in strategy::scenes())| {
//!     prop_assert!(m.check().is_empty());
//!     let xml = m.to_xml_string().unwrap();
//!     // What the crate writes reads back (names with '/' as literal names).
//!     prop_assert!(mjcf::Model::from_xml_str(&xml).is_ok());
//! });
//! ```

use ::proptest::collection::vec;
use ::proptest::prelude::*;
use ::proptest::strategy::Union;

use super::{
    ActuatorKind, AttrDraw, DefaultTag, Edit, EditRecipe, EqualityKind, FrameJoint, FrameRecipe,
    GeomRecipe, JointKind, MODEL_WORDS, ModelRecipe, ObjKind, Palette, Pick, SensorKind, Settings,
    Shape, Step, Unit, WORDS, Word,
};
use crate::model::Model;

/// A [`Unit`], from 0 to 1000 thousandths (shrinks towards 0).
///
/// Time: O(1) per value.
pub fn unit() -> impl Strategy<Value = Unit> + Clone {
    (0u16..=1000).prop_map(Unit)
}

/// A [`Pick`] (shrinks towards the first item).
///
/// Time: O(1) per value.
pub fn pick() -> impl Strategy<Value = Pick> + Clone {
    any::<u16>().prop_map(Pick)
}

/// A [`Word`] of [`WORDS`].
///
/// Time: O(1) per value.
pub fn word() -> impl Strategy<Value = Word> + Clone {
    (0..WORDS.len() as u8).prop_map(Word)
}

fn model_word() -> impl Strategy<Value = Word> + Clone {
    (0..MODEL_WORDS.len() as u8).prop_map(Word)
}

fn name() -> impl Strategy<Value = Option<Word>> + Clone {
    prop::option::weighted(0.8, word())
}

fn units<const N: usize>() -> impl Strategy<Value = [Unit; N]> + Clone {
    prop::array::uniform(unit())
}

/// An [`AttrDraw`].
///
/// Time: O(1) per value.
pub fn attr_draw() -> impl Strategy<Value = AttrDraw> + Clone {
    (pick(), units::<4>(), any::<u8>()).prop_map(|(which, values, len)| AttrDraw {
        which,
        values,
        len,
    })
}

fn extras() -> impl Strategy<Value = Vec<AttrDraw>> + Clone {
    vec(attr_draw(), 0..4)
}

fn shape() -> impl Strategy<Value = Shape> + Clone {
    prop_oneof![
        3 => Just(Shape::Sphere),
        2 => Just(Shape::Box),
        2 => Just(Shape::Capsule),
        1 => Just(Shape::Cylinder),
        1 => Just(Shape::Ellipsoid),
        1 => Just(Shape::Plane),
        1 => pick().prop_map(Shape::Mesh),
    ]
}

/// A [`GeomRecipe`].
///
/// Time: O(1) per value.
pub fn geom() -> impl Strategy<Value = GeomRecipe> + Clone {
    (
        name(),
        shape(),
        units::<3>(),
        prop::option::weighted(0.3, pick()),
        prop::option::weighted(0.3, pick()),
        extras(),
    )
        .prop_map(|(name, shape, size, class, material, extras)| GeomRecipe {
            name,
            shape,
            size,
            class,
            material,
            extras,
        })
}

fn joint_kind() -> impl Strategy<Value = JointKind> + Clone {
    prop_oneof![3 => Just(JointKind::Hinge), 2 => Just(JointKind::Slide), 1 => Just(JointKind::Ball)]
}

/// A [`FrameRecipe`]: nothing, a freejoint, or one to three joints.
///
/// Time: O(1) per value.
pub fn frame() -> impl Strategy<Value = FrameRecipe> + Clone {
    let joint = (name(), joint_kind(), units::<3>()).prop_map(|(name, kind, axis)| FrameJoint {
        name,
        kind,
        axis,
    });
    prop_oneof![
        2 => Just(FrameRecipe::default()),
        2 => Just(FrameRecipe { free: true, joints: Vec::new() }),
        2 => vec(joint, 1..4).prop_map(|joints| FrameRecipe { free: false, joints }),
    ]
}

fn settings() -> impl Strategy<Value = Settings> + Clone {
    (prop::option::weighted(0.3, 0u8..4), prop::option::weighted(0.1, any::<bool>()))
        .prop_map(|(timestep, radian)| Settings { timestep, radian })
}

/// One [`Step`]; `Attach` steps (with child recipes `depth - 1` deep) only when
/// `depth > 0`.
///
/// Time: O(1) to make; O(size) per value.
pub fn step(depth: u32) -> BoxedStrategy<Step> {
    step_in(depth, Palette::Valid)
}

/// One [`Step`] for recipes of `palette`: [`step`], and for the other palettes than
/// [`Palette::Valid`] MuJoCo `<frame>`s too (places to put bodies and sites in).
///
/// Time: O(1) to make; O(size) per value.
pub fn step_in(depth: u32, palette: Palette) -> BoxedStrategy<Step> {
    let mut arms: Vec<(u32, BoxedStrategy<Step>)> = vec![
        (6, body()),
        (3, geom_step()),
        (3, site()),
        (4, joint()),
        (1, camera()),
        (1, light()),
        (2, class()),
        (1, material()),
        (1, mesh()),
        (3, actuator()),
        (2, sensor()),
        (1, tendon()),
        (1, equality()),
        (1, exclude()),
        (1, pair()),
    ];
    if palette != Palette::Valid {
        arms.push((
            2,
            (pick(), units::<3>(), units::<3>())
                .prop_map(|(parent, pos, euler)| Step::Frame { parent, pos, euler })
                .boxed(),
        ));
    }
    if depth > 0 {
        arms.push((
            3,
            (pick(), recipe_in(depth - 1, 12, palette), frame())
                .prop_map(|(at, child, frame)| Step::Attach { at, child: Box::new(child), frame })
                .boxed(),
        ));
        arms.push((
            1,
            (pick(), pick(), frame())
                .prop_map(|(at, child, frame)| Step::AttachAgain { at, child, frame })
                .boxed(),
        ));
    }
    Union::new_weighted(arms).boxed()
}

/// `Step::Body`: a body with a geom (some free, some with a child class).
fn body() -> BoxedStrategy<Step> {
    (
        pick(),
        name(),
        units::<3>(),
        geom(),
        prop::bool::weighted(0.3),
        prop::option::weighted(0.3, pick()),
        extras(),
    )
        .prop_map(|(parent, name, pos, geom, free, childclass, extras)| Step::Body {
            parent,
            name,
            pos,
            geom,
            free,
            childclass,
            extras,
        })
        .boxed()
}

/// `Step::Geom`: a geom.
fn geom_step() -> BoxedStrategy<Step> {
    (pick(), geom()).prop_map(|(parent, geom)| Step::Geom { parent, geom }).boxed()
}

/// `Step::Site`: a site.
fn site() -> BoxedStrategy<Step> {
    (pick(), name(), units::<3>(), extras())
        .prop_map(|(parent, name, pos, extras)| Step::Site { parent, name, pos, extras })
        .boxed()
}

/// `Step::Joint`: a joint (some with a range, some with a class).
fn joint() -> BoxedStrategy<Step> {
    (
        pick(),
        name(),
        joint_kind(),
        units::<3>(),
        prop::option::weighted(0.5, units::<2>()),
        prop::option::weighted(0.3, pick()),
        extras(),
    )
        .prop_map(|(body, name, kind, axis, range, class, extras)| Step::Joint {
            body,
            name,
            kind,
            axis,
            range,
            class,
            extras,
        })
        .boxed()
}

/// `Step::Camera`: a camera.
fn camera() -> BoxedStrategy<Step> {
    (pick(), name(), extras())
        .prop_map(|(parent, name, extras)| Step::Camera { parent, name, extras })
        .boxed()
}

/// `Step::Light`: a light.
fn light() -> BoxedStrategy<Step> {
    (pick(), name(), extras())
        .prop_map(|(parent, name, extras)| Step::Light { parent, name, extras })
        .boxed()
}

/// `Step::Class`: a default class with up to three geom, joint and site defaults.
fn class() -> BoxedStrategy<Step> {
    (
        pick(),
        word(),
        vec(
            (
                prop_oneof![
                    Just(DefaultTag::Geom),
                    Just(DefaultTag::Joint),
                    Just(DefaultTag::Site)
                ],
                attr_draw(),
            ),
            0..4,
        ),
    )
        .prop_map(|(parent, name, defaults)| Step::Class { parent, name, defaults })
        .boxed()
}

/// `Step::Material`: a material.
fn material() -> BoxedStrategy<Step> {
    (word(), extras()).prop_map(|(name, extras)| Step::Material { name, extras }).boxed()
}

/// `Step::Mesh`: a mesh.
fn mesh() -> BoxedStrategy<Step> {
    (word(), units::<3>()).prop_map(|(name, scale)| Step::Mesh { name, scale }).boxed()
}

/// `Step::Actuator`: a motor, position or velocity actuator.
fn actuator() -> BoxedStrategy<Step> {
    (
        prop_oneof![
            Just(ActuatorKind::Motor),
            Just(ActuatorKind::Position),
            Just(ActuatorKind::Velocity)
        ],
        name(),
        pick(),
        extras(),
    )
        .prop_map(|(kind, name, joint, extras)| Step::Actuator { kind, name, joint, extras })
        .boxed()
}

/// `Step::Sensor`: a joint, site or frame sensor.
fn sensor() -> BoxedStrategy<Step> {
    (
        prop_oneof![
            Just(SensorKind::JointPos),
            Just(SensorKind::JointVel),
            Just(SensorKind::Touch),
            Just(SensorKind::Accelerometer),
            Just(SensorKind::Gyro),
            prop_oneof![Just(ObjKind::Body), Just(ObjKind::Geom), Just(ObjKind::Site)]
                .prop_map(SensorKind::FramePos),
        ],
        name(),
        pick(),
        extras(),
    )
        .prop_map(|(kind, name, target, extras)| Step::Sensor { kind, name, target, extras })
        .boxed()
}

/// `Step::Tendon`: a fixed tendon over one to three joints.
fn tendon() -> BoxedStrategy<Step> {
    (name(), vec((pick(), unit()), 1..4))
        .prop_map(|(name, joints)| Step::Tendon { name, joints })
        .boxed()
}

/// `Step::Equality`: a connect, weld or joint equality.
fn equality() -> BoxedStrategy<Step> {
    (
        prop_oneof![
            Just(EqualityKind::Connect),
            Just(EqualityKind::Weld),
            Just(EqualityKind::Joint)
        ],
        name(),
        pick(),
        pick(),
    )
        .prop_map(|(kind, name, first, second)| Step::Equality { kind, name, first, second })
        .boxed()
}

/// `Step::Exclude`: a contact exclude.
fn exclude() -> BoxedStrategy<Step> {
    (pick(), pick()).prop_map(|(first, second)| Step::Exclude { first, second }).boxed()
}

/// `Step::Pair`: a contact pair.
fn pair() -> BoxedStrategy<Step> {
    (pick(), pick()).prop_map(|(first, second)| Step::Pair { first, second }).boxed()
}

/// A recipe of up to `max_steps` steps whose attachments nest up to `depth` levels.
///
/// Time: O(1) to make; O(size) per value.
pub fn recipe(depth: u32, max_steps: usize) -> BoxedStrategy<ModelRecipe> {
    recipe_in(depth, max_steps, Palette::Valid)
}

/// [`recipe`] of `palette`: its steps are [`step_in`] that palette.
///
/// Time: O(1) to make; O(size) per value.
pub fn recipe_in(depth: u32, max_steps: usize, palette: Palette) -> BoxedStrategy<ModelRecipe> {
    (model_word(), settings(), vec(step_in(depth, palette), 0..=max_steps))
        .prop_map(move |(name, settings, steps)| ModelRecipe { name, settings, steps, palette })
        .boxed()
}

/// A recipe of a model without attachments: up to 24 steps.
///
/// Time: O(1) to make; O(size) per value.
pub fn model_recipe() -> BoxedStrategy<ModelRecipe> {
    recipe(0, 24)
}

/// A recipe of a model to attach: [`model_recipe`] that starts with a site in the
/// worldbody and a body holding a site, so it has places to attach at itself.
///
/// Time: O(1) to make; O(size) per value.
pub fn attachable_recipe() -> BoxedStrategy<ModelRecipe> {
    (model_recipe(), units::<3>(), geom())
        .prop_map(|(mut r, pos, geom)| {
            let site = |parent| Step::Site {
                parent: Pick(parent),
                name: Some(Word(0)),
                pos,
                extras: vec![],
            };
            let body = Step::Body {
                parent: Pick(0),
                name: Some(Word(3)),
                pos,
                geom,
                free: false,
                childclass: None,
                extras: vec![],
            };
            let mut steps = vec![site(0), body, site(1)];
            steps.append(&mut r.steps);
            r.steps = steps;
            r
        })
        .boxed()
}

/// A recipe of a composed scene: up to 24 steps, attachments of
/// [`attachable_recipe`]-like models nested up to two levels (at sites of the scene
/// and of what is attached to it, frames with joints or freejoints), models attached
/// more than once.
///
/// Time: O(1) to make; O(size) per value.
pub fn scene_recipe() -> BoxedStrategy<ModelRecipe> {
    (recipe(2, 24), attachable_recipe(), frame())
        .prop_map(|(mut r, child, frame)| {
            // At least one attachment, at the world, first.
            r.steps.insert(0, Step::Attach { at: Pick(0), child: Box::new(child), frame });
            r
        })
        .boxed()
}

/// A recipe of a model to attach in `palette`: [`attachable_recipe`], and for the
/// other palettes than [`Palette::Valid`] its body moves (a joint of any type) and
/// holds a `<frame>` with a site, so what is attached at them is below a moving body.
///
/// Time: O(1) to make; O(size) per value.
pub fn attachable_recipe_in(palette: Palette) -> BoxedStrategy<ModelRecipe> {
    if palette == Palette::Valid {
        return attachable_recipe();
    }
    (recipe_in(0, 24, palette), units::<3>(), geom(), joint_kind(), units::<3>())
        .prop_map(move |(mut r, pos, geom, kind, axis)| {
            let mut steps = moving_body_with_site(pos, geom, kind, axis, false);
            steps.insert(
                0,
                Step::Site { parent: Pick(0), name: Some(Word(0)), pos, extras: vec![] },
            );
            // A `<frame>` in the body ([world, base, frame] are the parents), a site in it.
            steps.push(Step::Frame { parent: Pick(1), pos, euler: axis });
            steps.push(Step::Site { parent: Pick(2), name: Some(Word(1)), pos, extras: vec![] });
            steps.append(&mut r.steps);
            r.steps = steps;
            r
        })
        .boxed()
}

/// The steps of a body in the worldbody (the first body), moving by a joint of
/// `kind` or, when `free`, a freejoint, with a site.
fn moving_body_with_site(
    pos: [Unit; 3],
    geom: GeomRecipe,
    kind: JointKind,
    axis: [Unit; 3],
    free: bool,
) -> Vec<Step> {
    let mut steps = vec![Step::Body {
        parent: Pick(0),
        name: Some(Word(3)),
        pos,
        geom,
        free,
        childclass: None,
        extras: vec![],
    }];
    if !free {
        steps.push(Step::Joint {
            body: Pick(0),
            name: Some(Word(4)),
            kind,
            axis,
            range: None,
            class: None,
            extras: vec![],
        });
    }
    steps.push(Step::Site { parent: Pick(1), name: Some(Word(2)), pos, extras: vec![] });
    steps
}

/// A recipe of a composed scene in `palette`: [`scene_recipe`] (for
/// [`Palette::Valid`], the same recipes), and for the other palettes it starts with
/// a moving body (a joint of any type, or a freejoint) with a site, and a model
/// ([`attachable_recipe_in`]) attached there, below the moving body; its steps are
/// [`step_in`] the palette.
///
/// [`Palette::Wide`] scenes are what `mjcf-mujoco`'s judge compares `check` with
/// MuJoCo on; [`Palette::Simulates`] scenes are for properties that simulate every
/// scene.
///
/// Time: O(1) to make; O(size) per value.
pub fn scene_recipe_in(palette: Palette) -> BoxedStrategy<ModelRecipe> {
    if palette == Palette::Valid {
        return scene_recipe();
    }
    let moving = (units::<3>(), geom(), joint_kind(), units::<3>(), prop::bool::weighted(0.25));
    let children = (attachable_recipe_in(palette), attachable_recipe_in(palette));
    (recipe_in(2, 24, palette), children, frame(), frame(), moving)
        .prop_map(move |(mut r, (c1, c2), f1, f2, (pos, geom, kind, axis, free))| {
            let mut steps = moving_body_with_site(pos, geom, kind, axis, free);
            // The site in the moving body is the first site.
            steps.push(Step::Attach { at: Pick(1), child: Box::new(c2), frame: f2 });
            steps.push(Step::Attach { at: Pick(0), child: Box::new(c1), frame: f1 });
            steps.append(&mut r.steps);
            r.steps = steps;
            r
        })
        .boxed()
}

/// One [`Edit`].
///
/// Time: O(1) to make; O(size) per value.
pub fn edit() -> BoxedStrategy<Edit> {
    prop_oneof![
        6 => step(1).prop_map(Edit::Add),
        4 => (pick(), attr_draw()).prop_map(|(target, attr)| Edit::Set { target, attr }),
        2 => (pick(), prop::option::weighted(0.8, word())).prop_map(|(target, name)| Edit::Rename { target, name }),
        3 => pick().prop_map(|target| Edit::Remove { target }),
        2 => pick().prop_map(|scope| Edit::Detach { scope }),
        1 => (pick(), model_word()).prop_map(|(scope, to)| Edit::RenameScope { scope, to }),
        1 => (recipe(0, 8), any::<bool>())
            .prop_map(|(source, override_attributes)| Edit::IncludeCopy { source, override_attributes }),
    ]
    .boxed()
}

/// An [`EditRecipe`] of up to 16 edits.
///
/// Time: O(1) to make; O(size) per value.
pub fn edit_recipe() -> BoxedStrategy<EditRecipe> {
    vec(edit(), 0..=16).prop_map(|edits| EditRecipe { edits }).boxed()
}

/// A scene recipe and edits to apply to the model it builds.
///
/// Time: O(1) to make; O(size) per value.
pub fn scene_and_edits() -> BoxedStrategy<(ModelRecipe, EditRecipe)> {
    (scene_recipe(), edit_recipe()).boxed()
}

/// Models built from [`model_recipe`]s.
///
/// Time: O(1) to make; each value is built ([`ModelRecipe::build`]).
pub fn models() -> BoxedStrategy<Model> {
    model_recipe().prop_map(|r| r.build()).boxed()
}

/// Composed models built from [`scene_recipe`]s.
///
/// Time: O(1) to make; each value is built ([`ModelRecipe::build`]).
pub fn scenes() -> BoxedStrategy<Model> {
    scene_recipe().prop_map(|r| r.build()).boxed()
}
