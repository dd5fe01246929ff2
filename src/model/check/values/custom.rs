//! The checks of a `<custom>` tuple (MuJoCo's `mjCTuple::Compile`, and the object
//! types its XML reader knows).

use crate::schema::ElementKind;

use super::{Check, found, found_element, on};

/// The object types MuJoCo 4.0.0 names (`mju_str2Type`), spelled as it spells them.
const OBJECT_TYPES: [&str; 26] = [
    "body", "xbody", "joint", "dof", "geom", "site", "camera", "light", "flex", "mesh", "skin",
    "hfield", "texture", "material", "pair", "exclude", "equality", "tendon", "actuator", "sensor",
    "numeric", "text", "tuple", "key", "plugin", "frame",
];

/// An `<element>` of a tuple (a tuple's only child kind).
fn tuple_element(k: ElementKind) -> bool {
    k.spec().parent.is_some_and(|p| on::at(p, "custom/tuple"))
}

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "tuple-empty",
        on: |k| on::at(k, "custom/tuple"),
        test: |at| {
            at.e.node.children().is_empty().then_some(())?;
            found_element(format!("tuple '{}' is empty", at.name()))
        },
        fix: "give the tuple an element, or remove it",
    },
    Check {
        name: "tuple-object-type",
        on: tuple_element,
        test: |at| {
            (!OBJECT_TYPES.contains(&at.str("objtype")?)).then_some(())?;
            found("objtype", "unknown object type")
        },
        fix: "use an object type MuJoCo knows (body, joint, geom, site, ...)",
    },
];

#[cfg(test)]
mod tests {
    use super::super::tests::assert_pairs;

    /// Each pair's verdicts are MuJoCo 4.0.0's.
    #[test]
    fn a_tuple_needs_elements_of_known_object_types() {
        let with = |custom: &str| {
            format!(
                r#"<mujoco><worldbody><body name="b"><joint name="j"/><geom size=".1"/></body></worldbody>
                <custom>{custom}</custom></mujoco>"#
            )
        };
        let element = |ty: &str| {
            with(&format!(r#"<tuple name="t"><element objtype="{ty}" objname="b"/></tuple>"#))
        };
        assert_pairs("tuple-empty", &[(&with(r#"<tuple name="t"/>"#), &element("body"))]);
        for (bad, good) in [("nope", "xbody"), ("Body", "body"), ("unknown", "body")] {
            assert_pairs("tuple-object-type", &[(&element(bad), &element(good))]);
        }
    }
}
