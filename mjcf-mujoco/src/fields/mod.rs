//! The array fields of `mjModel` and `mjData`, by name (generated from MuJoCo's
//! mjxmacro.h: generated.rs).

mod generated;

pub(crate) use generated::{DATA_FIELDS, MODEL_FIELDS, data_field, model_field};

/// The scalar type of a field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    F64,
    F32,
    I32,
    U8,
    Bool,
}

impl Scalar {
    pub(crate) fn name(self) -> &'static str {
        match self {
            Scalar::F64 => "f64",
            Scalar::F32 => "f32",
            Scalar::I32 => "i32",
            Scalar::U8 => "u8",
            Scalar::Bool => "bool",
        }
    }
}

/// A field: its name in the struct, its scalar, and the size field counting its rows
/// (`nbody`, `njnt`, `nv`, ...).
#[derive(Debug)]
pub(crate) struct Field {
    pub(crate) name: &'static str,
    pub(crate) scalar: Scalar,
    pub(crate) rows: &'static str,
}

/// A field of one model or data: where it is and its shape.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RawField {
    pub(crate) ptr: *mut u8,
    pub(crate) rows: usize,
    pub(crate) cols: usize,
}
