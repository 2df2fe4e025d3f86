//! Texts into and out of C strings, as both standards' importers pass and read them.

use std::ffi::{c_char, CStr, CString};

/// A C string the FMU passed, as Rust text: "" for NULL, invalid UTF-8 replaced.
pub(super) fn lossy(text: *const c_char) -> String {
    if text.is_null() {
        return String::new();
    }
    // SAFETY: the FMU passes NUL-terminated strings that live until the logger returns.
    unsafe { CStr::from_ptr(text) }
        .to_string_lossy()
        .into_owned()
}

pub(super) fn c_text(text: &Option<String>) -> Option<CString> {
    // Interior NULs cannot cross as C strings; cut there, as C would read it.
    text.as_ref()
        .map(|t| CString::new(t.split('\0').next().unwrap_or_default()).unwrap_or_default())
}

pub(super) fn c_pointer(text: &Option<CString>) -> *const c_char {
    text.as_ref().map_or(std::ptr::null(), |t| t.as_ptr())
}

/// Each text as a C string, without the NULs it cannot carry.
pub(super) fn c_strings(texts: &[&str]) -> Vec<CString> {
    texts
        .iter()
        .map(|t| CString::new(t.replace('\0', "")).unwrap_or_default())
        .collect()
}
