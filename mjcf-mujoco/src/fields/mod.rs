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

impl RawField {
    /// The field as a slice of `T`, if it holds `want` (else a `WrongType` error
    /// saying it was asked as `asked`).
    ///
    /// # Safety
    /// `self` describes a live array of `rows * cols` scalars of `field.scalar`, whose
    /// Rust type `T` is (`f64`, `f32`, `i32`), valid for `'a`.
    pub(crate) unsafe fn slice<'a, T>(
        &self,
        field: &'static Field,
        want: Scalar,
        asked: &'static str,
    ) -> Result<&'a [T], crate::error::BindError> {
        let len = self.checked_len(field, want, asked)?;
        if len == 0 {
            return Ok(&[]);
        }
        // SAFETY: as the caller promises.
        Ok(unsafe { std::slice::from_raw_parts(self.ptr.cast::<T>(), len) })
    }

    /// [`RawField::slice`], to write.
    ///
    /// # Safety
    /// As [`RawField::slice`], and nothing else reads or writes the array while the
    /// slice lives.
    pub(crate) unsafe fn slice_mut<'a, T>(
        &self,
        field: &'static Field,
        want: Scalar,
        asked: &'static str,
    ) -> Result<&'a mut [T], crate::error::BindError> {
        let len = self.checked_len(field, want, asked)?;
        if len == 0 {
            return Ok(&mut []);
        }
        // SAFETY: as the caller promises.
        Ok(unsafe { std::slice::from_raw_parts_mut(self.ptr.cast::<T>(), len) })
    }

    /// The number of scalars (0 for a null array), if the field holds `want`.
    fn checked_len(
        &self,
        field: &'static Field,
        want: Scalar,
        asked: &'static str,
    ) -> Result<usize, crate::error::BindError> {
        if field.scalar != want {
            return Err(crate::error::BindError::WrongType {
                field: field.name,
                holds: field.scalar.name(),
                asked,
            });
        }
        Ok(if self.ptr.is_null() { 0 } else { self.rows * self.cols })
    }
}
