//! The checks of data written inline (never read from a file): an asset mesh's
//! vertices and faces, a skin's vertices, faces and bones, a flex's elements and
//! vertices, each judged in the order MuJoCo 4.0.0's compiler judges them, so the
//! message is the first one MuJoCo gives.

use super::{At, Check, Found, found, found_element, hull, numbers, on};
use smol_str::SmolStr;

use super::super::expansion::named_by_expansion;
use crate::model::naming::is_builtin_name;
use crate::model::tree::Node;
use crate::schema::Namespace;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

pub(crate) const CHECKS: &[Check] = &[
    Check {
        name: "mesh-inline-data",
        on: |k: ElementKind| k.is(Role::Mesh),
        test: mesh_data,
        fix: "give at least 4 finite vertices (3 numbers each) and faces that name them",
    },
    Check {
        name: "skin-inline-data",
        on: |k| on::at(k, "asset/skin") || on::at(k, "deformable/skin"),
        test: skin_data,
        fix: "give the skin its vertices, faces and bones, each bone weighing existing vertices",
    },
    Check {
        name: "flex-inline-data",
        on: |k| on::at(k, "deformable/flex"),
        test: flex_data,
        fix: "give dim 1 to 3, dim+1 distinct existing vertices per element, and a body per vertex",
    },
    Check {
        name: "flex-poisson",
        on: |k| on::at(k, "(world)body/flexcomp"),
        test: poisson,
        fix: "give poisson in [0, 0.5)",
    },
];

/// A child's own value of `attr`, the first child of tag `tag`.
fn child_value<'m>(node: &'m Node, tag: &str, attr: &str) -> Option<&'m Value> {
    let child = node.children().iter().find(|c| c.kind().tag() == tag)?;
    child.attr(child.kind().attr_index(attr)?)
}

/// Numbers as whole numbers, if each is one.
fn whole(v: &[f64]) -> Option<Vec<i64>> {
    v.iter().map(|x| (x.fract() == 0.0 && x.abs() < 2e9).then_some(*x as i64)).collect()
}

/// `attr`'s own numbers, none when not written.
fn own(at: &At<'_, '_>, attr: &str) -> Vec<f64> {
    at.own_floats(attr).unwrap_or_default()
}

/// An asset mesh's vertices and faces as `mjCMesh` reads and first checks them: only
/// of a mesh whose data is all written (no file, builtin shape or plugin), and not
/// when visual assets may be discarded (MuJoCo then drops meshes no geom collides
/// with before judging them).
fn mesh_data(at: &At<'_, '_>) -> Option<Found> {
    if at.settings.discard_visual || at.has("file") || at.has("builtin") {
        return None;
    }
    let plugin = at.kind().child("plugin");
    if at.e.node.children().iter().any(|c| Some(c.kind()) == plugin) {
        return None;
    }
    let vert = own(at, "vertex");
    let face = own(at, "face");
    let normal = own(at, "normal");
    let texcoord = own(at, "texcoord");
    let message = if vert.len() % 3 != 0 {
        "vertex data must be a multiple of 3".to_string()
    } else if face.len() % 3 != 0 {
        "face data must be a multiple of 3".to_string()
    } else if let Some(i) = vert.chunks(3).position(|v| v.iter().any(|x| !x.is_finite())) {
        format!("vertex coordinate {i} is not finite")
    } else if vert.len() < 12 {
        "at least 4 vertices required".to_string()
    } else if normal.len() % 3 != 0 {
        "normal data must be a multiple of 3".to_string()
    } else if texcoord.len() % 2 != 0 {
        "texcoord must be a multiple of 2".to_string()
    } else if !texcoord.is_empty() && texcoord.len() != 2 * (vert.len() / 3) {
        "texcoord must be 2*nv if face texcoord indices are not provided in an OBJ file".to_string()
    } else {
        let nv = (vert.len() / 3) as i64;
        let face = whole(&face)?;
        match face.iter().enumerate().find(|(_, f)| **f < 0 || **f >= nv) {
            Some((i, f)) => format!("in face {}, vertex index {f} does not exist", i / 3),
            // Faces written: whether MuJoCo computes a hull depends on the geoms.
            None if face.is_empty() => hull::message(at, &vert)?,
            None => return None,
        }
    };
    found_element(message)
}

