//! Compiling: a model's MJCF and files handed to MuJoCo through its virtual file
//! system, in memory.

use std::collections::BTreeMap;
use std::ffi::{CString, c_char, c_int};
use std::path::Path;
use std::ptr::NonNull;

use mjcf::{FileAsset, Model, WriteOptions};

use crate::error::{CompileError, Error};
use crate::guard::{self, Message};
use crate::library::{Fns, MuJoCo};
use crate::model::Compiled;
use crate::sys::{mjModel, mjVFS};

/// The name the written XML gets in the virtual file system (another when an asset
/// already has it).
const XML_NAME: &str = "mjcf-model.xml";

/// The size of the buffer MuJoCo writes its error message into.
const ERROR_SIZE: usize = 4096;

/// A virtual file system, deleted on drop.
struct Vfs<'a> {
    fns: &'a Fns,
    vfs: mjVFS,
}

impl<'a> Vfs<'a> {
    fn new(fns: &'a Fns) -> Vfs<'a> {
        let mut vfs = mjVFS { impl_: std::ptr::null_mut() };
        // SAFETY: `mj_defaultVFS` initialises the struct it is given.
        unsafe { (fns.default_vfs)(&mut vfs) };
        Vfs { fns, vfs }
    }

    /// Adds `bytes` as the file `name`.
    fn add(&mut self, name: &str, bytes: &[u8]) -> Result<(), Error> {
        let refuse = |why: &str| CompileError {
            message: format!("cannot hand the file {name:?} to MuJoCo: {why}"),
            line: None,
            element: None,
        };
        let c_name = CString::new(name).map_err(|_| refuse("its name holds a NUL"))?;
        let len = c_int::try_from(bytes.len()).map_err(|_| refuse("larger than 2 GiB"))?;
        let mut status: c_int = 0;
        // SAFETY: the VFS is initialised; name and bytes outlive the call (MuJoCo
        // copies them); the guard calls `mj_addBufferVFS` with these arguments.
        let fatal = unsafe {
            guard::mjr_add_buffer(
                self.fns.add_buffer_vfs,
                &mut self.vfs,
                c_name.as_ptr(),
                bytes.as_ptr().cast(),
                len,
                &mut status,
            )
        };
        if fatal != 0 {
            return Err(Error::Fatal { call: "compile", message: guard::fatal_message() });
        }
        match status {
            0 => Ok(()),
            2 => Err(refuse("two files of that name").into()),
            _ => Err(refuse("MuJoCo could not load it").into()),
        }
    }
}

impl Drop for Vfs<'_> {
    fn drop(&mut self) {
        // SAFETY: initialised in `new`, deleted once.
        unsafe { (self.fns.delete_vfs)(&mut self.vfs) }
    }
}

impl MuJoCo {
    /// Compiles `model` in MuJoCo, in memory: its MJCF (written with default
    /// [`WriteOptions`]) and its files ([`Model::assets`]) are handed over through
    /// MuJoCo's virtual file system; nothing is written to disk.
    ///
    /// Time: O(N) to write the model (see [`Model::to_xml_string`]), plus MuJoCo's
    /// compile.
    ///
    /// # Errors
    /// [`Error::Write`] when the model cannot be written; [`Error::Compile`] when
    /// MuJoCo refuses it, with the element it names where it names one;
    /// [`Error::Fatal`] for a fatal error inside MuJoCo.
    pub fn compile(&self, model: &Model) -> Result<Compiled, Error> {
        self.compile_with(model, &WriteOptions::default())
    }

    /// [`MuJoCo::compile`] with the model written with `options` (for instance
    /// `merge_keyframes`).
    ///
    /// Time: as [`MuJoCo::compile`].
    ///
    /// # Errors
    /// As [`MuJoCo::compile`].
    pub fn compile_with(&self, model: &Model, options: &WriteOptions) -> Result<Compiled, Error> {
        let written = model.to_xml_written(options)?;
        let assets = model.assets(options)?;
        let (ptr, messages) = self
            .load_text(written.xml(), &assets)
            .map_err(|e| crate::model::locate(e, model, &written))?;
        let source = crate::model::Source::compiled(model.clone(), options.clone(), written);
        Ok(Compiled::new(self.clone(), ptr, Some(source), messages))
    }

