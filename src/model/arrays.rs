//! The shortest arrays MuJoCo accepts ([`ProblemKind::ArrayTooShort`](crate::ProblemKind)).
//!
//! The reader accepts an array shorter than its schema length, as dm_control does
//! (`pos="1 2"`), but MuJoCo refuses many ("attribute 'pos' does not have enough
//! data"). Which, and how short, is MuJoCo's: the table
//! `schema/mujoco-4.0-array-minimums.txt` was probed from MuJoCo 4.0.0, and the
//! binding crate's tests probe MuJoCo again and require the table to be exactly that.
//! Elements inside default classes are not held to it (MuJoCo reads them alike, but
//! the table was probed where elements are used). Beside the table, two length rules
//! MuJoCo's compiler has, each checked against MuJoCo by the binding crate's tests: a
//! geom's `size` needs as many numbers as its type uses (its classes' numbers fill
//! in where it gives fewer), and mesh data comes in whole vertices, normals, faces
//! and texture coordinates.

use std::collections::HashMap;
use std::sync::OnceLock;

use crate::schema::ElementKind;
use crate::value::Value;

const TABLE: &str = include_str!("../../schema/mujoco-4.0-array-minimums.txt");

/// The tags from `<mujoco>` down to `kind`, joined with `/` (the table's paths).
fn path(kind: ElementKind) -> String {
    let mut tags = vec![kind.tag()];
    let mut cur = kind.spec().parent;
    while let Some(p) = cur {
        tags.push(p.tag());
        cur = p.spec().parent;
    }
    tags.reverse();
    tags.join("/")
}

/// The minimum length of attribute `attr` of `kind`, where the table has one.
pub(crate) fn minimum(kind: ElementKind, attr: usize) -> Option<usize> {
    static MINIMUMS: OnceLock<HashMap<(ElementKind, usize), usize>> = OnceLock::new();
    let table = MINIMUMS.get_or_init(|| {
        let by_path: HashMap<String, ElementKind> =
            ElementKind::all().map(|k| (path(k), k)).collect();
        let mut out = HashMap::new();
        for line in TABLE.lines().filter(|l| !l.starts_with('#')) {
            let mut words = line.split_whitespace();
            let (Some(p), Some(a), Some(n)) = (words.next(), words.next(), words.next()) else {
                continue;
            };
            let (Some(kind), Ok(n)) = (by_path.get(p), n.parse()) else { continue };
            if let Some(i) = kind.attr_index(a) {
                out.insert((*kind, i), n);
            }
        }
        out
    });
    table.get(&(kind, attr)).copied()
}

/// The numbers MuJoCo needs in a geom's `size` for its type (a `fromto` gives the
/// length), each above 0: MuJoCo refuses fewer ("size 2 must be positive").
pub(crate) fn geom_size_needed(geom_type: &str, fromto: bool) -> usize {
    match geom_type {
        "sphere" => 1,
        "capsule" | "cylinder" => {
            if fromto {
                1
            } else {
                2
            }
        }
        "box" | "ellipsoid" => {
            if fromto {
                1
            } else {
                3
            }
        }
        "plane" => 3,
        _ => 0,
    }
}

/// The mesh arrays whose length must be a multiple: MuJoCo refuses others ("vertex
/// data must be a multiple of 3").
pub(crate) const MULTIPLES: [(&str, &str, usize); 4] =
    [("mesh", "vertex", 3), ("mesh", "normal", 3), ("mesh", "face", 3), ("mesh", "texcoord", 2)];

pub(crate) fn array_len(v: &Value) -> Option<usize> {
    match v {
        Value::Floats(xs) => Some(xs.len()),
        Value::Ints(xs) => Some(xs.len()),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_names_only_elements_and_attributes_of_the_schema() {
        let mut entries = 0;
        for line in TABLE.lines().filter(|l| !l.starts_with('#')) {
            let w: Vec<&str> = line.split_whitespace().collect();
            let kind =
                ElementKind::all().find(|k| path(*k) == w[0]).unwrap_or_else(|| panic!("{line}"));
            let i = kind.attr_index(w[1]).unwrap_or_else(|| panic!("{line}"));
            assert_eq!(minimum(kind, i), Some(w[2].parse().unwrap()), "{line}");
            entries += 1;
        }
        assert!(entries > 200, "{entries}");
    }
}
