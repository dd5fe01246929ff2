//! What steps and edits pick from: the elements of a model as recipes choose them
//! ([`Pick`] takes one of them modulo their number).

use crate::model::{Event, JointType, Loc, Model};
use crate::schema::{ElementKind, Namespace, Role};

use super::recipe::{JointKind, Pick};

pub(super) fn view(m: &Model, loc: &Loc) -> Option<(&'static str, ElementKind, bool)> {
    let e = m.element(loc)?;
    Some((e.tag(), e.kind(), e.is_frame()))
}

/// The worldbody, then every body that is not an attachment frame, then every MuJoCo
/// `<frame>` (inside attachments too).
pub(super) fn body_parents(m: &Model) -> Vec<Loc> {
    let mut out = vec![m.worldbody()];
    out.extend(m.find_all(Namespace::Body).into_iter().filter(|l| !is_frame(m, l)));
    out.extend(elements(m, |t| t.kind.is(Role::Frame) && !t.frame).into_iter().map(|t| t.loc));
    out
}

pub(super) fn is_frame(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| e.is_frame())
}

/// Whether a joint of this kind fits in a body after its joints: at most 6 degrees of
/// freedom, and no rotation after a ball (MuJoCo: "ball followed by rotation").
pub(super) fn joint_fits(m: &Model, body: &Loc, kind: JointKind) -> bool {
    let ball = m
        .element(body)
        .is_some_and(|e| e.children().any(|c| c.joint_type() == Some(JointType::Ball)));
    dofs(m, body) + kind.dofs() <= 6 && !(ball && kind != JointKind::Slide)
}

/// The degrees of freedom of a body's own joints (a freejoint has 6).
pub(super) fn dofs(m: &Model, loc: &Loc) -> usize {
    m.element(loc)
        .map_or(6, |e| e.children().filter_map(|c| c.joint_type()).map(JointType::nv).sum())
}

/// The named elements of this model's own tree in `ns` that pass `keep`, with their
/// names.
pub(super) fn named(m: &Model, ns: Namespace, keep: impl Fn(&Model, &Loc) -> bool) -> Vec<String> {
    m.find_all(ns)
        .into_iter()
        .filter(|l| !l.is_scoped() && keep(m, l))
        .filter(|l| !m.element(l).and_then(|e| e.parent()).is_some_and(|p| p.is_frame()))
        .filter_map(|l| m.element(&l)?.identifier().map(str::to_string))
        .collect()
}

/// Whether a joint moves along or about one axis (a hinge or a slide).
pub(super) fn scalar_joint(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| {
        e.kind().is(Role::Joint)
            && matches!(e.joint_type(), Some(JointType::Hinge | JointType::Slide))
    })
}

pub(super) fn not_plane(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| e.string("type") != Some("plane"))
}

pub(super) fn not_frame(m: &Model, loc: &Loc) -> bool {
    !is_frame(m, loc)
}

pub(super) fn any(_: &Model, _: &Loc) -> bool {
    true
}

/// Two different items, picked by `a` and `b`.
pub(super) fn two(items: &[String], a: Pick, b: Pick) -> Option<(&str, &str)> {
    let x = a.of(items)?;
    let rest: Vec<&String> = items.iter().filter(|s| *s != x).collect();
    Some((x, b.of(&rest)?))
}

/// Whether the model has no more problems than allowed.
pub(super) fn valid(m: &Model, allowed: usize) -> bool {
    m.check().len() <= allowed
}

/// The kind of the root default class.
pub(super) fn m_default_kind() -> ElementKind {
    ElementKind::DEFAULT
}

/// An element of the composed model, as edits pick them.
pub(super) struct Target {
    pub(super) loc: Loc,
    pub(super) tag: &'static str,
    pub(super) kind: ElementKind,
    pub(super) frame: bool,
    pub(super) in_default: bool,
    /// A child of an attachment frame (a frame joint or inertial).
    pub(super) in_frame: bool,
    pub(super) removable: bool,
}

/// The elements of the composed model (walk order) that pass `keep`.
pub(super) fn elements(m: &Model, keep: impl Fn(&Target) -> bool) -> Vec<Target> {
    let mut out = Vec::new();
    // Per open element: whether it is an attachment frame.
    let mut stack: Vec<bool> = Vec::new();
    for event in m.walk() {
        match event {
            Event::Enter(e) => {
                let parent_frame = stack.last().copied().unwrap_or(false);
                let kind = e.kind();
                let multiplicity = kind.multiplicity();
                let t = Target {
                    loc: e.loc(),
                    tag: e.tag(),
                    kind,
                    frame: e.is_frame(),
                    in_default: kind.spec().parent.is_some_and(|p| p.is(Role::DefaultClass)),
                    in_frame: parent_frame,
                    removable: stack.len() >= 2
                        && !e.is_frame()
                        && multiplicity != crate::schema::Multiplicity::Singleton,
                };
                stack.push(e.is_frame());
                if keep(&t) {
                    out.push(t);
                }
            }
            Event::Leave(_) => {
                stack.pop();
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_body_s_joints_count_by_the_type_in_force_their_classes_included() {
        let m = Model::from_xml_str(
            r#"<mujoco><default><default class="b"><joint type="ball"/></default></default>
               <worldbody><body name="x"><joint name="cb" class="b"/><joint name="s" type="slide"/>
                 <geom size="1"/></body>
               <body name="f"><joint type="free"/><geom size="1"/></body></worldbody></mujoco>"#,
        )
        .unwrap();
        let (x, f) = (m.find(Namespace::Body, "x").unwrap(), m.find(Namespace::Body, "f").unwrap());
        assert_eq!(dofs(&m, &x), 4);
        assert_eq!(dofs(&m, &f), 6);
        // A ball by its class: no rotation after it, a slide fits.
        assert!(!joint_fits(&m, &x, JointKind::Hinge));
        assert!(joint_fits(&m, &x, JointKind::Slide));
        assert!(!scalar_joint(&m, &m.find(Namespace::Joint, "cb").unwrap()));
        assert!(scalar_joint(&m, &m.find(Namespace::Joint, "s").unwrap()));
    }
}
