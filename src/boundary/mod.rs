//! What both standards' C boundaries share: reading C arguments, and the shims of the calls
//! whose C signatures FMI 2.0 and FMI 3.0 have in common (logging, getters and setters, FMU states). Each
//! takes the handle and the [`Dialect`] of the standard that calls it.
//!
//! [`Dialect`]: crate::instance::calls::Dialect

pub mod args;
pub mod forward;
pub mod logging;
pub mod states;
pub mod values;
