//! The library of a variant FMU of LongitudinalFriction: reads its resources/variant.toml and
//! accepts only that file's GUID.
// The crate is named as the FMU's modelIdentifier, the file name FMI requires.
#![allow(non_snake_case)]
friction_fmu::export_fmu_library!(LONGITUDINAL, variant);