/// A skin's data as `mjCSkin` checks it (a skin read from a file is not judged):
/// all present, sizes, then each bone's vertex ids and the weight of each vertex
/// (summed in single precision, as MuJoCo sums them).
fn skin_data(at: &At<'_, '_>) -> Option<Found> {
    if at.has("file") {
        return None;
    }
    let vert = own(at, "vertex");
    let face = own(at, "face");
    let texcoord = own(at, "texcoord");
    let bone = at.kind().child("bone");
    let bones: Vec<&Node> =
        at.e.node.children().iter().filter(|c| Some(c.kind()) == bone).collect();
    let message = if vert.is_empty() || face.is_empty() || bones.is_empty() {
        "Missing data in skin".to_string()
    } else if vert.len() % 3 != 0 {
        "Vertex data must be multiple of 3".to_string()
    } else if !texcoord.is_empty() && texcoord.len() != 2 * vert.len() / 3 {
        "Vertex and texcoord data incompatible size".to_string()
    } else if face.len() % 3 != 0 {
        "Face data must be multiple of 3".to_string()
    } else if let Some(f) =
        whole(&face)?.into_iter().find(|f| *f < 0 || *f >= (vert.len() / 3) as i64)
    {
        format!("face vertex index {f} out of range in skin")
    } else {
        bone_message(&bones, vert.len() / 3)?
    };
    found_element(message)
}

/// What MuJoCo says of a skin's bones over `nvert` vertices, if anything.
fn bone_message(bones: &[&Node], nvert: usize) -> Option<String> {
    let mut weight = vec![0f32; nvert];
    for bone in bones {
        let ids = whole(&child_numbers(bone, "vertid")?)?;
        let weights = child_numbers(bone, "vertweight")?;
        if ids.len() != weights.len() || ids.is_empty() {
            return Some("vertid and vertweight must have same non-zero size in skin".into());
        }
        for (id, w) in ids.iter().zip(&weights) {
            if *id < 0 || *id >= nvert as i64 {
                return Some(format!("vertid {id} out of range in skin"));
            }
            weight[*id as usize] += *w as f32;
        }
    }
    let i = weight.iter().position(|w| f64::from(*w) <= 1e-15)?;
    Some(format!("vertex {i} must have positive total weight in skin"))
}

/// A node's own numbers of `attr`.
fn child_numbers(node: &Node, attr: &str) -> Option<Vec<f64>> {
    node.attr(node.kind().attr_index(attr)?).and_then(numbers)
}

