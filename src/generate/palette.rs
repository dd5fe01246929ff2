//! Attribute palettes: which attributes recipes set on each tag, in which ranges. The
//! schema gives each one's type and length.

use std::collections::HashSet;

use crate::model::Element;
use crate::schema::{ArrayType, AttrType, ElementKind};
use crate::value::AttrInput;

use super::recipe::{AttrDraw, Palette, Pick, Unit};

/// The range of values an attribute of a palette takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Numbers from `lo / 1000` to `hi / 1000` (in steps of 1/1000).
    Real(i32, i32),
    /// Integers from `lo` to `hi`.
    Int(i32, i32),
    /// One of these integers.
    IntSet(&'static [i32]),
    /// One of these keywords (each one of the schema's).
    Words(&'static [&'static str]),
    /// A non-zero direction (three numbers from -1 to 1).
    Direction,
    /// A pair `lo < hi`: `lo` from `a / 1000` to `a / 10000`, `hi` from `b / 10000`
    /// to `b / 1000` (`a < 0 < b`).
    Range(i32, i32),
}

/// How many entries an array attribute of a palette gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Length {
    /// The schema's length (1 if it has none).
    Full,
    /// From 1 to this many.
    UpTo(u8),
}

/// One attribute of a palette.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PaletteEntry {
    /// The attribute.
    pub name: &'static str,
    /// Its values.
    pub domain: Domain,
    /// Its length, for an array.
    pub length: Length,
}

const fn p(name: &'static str, domain: Domain, length: Length) -> PaletteEntry {
    PaletteEntry { name, domain, length }
}

use Domain::{Direction, Int, IntSet, Range, Real, Words};
use Length::{Full, UpTo};

const BOOL: &[&str] = &["false", "true"];

