//! The logging call both standards share: the categories' C strings read once, then the instance.

use super::args::{slice, text};
use crate::instance::calls::{Call, Dialect};
use crate::instance::{handles, Status};
use std::ffi::c_char;

/// SetDebugLogging: `categories` holds `n_categories` C strings.
///
/// # Safety
/// `categories` is NULL or an array of `n_categories` NULL or NUL-terminated strings.
pub unsafe fn set_debug_logging(
    handle: usize,
    dialect: &'static Dialect,
    logging_on: bool,
    n_categories: usize,
    categories: *const *const c_char,
) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        let Some(categories) = slice(categories, n_categories) else {
            return instance.null_argument(Call::SetDebugLogging, "categories");
        };
        let mut names = Vec::with_capacity(categories.len());
        for &category in categories {
            match text(category) {
                Some(name) => names.push(name.to_string()),
                None => return instance.null_argument(Call::SetDebugLogging, "a category name"),
            }
        }
        instance.set_debug_logging(logging_on, &names)
    })
}
