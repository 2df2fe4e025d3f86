//! The FMI 2.0 co-simulation API, the boundary the FMUs export: with the in-process importer
//! ([`crate::importer`]) and the CPU clock, the only `unsafe` code of the crate.
//!
//! `exports` turns C pointers into slices and strings once, at the edge, and hands them to
//! [`crate::instance`], one state machine shared by every model and both standards; `dialect`
//! names its calls and phases as FMI 2.0 does. No panic crosses the C boundary: every exported
//! function runs its body under `catch_unwind`.

// The modules that touch C pointers or the C library, each allowed `unsafe` by name; the rest
// of the crate denies it (src/lib.rs).
#[allow(unsafe_code)]
pub mod binary;
pub mod dialect;
#[allow(unsafe_code)]
pub mod exports;
pub mod ffi;
#[allow(unsafe_code)]
pub mod logger;

include!(concat!(env!("OUT_DIR"), "/guids.rs"));

/// The GUID written into a model's modelDescription.xml.
pub fn guid(model_identifier: &str) -> Option<&'static str> {
    GUIDS
        .iter()
        .find(|(id, _)| *id == model_identifier)
        .map(|(_, guid)| *guid)
}