    /// Compiles MJCF text with the files it names (name → contents), in memory.
    ///
    /// Time: MuJoCo's compile.
    ///
    /// # Errors
    /// [`Error::Compile`] when MuJoCo refuses it; [`Error::Fatal`] for a fatal error
    /// inside MuJoCo.
    pub fn compile_xml(
        &self,
        xml: &str,
        assets: &BTreeMap<String, FileAsset>,
    ) -> Result<Compiled, Error> {
        let (ptr, messages) = self.load_text(xml, assets)?;
        Ok(Compiled::new(self.clone(), ptr, None, messages))
    }

    /// Compiles the MJCF file at `path` as MuJoCo reads it (its includes and files
    /// from disk, relative to it).
    ///
    /// Time: MuJoCo's compile.
    ///
    /// # Errors
    /// [`Error::Compile`] when MuJoCo cannot read or refuses it; [`Error::Fatal`] for
    /// a fatal error inside MuJoCo.
    pub fn compile_path(&self, path: impl AsRef<Path>) -> Result<Compiled, Error> {
        let path = path.as_ref();
        let c_path =
            CString::new(path.as_os_str().as_encoded_bytes()).map_err(|_| CompileError {
                message: format!("the path {} holds a NUL", path.display()),
                line: None,
                element: None,
            })?;
        let (ptr, messages) = self.load_xml(&c_path, None)?;
        Ok(Compiled::new(self.clone(), ptr, None, messages))
    }

    /// Loads `xml` (and `assets`) through a fresh virtual file system.
    fn load_text(
        &self,
        xml: &str,
        assets: &BTreeMap<String, FileAsset>,
    ) -> Result<(NonNull<mjModel>, Vec<Message>), Error> {
        let fns = &self.lib.fns;
        let mut vfs = Vfs::new(fns);
        let mut name = XML_NAME.to_string();
        while assets.contains_key(&name) {
            name.insert(0, '_');
        }
        vfs.add(&name, xml.as_bytes())?;
        for (file, asset) in assets {
            vfs.add(file, asset.contents())?;
        }
        let c_name = CString::new(name).unwrap_or_default();
        self.load_xml(&c_name, Some(&vfs.vfs))
    }

    fn load_xml(
        &self,
        name: &CString,
        vfs: Option<&mjVFS>,
    ) -> Result<(NonNull<mjModel>, Vec<Message>), Error> {
        let fns = &self.lib.fns;
        let mut error = vec![0 as c_char; ERROR_SIZE];
        let mut model: *mut mjModel = std::ptr::null_mut();
        guard::take_messages();
        // SAFETY: the name is NUL-terminated, the VFS (if any) initialised, the error
        // buffer of the size given; the guard calls `mj_loadXML` with them.
        let fatal = unsafe {
            guard::mjr_load_xml(
                fns.load_xml,
                name.as_ptr(),
                vfs.map_or(std::ptr::null(), |v| v as *const mjVFS),
                error.as_mut_ptr(),
                ERROR_SIZE as c_int,
                &mut model,
            )
        };
        let mut messages = guard::take_messages();
        if fatal != 0 {
            return Err(Error::Fatal { call: "compile", message: guard::fatal_message() });
        }
        // SAFETY: MuJoCo NUL-terminates what it writes in the buffer, which was zeroed.
        let text = unsafe { std::ffi::CStr::from_ptr(error.as_ptr()) }
            .to_string_lossy()
            .trim()
            .to_string();
        match NonNull::new(model) {
            Some(model) => {
                // A model with a message: MuJoCo's warning about it.
                if !text.is_empty() {
                    messages.push(Message { warning: true, function: None, text });
                }
                Ok((model, messages))
            }
            None => Err(CompileError { line: line_of(&text), message: text, element: None }.into()),
        }
    }
}

/// The line MuJoCo's message names, if any: its compiler's `Element name 'a', id 1,
/// line 7`, or its XML parser's `Line number=3`.
fn line_of(message: &str) -> Option<usize> {
    ["line ", "Line number="].iter().find_map(|label| {
        let at = message.rfind(label)? + label.len();
        let digits: String = message[at..].chars().take_while(char::is_ascii_digit).collect();
        digits.parse().ok()
    })
}

#[cfg(test)]
mod tests {
    use super::line_of;

    #[test]
    fn line_of_finds_the_line_mujoco_names() {
        assert_eq!(
            line_of("Error: repeated name 'a' in geom\nElement name 'a', id 1, line 7"),
            Some(7)
        );
        assert_eq!(
            line_of("XML Error: Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=16 Line number=3"),
            Some(3)
        );
        assert_eq!(line_of("no line here"), None);
    }
}
