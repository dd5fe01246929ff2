//! Rule *arrays as long as MuJoCo reads them* ([`ProblemKind::ArrayTooShort`],
//! [`ProblemKind::ArrayNotMultiple`]); the minimums are in `model::arrays`.

use crate::model::arrays::{MULTIPLES, array_len, geom_size_needed, minimum};
use crate::model::layout::{effective, from_classes};
use crate::schema::{AttrType, Role};
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

/// The arrays MuJoCo refuses for their length: shorter than MuJoCo reads (the
/// table), a geom `size` with fewer numbers than its type needs (counting those its
/// classes give; not for a geom with a mesh, which MuJoCo sizes), mesh data not a
/// multiple of 3 (or 2).
#[derive(Default)]
pub(super) struct ArrayLengths;

impl<'m> Rule<'m> for ArrayLengths {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let (node, kind) = (e.node, e.node.kind());
        for (i, v) in node.attrs() {
            let i = *i as usize;
            let (Some(found), AttrType::Array { .. }) = (array_len(v), &kind.attr(i).ty) else {
                continue;
            };
            let attribute = kind.attr(i).name;
            if let Some(minimum) = minimum(kind, i).filter(|m| found < *m) {
                out.push(ProblemKind::ArrayTooShort { attribute, minimum, found });
            }
            if let Some((_, _, of)) =
                MULTIPLES.iter().find(|(t, a, _)| *t == kind.tag() && *a == attribute)
            {
                if found % of != 0 {
                    out.push(ProblemKind::ArrayNotMultiple { attribute, of: *of, found });
                }
            }
        }
        // A geom with a mesh MuJoCo sizes itself (fitting a primitive to the mesh).
        if kind.is(Role::Geom) && effective(e.model, node, e.class, "mesh").is_none() {
            let (m, class) = (e.model, e.class);
            let ty = effective(m, node, class, "type").and_then(Value::as_str).unwrap_or("sphere");
            let needed = geom_size_needed(ty, effective(m, node, class, "fromto").is_some());
            let own = kind.attr_index("size").and_then(|i| node.attr(i)).and_then(array_len);
            let given = from_classes(m, kind, class, "size").and_then(array_len);
            let found = own.unwrap_or(0).max(given.unwrap_or(0));
            if found < needed && (own.is_some() || given.is_some()) {
                out.push(ProblemKind::ArrayTooShort { attribute: "size", minimum: needed, found });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::model::check::tests::kinds_of;

    #[test]
    fn a_short_array_a_short_geom_size_and_mesh_data_not_in_whole_items_are_found() {
        let m = Model::from_xml_str(
            r#"<mujoco><default><geom type="box"/></default>
               <asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1 1"/></asset>
               <worldbody><body pos="1 2"><geom size="1 1"/><geom size="1 1 1"/></body></worldbody></mujoco>"#,
        )
        .unwrap();
        assert_eq!(
            kinds_of(&m, ArrayLengths),
            [
                ProblemKind::ArrayNotMultiple { attribute: "vertex", of: 3, found: 13 },
                ProblemKind::ArrayTooShort { attribute: "pos", minimum: 3, found: 2 },
                ProblemKind::ArrayTooShort { attribute: "size", minimum: 3, found: 2 },
            ]
        );
    }

    /// Each verdict is MuJoCo 4.0.0's: a primitive fitted to a mesh takes its size
    /// from the mesh, whatever its own `size` holds.
    #[test]
    fn a_geom_fitted_to_a_mesh_needs_no_size_of_its_type() {
        let mesh = r#"<asset><mesh name="m" vertex="0 0 0 1 0 0 0 1 0 0 0 1"/></asset>"#;
        let m = |body: &str| {
            Model::from_xml_str(&format!("<mujoco>{mesh}<worldbody>{body}</worldbody></mujoco>"))
                .unwrap()
        };
        for compiled in [
            m(r#"<geom type="capsule" mesh="m" size=".1"/>"#),
            m(r#"<geom type="box" mesh="m" size=".1 .2"/>"#),
        ] {
            assert_eq!(kinds_of(&compiled, ArrayLengths), []);
        }
        assert_eq!(
            kinds_of(&m(r#"<geom type="capsule" size=".1"/>"#), ArrayLengths),
            [ProblemKind::ArrayTooShort { attribute: "size", minimum: 2, found: 1 }]
        );
    }
}
