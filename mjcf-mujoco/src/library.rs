//! Finding, loading and checking MuJoCo's shared library.

use std::ffi::{CStr, c_char, c_int, c_void};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::error::Error;
use crate::guard;
use crate::sys::{self, mjData, mjModel, mjVFS};

/// The file names tried on the system's library paths, in order.
const SYSTEM_NAMES: &[&str] = &["libmujoco.so.4.0.0", "libmujoco.so"];

/// MuJoCo's functions the binding calls, checked present when the library is loaded.
#[derive(Clone, Copy)]
pub(crate) struct Fns {
    pub(crate) default_vfs: unsafe extern "C" fn(*mut mjVFS),
    pub(crate) add_buffer_vfs:
        unsafe extern "C" fn(*mut mjVFS, *const c_char, *const c_void, c_int) -> c_int,
    pub(crate) delete_vfs: unsafe extern "C" fn(*mut mjVFS),
    pub(crate) load_xml:
        unsafe extern "C" fn(*const c_char, *const mjVFS, *mut c_char, c_int) -> *mut mjModel,
    pub(crate) delete_model: unsafe extern "C" fn(*mut mjModel),
    pub(crate) copy_model: unsafe extern "C" fn(*mut mjModel, *const mjModel) -> *mut mjModel,
    pub(crate) make_data: unsafe extern "C" fn(*const mjModel) -> *mut mjData,
    pub(crate) delete_data: unsafe extern "C" fn(*mut mjData),
    pub(crate) set_const: unsafe extern "C" fn(*mut mjModel, *mut mjData),
    pub(crate) reset_data: unsafe extern "C" fn(*const mjModel, *mut mjData),
    pub(crate) reset_data_keyframe: unsafe extern "C" fn(*const mjModel, *mut mjData, c_int),
    pub(crate) forward: unsafe extern "C" fn(*const mjModel, *mut mjData),
    pub(crate) step: unsafe extern "C" fn(*const mjModel, *mut mjData),
    pub(crate) name2id: unsafe extern "C" fn(*const mjModel, c_int, *const c_char) -> c_int,
    pub(crate) id2name: unsafe extern "C" fn(*const mjModel, c_int, c_int) -> *const c_char,
    pub(crate) warning_text: unsafe extern "C" fn(c_int, usize) -> *const c_char,
}

/// The loaded library: its functions, and the library itself, kept loaded while any
/// model or data made with it lives.
pub(crate) struct Lib {
    pub(crate) fns: Fns,
    pub(crate) path: PathBuf,
    pub(crate) version: String,
    _api: sys::MujocoApi,
}

/// MuJoCo's library, loaded at run time and checked to be MuJoCo
/// [`MUJOCO_VERSION`](crate::MUJOCO_VERSION).
///
/// Cloning is O(1); the library stays loaded while a clone, a [`Compiled`] model or a
/// [`Physics`] made with it lives.
///
/// Loading replaces MuJoCo's process-wide log handler with the binding's (see the
/// crate's documentation: fatal errors become [`Error::Fatal`], messages are collected,
/// nothing is written to `MUJOCO_LOG.TXT`).
///
/// [`Compiled`]: crate::Compiled
/// [`Physics`]: crate::Physics
#[derive(Clone)]
pub struct MuJoCo {
    pub(crate) lib: Arc<Lib>,
}

impl std::fmt::Debug for MuJoCo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MuJoCo")
            .field("path", &self.lib.path)
            .field("version", &self.lib.version)
            .finish()
    }
}

impl MuJoCo {
    /// Loads MuJoCo from `MUJOCO_LIB` (the library file) when it is set, else from the
    /// system's library paths (`libmujoco.so.4.0.0`, then `libmujoco.so`, as the
    /// dynamic loader finds them: `LD_LIBRARY_PATH`, the system's folders).
    ///
    /// The file must be MuJoCo's library: loading runs its initialisers, as loading
    /// any shared library does. Its version is checked before anything else is called.
    ///
    /// Time: O(1) (the dynamic loader's work).
    ///
    /// # Errors
    /// [`Error::NotFound`] with what was tried; [`Error::Load`] or [`Error::Version`]
    /// for a file that is there but is not MuJoCo 4.0.0.
    pub fn load() -> Result<MuJoCo, Error> {
        if let Some(path) = std::env::var_os("MUJOCO_LIB") {
            return MuJoCo::load_from(PathBuf::from(path));
        }
        let mut tried = vec!["MUJOCO_LIB is not set".to_string()];
        for name in SYSTEM_NAMES {
            // SAFETY: loading a shared library runs its initialisers; a file of
            // MuJoCo's library name is taken to be MuJoCo (documented above).
            match unsafe { libloading::Library::new(name) } {
                Ok(library) => return MuJoCo::from_library(library, PathBuf::from(name)),
                Err(e) => tried.push(format!("{name}: {e}")),
            }
        }
        Err(Error::NotFound { tried: tried.join("; ") })
    }

