//! The calls into MuJoCo that can raise a fatal error, through the C guard
//! (shim/guard.c), and the messages MuJoCo logs, collected per thread.
//!
//! Policy: MuJoCo's fatal errors (`mju_error`, which MuJoCo expects not to return) jump
//! back in C to the guarded call that entered MuJoCo on that thread and come out as
//! [`Error::Fatal`](crate::Error::Fatal); no Rust frame is ever crossed by the jump,
//! and no Rust panic can unwind into C (the sink below cannot panic, and an
//! `extern "C"` function aborts rather than unwind). A fatal error on a thread that
//! MuJoCo started itself (no guard there) prints its message and aborts the process.
//! Warnings and other messages are collected by the thread that raised them and handed
//! to the caller of the call that raised them; nothing is printed, and no
//! `MUJOCO_LOG.TXT` is written.

use std::cell::RefCell;
use std::ffi::{CStr, c_char, c_int, c_long, c_void};

use crate::sys::{mjData, mjLogMessage, mjModel, mjVFS};

unsafe extern "C" {
    fn mjr_log_message_size() -> usize;
    fn mjr_log_message_body_offset() -> usize;
    fn mjr_set_sink(
        sink: Option<unsafe extern "C" fn(c_int, *const c_char, *const c_char, *const c_char)>,
    );
    pub(crate) fn mjr_log_handler(message: *const mjLogMessage);
    fn mjr_fatal_message() -> *const c_char;
    pub(crate) fn mjr_step(
        step: unsafe extern "C" fn(*const mjModel, *mut mjData),
        m: *const mjModel,
        d: *mut mjData,
        n: c_long,
    ) -> c_int;
    pub(crate) fn mjr_call(
        f: unsafe extern "C" fn(*const mjModel, *mut mjData),
        m: *const mjModel,
        d: *mut mjData,
    ) -> c_int;
    pub(crate) fn mjr_set_const(
        f: unsafe extern "C" fn(*mut mjModel, *mut mjData),
        m: *mut mjModel,
        d: *mut mjData,
    ) -> c_int;
    pub(crate) fn mjr_reset_key(
        f: unsafe extern "C" fn(*const mjModel, *mut mjData, c_int),
        m: *const mjModel,
        d: *mut mjData,
        key: c_int,
    ) -> c_int;
    pub(crate) fn mjr_make_data(
        f: unsafe extern "C" fn(*const mjModel) -> *mut mjData,
        m: *const mjModel,
        out: *mut *mut mjData,
    ) -> c_int;
    pub(crate) fn mjr_copy_model(
        f: unsafe extern "C" fn(*mut mjModel, *const mjModel) -> *mut mjModel,
        src: *const mjModel,
        out: *mut *mut mjModel,
    ) -> c_int;
    pub(crate) fn mjr_load_xml(
        f: unsafe extern "C" fn(*const c_char, *const mjVFS, *mut c_char, c_int) -> *mut mjModel,
        name: *const c_char,
        vfs: *const mjVFS,
        error: *mut c_char,
        error_sz: c_int,
        out: *mut *mut mjModel,
    ) -> c_int;
    pub(crate) fn mjr_add_buffer(
        f: unsafe extern "C" fn(*mut mjVFS, *const c_char, *const c_void, c_int) -> c_int,
        vfs: *mut mjVFS,
        name: *const c_char,
        buffer: *const c_void,
        n: c_int,
        out: *mut c_int,
    ) -> c_int;
}

/// Whether the C guard's copy of `mjLogMessage` has the layout of the bindings' (the
/// one the loaded MuJoCo uses, its version being checked).
pub(crate) fn layout_matches() -> bool {
    // SAFETY: both functions only return constants.
    let (size, body) = unsafe { (mjr_log_message_size(), mjr_log_message_body_offset()) };
    size == size_of::<mjLogMessage>() && body == std::mem::offset_of!(mjLogMessage, body)
}

/// Serializes the installation of the handlers: the guard's sink pointer and
/// MuJoCo's log handler are plain globals, which two threads loading MuJoCo at once
/// must not write together.
pub(crate) static INSTALL: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Installs the sink of non-fatal messages (idempotent); call it holding [`INSTALL`].
pub(crate) fn install_sink() {
    // SAFETY: `sink` has the signature the guard calls, and never unwinds; the
    // caller holds `INSTALL`, so no other thread writes the pointer meanwhile.
    unsafe { mjr_set_sink(Some(sink)) }
}

/// One message MuJoCo logged (a warning, or information).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Message {
    /// `true` for a warning, `false` for information or a debug trace.
    pub warning: bool,
    /// The function that logged it, if MuJoCo said.
    pub function: Option<String>,
    /// The message.
    pub text: String,
}

impl std::fmt::Display for Message {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.function {
            Some(func) => write!(f, "{func}: {}", self.text),
            None => f.write_str(&self.text),
        }
    }
}

thread_local! {
    static MESSAGES: RefCell<Vec<Message>> = const { RefCell::new(Vec::new()) };
}

/// Text from a C string that may be null.
///
/// # Safety
/// `p` is null or points to a NUL-terminated string that outlives the call.
unsafe fn text(p: *const c_char) -> Option<String> {
    // SAFETY: as the caller promises.
    (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned())
}

/// Called by the guard for every non-fatal message. It cannot panic: the thread-local
/// may be gone (thread exit) or borrowed (a message while collecting), and then the
/// message is dropped.
unsafe extern "C" fn sink(
    level: c_int,
    func: *const c_char,
    subject: *const c_char,
    body: *const c_char,
) {
    // SAFETY: MuJoCo passes NUL-terminated strings (or null) valid during the call.
    let (function, subject, body) = unsafe { (text(func), text(subject), text(body)) };
    let mut text = subject.unwrap_or_default();
    if let Some(body) = body {
        text.push('\n');
        text.push_str(&body);
    }
    let message = Message { warning: level >= 2, function, text };
    let _ = MESSAGES.try_with(|m| {
        if let Ok(mut m) = m.try_borrow_mut() {
            m.push(message);
        }
    });
}

/// The messages logged on this thread since the last call.
pub(crate) fn take_messages() -> Vec<Message> {
    MESSAGES
        .try_with(|m| m.try_borrow_mut().map(|mut m| std::mem::take(&mut *m)).unwrap_or_default())
        .unwrap_or_default()
}

/// The message of the last fatal error caught on this thread.
pub(crate) fn fatal_message() -> String {
    // SAFETY: the guard's thread-local buffer, always NUL-terminated.
    unsafe { text(mjr_fatal_message()) }.unwrap_or_default()
}