static BODY: &[PaletteEntry] = &[
    p("pos", Real(-1000, 1000), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("gravcomp", Real(0, 1000), Full),
];
static GEOM: &[PaletteEntry] = &[
    p("pos", Real(-300, 300), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("rgba", Real(0, 1000), Full),
    p("friction", Real(100, 2000), UpTo(3)),
    p("condim", IntSet(&[1, 3, 4, 6]), Full),
    p("contype", Int(0, 3), Full),
    p("conaffinity", Int(0, 3), Full),
    p("group", Int(0, 5), Full),
    p("priority", Int(0, 2), Full),
    p("density", Real(100_000, 2_000_000), Full),
    p("margin", Real(0, 10), Full),
];
static SITE: &[PaletteEntry] =
    &[p("rgba", Real(0, 1000), Full), p("size", Real(5, 50), UpTo(3)), p("group", Int(0, 5), Full)];
static JOINT: &[PaletteEntry] = &[
    p("pos", Real(-100, 100), Full),
    p("damping", Real(0, 2000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(0, 100), Full),
    p("frictionloss", Real(0, 500), Full),
    p("group", Int(0, 5), Full),
];
static CAMERA: &[PaletteEntry] = &[
    p("pos", Real(-2000, 2000), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("fovy", Real(10_000, 90_000), Full),
    p("mode", Words(&["fixed", "track", "trackcom"]), Full),
];
static LIGHT: &[PaletteEntry] = &[
    p("pos", Real(-2000, 2000), Full),
    p("dir", Direction, Full),
    p("diffuse", Real(0, 1000), Full),
    p("specular", Real(0, 500), Full),
    p("directional", Words(BOOL), Full),
    p("castshadow", Words(BOOL), Full),
];
static MATERIAL: &[PaletteEntry] = &[
    p("rgba", Real(0, 1000), Full),
    p("specular", Real(0, 1000), Full),
    p("shininess", Real(0, 1000), Full),
    p("reflectance", Real(0, 1000), Full),
    p("emission", Real(0, 1000), Full),
];
static MESH: &[PaletteEntry] = &[p("scale", Real(50, 300), Full)];
static MOTOR: &[PaletteEntry] =
    &[p("gear", Real(500, 5000), UpTo(1)), p("ctrlrange", Range(-2000, 2000), Full)];
static POSITION: &[PaletteEntry] =
    &[p("kp", Real(1000, 100_000), Full), p("ctrlrange", Range(-1500, 1500), Full)];
static VELOCITY: &[PaletteEntry] =
    &[p("kv", Real(100, 10_000), Full), p("ctrlrange", Range(-2000, 2000), Full)];
static SENSOR: &[PaletteEntry] = &[p("noise", Real(0, 10), Full)];
static TENDON: &[PaletteEntry] =
    &[p("stiffness", Real(0, 2000), UpTo(1)), p("damping", Real(0, 1000), UpTo(1))];
static DEFAULT_GEOM: &[PaletteEntry] = &[
    p("rgba", Real(0, 1000), Full),
    p("friction", Real(100, 2000), UpTo(3)),
    p("density", Real(100_000, 2_000_000), Full),
    p("condim", IntSet(&[1, 3, 4, 6]), Full),
    p("contype", Int(0, 3), Full),
    p("conaffinity", Int(0, 3), Full),
    p("group", Int(0, 5), Full),
];
static DEFAULT_JOINT: &[PaletteEntry] = &[
    p("damping", Real(0, 2000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(0, 100), Full),
];
static DEFAULT_SITE: &[PaletteEntry] =
    &[p("rgba", Real(0, 1000), Full), p("group", Int(0, 5), Full)];

/// The attributes recipes set on elements of `tag` (beyond the ones a step sets
/// itself: names, references, types, sizes, axes), with their ranges;
/// `in_default` for the element in a default class. Empty for other tags.
///
/// Time: O(1).
///
/// # Examples
/// ```
/// use mjcf::generate::palette;
/// assert!(palette("geom", false).iter().any(|e| e.name == "rgba"));
/// assert!(palette("worldbody", false).is_empty());
/// ```
pub fn palette(tag: &str, in_default: bool) -> &'static [PaletteEntry] {
    if in_default {
        return match tag {
            "geom" => DEFAULT_GEOM,
            "joint" => DEFAULT_JOINT,
            "site" => DEFAULT_SITE,
            _ => &[],
        };
    }
    match tag {
        "body" => BODY,
        "geom" => GEOM,
        "site" => SITE,
        "joint" => JOINT,
        "camera" => CAMERA,
        "light" => LIGHT,
        "material" => MATERIAL,
        "mesh" => MESH,
        "motor" => MOTOR,
        "position" => POSITION,
        "velocity" => VELOCITY,
        "jointpos" | "jointvel" | "touch" | "accelerometer" | "gyro" | "framepos" => SENSOR,
        "fixed" => TENDON,
        _ => &[],
    }
}

static SIM_JOINT: &[PaletteEntry] = &[
    p("pos", Real(-100, 100), Full),
    p("damping", Real(1000, 3000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(100, 500), Full),
    p("frictionloss", Real(0, 500), Full),
    p("group", Int(0, 5), Full),
];
static SIM_DEFAULT_JOINT: &[PaletteEntry] = &[
    p("damping", Real(1000, 3000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(100, 500), Full),
];

/// The palette of `tag` for models of the recipe palette `pal`: [`palette`], but
/// for [`Palette::Simulates`] joints keep armature (at least 0.1) and damping (at
/// least 1).
pub(super) fn palette_of(tag: &str, in_default: bool, pal: Palette) -> &'static [PaletteEntry] {
    match (pal, tag, in_default) {
        (Palette::Simulates, "joint", false) => SIM_JOINT,
        (Palette::Simulates, "joint", true) => SIM_DEFAULT_JOINT,
        _ => palette(tag, in_default),
    }
}

/// `lo..=hi` thousandths, picked by `u`, as a number of at most three decimals.
pub(super) fn real(lo: i32, hi: i32, u: Unit) -> f64 {
    let (lo, hi) = (i64::from(lo), i64::from(hi));
    (lo + (hi - lo) * u.thousandths() / 1000) as f64 / 1000.0
}

pub(super) fn int(lo: i32, hi: i32, u: Unit) -> i32 {
    let span = (hi - lo).unsigned_abs() + 1;
    lo + (u32::from(u.0) % span) as i32
}

/// A non-zero vector from three units (each -1 to 1); `[0, 0, 1]` if all are 0.
pub(super) fn direction(u: [Unit; 3]) -> Vec<f64> {
    let v: Vec<f64> = u.iter().map(|x| real(-1000, 1000, *x)).collect();
    if v.iter().all(|x| *x == 0.0) { vec![0.0, 0.0, 1.0] } else { v }
}

/// The value of a palette entry on an element of `kind`, of the type and length the
/// schema gives that attribute; `None` when the kind has no such attribute or the
/// entry does not fit its type.
///
/// Time: O(log k) for the `k` attributes of the kind.
///
/// # Examples
/// ```
/// use mjcf::ElementKind;
/// use mjcf::generate::{AttrDraw, Unit, palette, value};
/// let geom = ElementKind::ROOT.child("worldbody").unwrap().child("geom").unwrap();
/// let rgba = palette("geom", false).iter().find(|e| e.name == "rgba").unwrap();
/// let v = value(geom, rgba, &AttrDraw { values: [Unit(1000); 4], ..AttrDraw::default() });
/// assert_eq!(v, Some(vec![1.0, 1.0, 1.0, 1.0].into())); // the schema's length: 4
/// ```
pub fn value(kind: ElementKind, entry: &PaletteEntry, draw: &AttrDraw) -> Option<AttrInput> {
    let ty = kind.attr(kind.attr_index(entry.name)?).ty;
    let length = |max_len: Option<u32>| -> usize {
        let n = match entry.length {
            Length::Full => max_len.map_or(1, |n| n as usize),
            Length::UpTo(k) => 1 + usize::from(draw.len % k.max(1)),
        };
        n.clamp(1, draw.values.len())
    };
    let v = &draw.values;
    Some(match (ty, entry.domain) {
        (AttrType::Float, Domain::Real(lo, hi)) => real(lo, hi, v[0]).into(),
        (AttrType::Int, Domain::Int(lo, hi)) => int(lo, hi, v[0]).into(),
        (AttrType::Int, Domain::IntSet(set)) => set[usize::from(v[0].0) % set.len()].into(),
        (AttrType::Keyword(words), Domain::Words(ours)) => {
            let ours: Vec<&str> = ours
                .iter()
                .copied()
                .filter(|w| words.iter().any(|s| s.eq_ignore_ascii_case(w)))
                .collect();
            (*Pick(v[0].0).of(&ours)?).into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len }, Domain::Real(lo, hi)) => {
            v[..length(max_len)].iter().map(|u| real(lo, hi, *u)).collect::<Vec<f64>>().into()
        }
        (AttrType::Array { elem: ArrayType::Int, max_len }, Domain::Int(lo, hi)) => {
            v[..length(max_len)].iter().map(|u| int(lo, hi, *u)).collect::<Vec<i32>>().into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len: Some(3) }, Domain::Direction) => {
            direction([v[0], v[1], v[2]]).into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len: Some(2) }, Domain::Range(a, b)) => {
            vec![real(a, a / 10, v[0]), real(b / 10, b, v[1])].into()
        }
        _ => return None,
    })
}

/// Sets the palette attributes `draws` pick on `el` (of `kind`), each at most once
/// and none in `taken`.
pub(super) fn with_extras(
    mut el: Element,
    kind: ElementKind,
    pal: &[PaletteEntry],
    draws: &[AttrDraw],
    taken: &[&str],
) -> Element {
    let mut set: HashSet<&str> = taken.iter().copied().collect();
    for d in draws.iter().take(8) {
        let Some(entry) = d.which.of(pal) else { continue };
        if !set.insert(entry.name) {
            continue;
        }
        if let Some(v) = value(kind, entry, d) {
            el = el.attr(entry.name, v);
        }
    }
    el
}
