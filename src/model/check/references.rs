//! Rule *references resolve* ([`ProblemKind::DanglingReference`],
//! [`ProblemKind::MissingRequired`], [`ProblemKind::RemovedReference`]).

use std::collections::HashMap;

use smol_str::SmolStr;

use crate::model::layout::from_classes;
use crate::model::tree::ElementId;
use crate::schema::{AttrType, Namespace, Role};
use crate::suggest::Suggester;
use crate::value::{Reference, Value};

use super::ProblemKind;
use super::walk::{Event, Rule};
use crate::model::Model;
use crate::model::tree::Node;

/// Names ranked for suggestions, per model (walk instance) and namespace, each made
/// once.
pub(super) type Suggesters<'m> = HashMap<(usize, Namespace), Suggester<'m>>;

/// The rule: each element's references, with suggestions ranked once per model and
/// namespace.
#[derive(Default)]
pub(super) struct References<'m> {
    suggesters: Suggesters<'m>,
}

impl<'m> Rule<'m> for References<'m> {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let found = unresolved_references(e.model, e.inst, e.node, e.class, &mut self.suggesters);
        out.extend(found);
    }
}

/// Rule *references resolve*: each reference by name of `node` (of the model `m`,
/// walk instance `inst`) names an element of its own model or a builtin name
/// ([`ProblemKind::DanglingReference`], with the nearest names), and each resolved
/// reference an element still there ([`ProblemKind::MissingRequired`] for a required
/// attribute, [`ProblemKind::RemovedReference`] for an optional one). A reference
/// its default classes (`class` in force) give it counts as its own; an element of a
/// default class is judged where it is used, not on its own (MuJoCo compiles a class
/// whose reference no element uses). A name that the writer gives an element of `m`
/// (an attachment frame's `scope/`, a frame joint's, an automatic
/// `//unnamed_joint_0`) resolves too: MuJoCo finds it in the written model.
fn unresolved_references<'m>(
    m: &'m Model,
    inst: usize,
    node: &'m Node,
    class: Option<ElementId>,
    suggesters: &mut Suggesters<'m>,
) -> Vec<ProblemKind> {
    let kind = node.kind();
    let mut out = Vec::new();
    if kind.spec().parent.is_some_and(|p| p.is(Role::DefaultClass)) {
        return out;
    }
    let own = node.attrs().iter().map(|(i, v)| (*i as usize, v));
    let inherited = (0..kind.spec().attrs.len())
        .filter(|&i| node.attr(i).is_none())
        .filter(|&i| matches!(kind.attr(i).ty, AttrType::Reference(t) if t.namespace(None) != Some(Namespace::Default)))
        .filter_map(|i| Some((i, from_classes(m, kind, class, kind.attr(i).name)?)));
    for (i, v) in own.chain(inherited) {
        let spec = kind.attr(i);
        match v {
            Value::Reference(Reference::Name(n)) => {
                let Some(ns) = node.reference_namespace(i) else { continue };
                if super::naming::is_builtin_name(ns, n)
                    || m.index.names.contains_key(&(ns, n.clone()))
                {
                    continue;
                }
                if ns == Namespace::AttachmentFrame || m.find(ns, n).is_some() {
                    continue;
                }
                if super::expansion::named_by_expansion(m, ns, n) {
                    continue;
                }
                // A name the writer gives (frames, frame joints, automatic names).
                if n.contains('/') && m.from_full_name(ns, n).is_some() {
                    continue;
                }
                let ranked = suggesters.entry((inst, ns)).or_insert_with(|| {
                    Suggester::new(
                        m.index.names.keys().filter(|(k, _)| *k == ns).map(|(_, n)| n.as_str()),
                    )
                });
                let suggestions = ranked.nearest(n, 3).into_iter().map(SmolStr::from).collect();
                out.push(ProblemKind::DanglingReference {
                    attribute: spec.name,
                    name: n.clone(),
                    namespace: ns,
                    suggestions,
                });
            }
            Value::Reference(Reference::Element(id)) if !m.index.contains(*id) => {
                let attribute = spec.name;
                out.push(if spec.required {
                    ProblemKind::MissingRequired { attribute }
                } else {
                    ProblemKind::RemovedReference { attribute }
                });
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Element;
    use crate::model::check::tests::node;

    #[test]
    fn references_by_name_resolve_in_their_model_or_are_dangling_with_suggestions() {
        let mut m = Model::new("m");
        let b = m.add_mut(&m.worldbody(), Element::new("body").attr("name", "b")).unwrap();
        m.add_mut(&b, Element::new("joint").attr("name", "hinge")).unwrap();
        m.add_mut(&m.actuator(), Element::new("motor").attr("name", "ok").attr("joint", "hinge"))
            .unwrap();
        m.add_mut(&m.actuator(), Element::new("motor").attr("name", "typo").attr("joint", "hinj"))
            .unwrap();
        let mut suggesters = Suggesters::new();
        let ok = node(&m, Namespace::Actuator, "ok");
        assert_eq!(unresolved_references(&m, 0, ok, None, &mut suggesters), []);
        let typo = node(&m, Namespace::Actuator, "typo");
        assert_eq!(
            unresolved_references(&m, 0, typo, None, &mut suggesters),
            [ProblemKind::DanglingReference {
                attribute: "joint",
                name: "hinj".into(),
                namespace: Namespace::Joint,
                suggestions: vec!["hinge".into()],
            }]
        );
    }

    #[test]
    fn a_resolved_reference_to_a_removed_element_is_missing_or_removed_as_it_is_required() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="a"><joint name="j"/><geom size="1"/></body>
                 <body name="b"><geom size="1"/></body>
               </worldbody>
               <contact><exclude body1="a" body2="b"/></contact>
               <actuator><motor name="mo" joint="j"/></actuator></mujoco>"#,
        )
        .unwrap();
        let a = m.find(Namespace::Body, "a").unwrap();
        let removed = m.remove(&a).unwrap();
        let mut suggesters = Suggesters::new();
        let motor = node(&removed, Namespace::Actuator, "mo");
        assert_eq!(
            unresolved_references(&removed, 0, motor, None, &mut suggesters),
            [ProblemKind::RemovedReference { attribute: "joint" }]
        );
        let contact = removed.section("contact").unwrap();
        let exclude = removed.node_by_id(contact.id()).unwrap().children().iter().next().unwrap();
        assert_eq!(
            unresolved_references(&removed, 0, exclude, None, &mut suggesters),
            [ProblemKind::MissingRequired { attribute: "body1" }]
        );
    }

    #[test]
    fn references_to_replicated_copies_and_attached_parts_are_not_dangling() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <replicate count="3" offset="1 0 0">
                   <body name="b"><joint name="j"/><geom size=".1"/></body>
                 </replicate>
               </worldbody>
               <actuator><motor name="copy" joint="j2"/><motor name="base" joint="j"/>
                 <motor name="beyond" joint="j3"/></actuator></mujoco>"#,
        )
        .unwrap();
        let problems = |name: &str| {
            let mut suggesters = Suggesters::new();
            unresolved_references(&m, 0, node(&m, Namespace::Actuator, name), None, &mut suggesters)
                .len()
        };
        assert_eq!(problems("copy"), 0);
        assert_eq!(problems("base"), 0);
        assert_eq!(problems("beyond"), 1);
    }

    /// Verdicts of MuJoCo 4.0.0: a class's reference that no element uses compiles;
    /// one an element inherits is refused ("material 'nope' not found in geom 0").
    #[test]
    fn a_class_s_reference_is_judged_where_an_element_uses_it() {
        let count = |text: &str| {
            let m = Model::from_xml_str(text).unwrap();
            crate::model::check::tests::kinds_of(&m, References::default()).len()
        };
        let unused = r#"<mujoco><default><geom material="nope"/></default>
            <asset><material name="m"/></asset>
            <worldbody><geom size=".1" material="m"/></worldbody></mujoco>"#;
        assert_eq!(count(unused), 0);
        let used = r#"<mujoco><default><geom material="nope"/></default>
            <worldbody><geom size=".1"/></worldbody></mujoco>"#;
        assert_eq!(count(used), 1);
    }

    /// Names the writer gives: an attachment frame's `scope/` (a body) and an unnamed
    /// joint's automatic name, referred to from the model that holds them.
    #[test]
    fn names_the_writer_gives_resolve() {
        let mut child = Model::new("sens");
        child
            .add_mut(&child.worldbody(), crate::model::Element::new("body").attr("name", "b"))
            .unwrap();
        let mut m = Model::new("root");
        let b = m.add_mut(&m.worldbody(), crate::model::Element::new("body")).unwrap();
        m.add_mut(&b, crate::model::Element::new("joint")).unwrap();
        m.add_mut(&b, crate::model::Element::new("geom").attr("size", [0.1])).unwrap();
        m.attach_mut(&m.worldbody(), &child).unwrap();
        let frame_pos =
            crate::model::Element::new("framepos").attr("objtype", "body").attr("objname", "sens/");
        let sensor = m.section_for("framepos").unwrap();
        m.add_mut(&sensor, frame_pos).unwrap();
        let motor = crate::model::Element::new("motor").attr("joint", "//unnamed_joint_0");
        m.add_mut(&m.actuator(), motor).unwrap();
        assert_eq!(crate::model::check::tests::kinds_of(&m, References::default()), []);
    }
}