/// A flex's sizes and elements as `mjCFlex` checks them, in its order, stopping at a
/// check it makes that this one does not (an interpolated flex, with nodes, is not
/// judged).
fn flex_data(at: &At<'_, '_>) -> Option<Found> {
    if at.has("node") {
        return None;
    }
    let dim = at.own_int("dim").unwrap_or(2);
    let elem = whole(&own(at, "element"))?;
    let vert = own(at, "vertex");
    let bodies: Vec<&str> = at.own_str("body").map_or(vec![], |b| b.split_whitespace().collect());
    if !(1..=3).contains(&dim) {
        return found("dim", "dim must be 1, 2 or 3");
    }
    if elem.is_empty() {
        return None;
    }
    if elem.len() % (dim as usize + 1) != 0 {
        return found("element", "elem size must be multiple of (dim+1)");
    }
    if bodies.is_empty() {
        return None;
    }
    if vert.len() % 3 != 0 {
        return found("vertex", "vert size must be a multiple of 3");
    }
    if edge_stiffness(at.e.node) > 0.0 && dim > 1 {
        return None;
    }
    let elasticity = |attr: &str| elasticity_number(at.e.node, attr);
    if elastic2d(at.e.node) {
        // Its 2d elasticity's checks: thickness, poisson, a 2d flex.
        (elasticity("thickness")? > 0.0).then_some(())?;
        if poisson_out(elasticity("poisson")?) {
            return found("poisson", "Poisson ratio must be in [0, 0.5)");
        }
        (dim == 2).then_some(())?;
    }
    let nvert = if vert.is_empty() { bodies.len() } else { vert.len() / 3 };
    if !vert.is_empty() && bodies.len() != 1 && bodies.len() != nvert {
        return found("body", "vertbody size must be 1 or nvert");
    }
    if (nvert as i64) < dim + 1 {
        return None;
    }
    if elem.iter().any(|e| *e < 0 || *e >= nvert as i64) {
        return found("element", "elem vertex id out of range");
    }
    let texcoord = own(at, "texcoord");
    if !texcoord.is_empty() && texcoord.len() != 2 * nvert {
        return None;
    }
    if at.own_str("material").is_some_and(|n| !known(at, Namespace::Material, n)) {
        return None;
    }
    if let Some(b) = bodies.iter().find(|b| !known(at, Namespace::Body, b)) {
        return found("body", format!("unknown body '{b}' in flex"));
    }
    let repeated = elem.chunks(dim as usize + 1).any(|e| {
        let mut e = e.to_vec();
        e.sort_unstable();
        e.windows(2).any(|w| w[0] == w[1])
    });
    if repeated {
        return found("element", "repeated vertex in element");
    }
    // Without a 2d elasticity, MuJoCo judges the poisson ratio of a positive young's
    // modulus after all the above.
    (elasticity("young")? > 0.0 && poisson_out(elasticity("poisson")?)).then_some(())?;
    found("poisson", "Poisson ratio must be in [0, 0.5)")
}

/// Whether `name` names an element of namespace `ns` in the element's model, as a
/// reference resolves (a builtin name, one the model or its expansions give, or a
/// name the writer gives).
fn known(at: &At<'_, '_>, ns: Namespace, name: &str) -> bool {
    let m = at.e.model;
    is_builtin_name(ns, name)
        || m.index.names.contains_key(&(ns, SmolStr::from(name)))
        || m.find(ns, name).is_some()
        || named_by_expansion(m, ns, name)
        || name.contains('/') && m.from_full_name(ns, name).is_some()
}

/// A flex's `<edge stiffness>`, 0 when not given.
fn edge_stiffness(node: &Node) -> f64 {
    child_value(node, "edge", "stiffness")
        .and_then(numbers)
        .and_then(|v| v.first().copied())
        .unwrap_or(0.0)
}

/// The first number of `attr` of a flex's (or flexcomp's) `<elasticity>`.
fn elasticity_number(node: &Node, attr: &str) -> Option<f64> {
    child_value(node, "elasticity", attr).and_then(numbers).and_then(|v| v.first().copied())
}

/// Whether its `<elasticity>` has a 2d elasticity (`elastic2d` other than `none`).
fn elastic2d(node: &Node) -> bool {
    let e = child_value(node, "elasticity", "elastic2d").and_then(Value::as_str);
    !matches!(e, None | Some("none"))
}

/// A poisson ratio outside `[0, 0.5)` (nan passes MuJoCo's comparisons).
fn poisson_out(p: f64) -> bool {
    !p.is_nan() && !(0.0..0.5).contains(&p)
}

/// `Poisson ratio must be in [0, 0.5)` of a flexcomp whose elasticity has a positive
/// young's modulus (judged here only without a 2d elasticity, whose other checks come
/// first; a `<flex>`'s is judged with its data, in MuJoCo's order).
fn poisson(at: &At<'_, '_>) -> Option<Found> {
    let node = at.e.node;
    (!elastic2d(node)).then_some(())?;
    let (young, p) = (elasticity_number(node, "young")?, elasticity_number(node, "poisson")?);
    (young > 0.0 && poisson_out(p)).then_some(())?;
    found("poisson", "Poisson ratio must be in [0, 0.5)")
}

#[cfg(test)]
#[path = "inline_tests.rs"]
mod tests;
