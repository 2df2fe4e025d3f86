//! friction-fmu: friction-vibration contact models as FMI 2.0 co-simulation FMUs.
//!
//! Data flows one way: parameters ([`interface`]) -> friction law ([`friction`]) + scene
//! equations ([`scenes`]) -> outputs -> the FMI getters ([`fmi2`], the only `unsafe` code).

pub mod fmi2;
pub mod friction;
pub mod interface;
pub mod model_description;
pub mod package;
pub mod report;
pub mod scene_file;
pub mod scenes;
pub mod solve;
