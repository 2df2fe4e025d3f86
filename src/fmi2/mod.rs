//! The FMI 2.0 co-simulation API: the only `unsafe` code of the crate.
//!
//! `exports` turns C pointers into slices and strings once, at the edge, and hands them to
//! `instance`, one state machine shared by every model. No panic crosses the C boundary: every
//! exported function runs its body under `catch_unwind`.

pub mod binary;
pub mod cpu_clock;
pub mod driver;
pub mod exports;
pub mod ffi;
pub mod instance;
pub mod logger;
pub mod snapshot;

include!(concat!(env!("OUT_DIR"), "/guids.rs"));

/// The GUID written into a model's modelDescription.xml.
pub fn guid(model_identifier: &str) -> Option<&'static str> {
    GUIDS
        .iter()
        .find(|(id, _)| *id == model_identifier)
        .map(|(_, guid)| *guid)
}
