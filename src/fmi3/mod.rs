//! The FMI 3.0 co-simulation API, the boundary the FMI 3.0 FMUs export: the same instance as
//! FMI 2.0's ([`crate::instance`]) behind FMI 3.0's C types, statuses and callbacks.
//!
//! `exports` turns C pointers into slices and strings once, at the edge, and hands them to the
//! instance; `dialect` names its calls and phases as FMI 3.0 does. No panic crosses the C
//! boundary: every exported function runs its body under `catch_unwind`.

#[allow(unsafe_code)]
pub mod binary;
pub mod dialect;
#[allow(unsafe_code)]
pub mod exports;
pub mod ffi;
#[allow(unsafe_code)]
pub mod logger;
pub mod updates;
