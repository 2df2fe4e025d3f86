//! friction-fmu: friction-vibration contact models as FMI 2.0 co-simulation FMUs.
//!
//! Data flows one way: parameters ([`variables`]) -> friction law ([`friction`]) + model
//! equations ([`models`]) -> outputs -> the FMI getters ([`fmi2`], the only `unsafe` code).

// Only the FMI boundary (src/fmi2), the in-process importer that calls it and the CPU clock use
// `unsafe`: each module that does is allowed it by name.
#![deny(unsafe_code)]

#[allow(unsafe_code)]
pub mod boundary;
#[cfg(feature = "tools")]
#[allow(unsafe_code)]
pub mod cpu_clock;
pub mod error;
pub mod fmi2;
pub mod fmi3;
pub mod friction;
#[cfg(feature = "tools")]
#[allow(unsafe_code)]
pub mod importer;
pub mod instance;
pub mod model_description;
pub mod models;
#[cfg(feature = "tools")]
pub mod package;
#[cfg(feature = "tools")]
pub mod report;
pub mod solve;
pub mod variables;
pub mod variant;