    /// Loads MuJoCo from the library file at `path` (such as
    /// `site-packages/mujoco/libmujoco.so.4.0.0` of the `mujoco` wheel).
    ///
    /// Time: O(1) (the dynamic loader's work).
    ///
    /// # Errors
    /// [`Error::Load`] when the file cannot be loaded or lacks one of MuJoCo's
    /// functions; [`Error::Version`] when it is another version of MuJoCo.
    pub fn load_from(path: impl AsRef<Path>) -> Result<MuJoCo, Error> {
        let path = path.as_ref();
        // A bare file name would be searched on the library paths: name it as a path.
        let file = if path.components().count() == 1 {
            Path::new(".").join(path)
        } else {
            path.to_path_buf()
        };
        // SAFETY: as in `load`: the caller names MuJoCo's library.
        let library = unsafe { libloading::Library::new(&file) }
            .map_err(|e| Error::Load { path: path.to_path_buf(), reason: e.to_string() })?;
        MuJoCo::from_library(library, path.to_path_buf())
    }

    fn from_library(library: libloading::Library, path: PathBuf) -> Result<MuJoCo, Error> {
        // SAFETY: `from_library` only looks symbols up; none is called here.
        let api = unsafe { sys::MujocoApi::from_library(library) }
            .map_err(|e| Error::Load { path: path.clone(), reason: e.to_string() })?;
        let missing =
            |e: &libloading::Error| Error::Load { path: path.clone(), reason: e.to_string() };
        // The version first: nothing else is called in a library of another version.
        let version_string = *api.mj_versionString.as_ref().map_err(missing)?;
        let version_number = *api.mj_version.as_ref().map_err(missing)?;
        // SAFETY: `mj_versionString` and `mj_version` take nothing and return a static
        // string and an int in every MuJoCo release.
        let (version, number) = unsafe {
            let s = version_string();
            let text = if s.is_null() {
                String::new()
            } else {
                CStr::from_ptr(s).to_string_lossy().into_owned()
            };
            (text, version_number())
        };
        if version != crate::MUJOCO_VERSION || number != sys::mjVERSION_HEADER as c_int {
            return Err(Error::Version { path, found: version });
        }
        if !guard::layout_matches() {
            return Err(Error::Load {
                path,
                reason: "the fatal-error guard's mjLogMessage does not match the bindings'".into(),
            });
        }
        macro_rules! get {
            ($name:ident) => {
                *api.$name.as_ref().map_err(missing)?
            };
        }
        let fns = Fns {
            default_vfs: get!(mj_defaultVFS),
            add_buffer_vfs: get!(mj_addBufferVFS),
            delete_vfs: get!(mj_deleteVFS),
            load_xml: get!(mj_loadXML),
            delete_model: get!(mj_deleteModel),
            copy_model: get!(mj_copyModel),
            make_data: get!(mj_makeData),
            delete_data: get!(mj_deleteData),
            set_const: get!(mj_setConst),
            reset_data: get!(mj_resetData),
            reset_data_keyframe: get!(mj_resetDataKeyframe),
            forward: get!(mj_forward),
            step: get!(mj_step),
            name2id: get!(mj_name2id),
            id2name: get!(mj_id2name),
            warning_text: get!(mju_warningText),
        };
        let set_log_handler = get!(mju_setLogHandler);
        // One thread at a time writes the handlers (a poisoned lock only means another
        // thread panicked while holding it: the handlers are plain pointers).
        let _installing = guard::INSTALL.lock().unwrap_or_else(|e| e.into_inner());
        guard::install_sink();
        // SAFETY: the guard's handler has MuJoCo 4.0's handler signature (its message
        // layout checked above); it never returns on an error level, as MuJoCo asks.
        unsafe {
            set_log_handler(Some(guard::mjr_log_handler));
        }
        Ok(MuJoCo { lib: Arc::new(Lib { fns, path, version, _api: api }) })
    }

    /// The version of the loaded library (`4.0.0`).
    ///
    /// Time: O(1).
    pub fn version(&self) -> &str {
        &self.lib.version
    }

    /// The library file it was loaded from (as given, or the name found on the
    /// system's library paths).
    ///
    /// Time: O(1).
    pub fn path(&self) -> &Path {
        &self.lib.path
    }
}
