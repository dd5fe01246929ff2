//! What the simulating palette ([`Palette::Simulates`](super::Palette::Simulates))
//! does once a model is built: which geoms collide with which.
//!
//! Generated bodies are placed at random, so two of them often start deep inside one
//! another. A free body pushed out of another moves away; but two bodies that only
//! turn or slide about their joints (or a body and a static geom) may be unable to
//! part, and MuJoCo's contact forces between them then pump energy in until the
//! simulation diverges (most of the generated scenes that diverged before this rule
//! did so). So in a simulating model every geom is of one of three contact classes,
//! by the nearest body at or above it that moves: a static geom (none moves) and a
//! free geom (a freejoint) collide with every free geom; an articulated geom (other
//! joints) collides with free geoms only.

use crate::model::{Attrs, Event, JointType, Loc, Model};
use crate::schema::Role;

/// A geom's contact class: by the nearest moving body at or above it.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum ContactClass {
    /// Nothing above it moves.
    Static,
    /// A freejoint moves it.
    Free,
    /// Other joints move it.
    Articulated,
}

impl ContactClass {
    /// `contype` and `conaffinity`: a pair collides when one's `contype` shares a
    /// bit with the other's `conaffinity`.
    pub(super) fn bits(self) -> (i32, i32) {
        match self {
            ContactClass::Static => (1, 1),
            ContactClass::Free => (1, 3),
            ContactClass::Articulated => (2, 0),
        }
    }
}

/// Every geom of the composed model with its contact class.
pub(super) fn contact_classes(m: &Model) -> Vec<(Loc, ContactClass)> {
    let mut out = Vec::new();
    let mut stack: Vec<ContactClass> = Vec::new();
    for event in m.walk() {
        match event {
            Event::Enter(e) => {
                let above = stack.last().copied().unwrap_or(ContactClass::Static);
                let mut own = above;
                if e.kind().is(Role::Body) || e.is_frame() {
                    for c in e.children() {
                        if c.joint_type() == Some(JointType::Free) {
                            own = ContactClass::Free;
                            break;
                        }
                        if c.kind().is(Role::Joint) {
                            own = ContactClass::Articulated;
                        }
                    }
                }
                if e.kind().is(Role::Geom) {
                    out.push((e.loc(), above));
                }
                stack.push(own);
            }
            Event::Leave(_) => {
                stack.pop();
            }
        }
    }
    out
}

/// The model with every geom's `contype` and `conaffinity` set by its contact class
/// (a geom of a default class keeps none of the class's).
pub(super) fn with_contact_classes(m: Model) -> Model {
    let mut cur = m;
    for (loc, class) in contact_classes(&cur) {
        let (t, a) = class.bits();
        if let Ok(next) = cur.set(&loc, Attrs::new().set("contype", t).set("conaffinity", a)) {
            cur = next;
        }
    }
    cur
}
