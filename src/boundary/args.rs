//! C arguments as both standards' boundaries read them: NULL-checked strings and slices.

use std::ffi::{c_char, CStr};

/// A borrowed C string, or None for NULL or invalid UTF-8.
///
/// # Safety
/// `s` is NULL or a NUL-terminated string that outlives the borrow.
pub unsafe fn text<'a>(s: *const c_char) -> Option<&'a str> {
    if s.is_null() {
        None
    } else {
        CStr::from_ptr(s).to_str().ok()
    }
}

/// A slice from a pointer and a length; NULL is only acceptable for an empty slice.
///
/// # Safety
/// `p` is NULL or valid for reading `n` elements for the borrow.
pub unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts(p, n))
    }
}

/// A mutable slice from a pointer and a length; NULL is only acceptable for an empty slice.
///
/// # Safety
/// `p` is NULL or valid for writing `n` elements for the borrow, and not aliased.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    if n == 0 {
        Some(&mut [])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts_mut(p, n))
    }
}
