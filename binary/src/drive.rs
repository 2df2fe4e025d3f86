//! The library of DriveTrain's FMU: accepts its GUID alone.
// The crate is named as the FMU's modelIdentifier, the file name FMI requires.
#![allow(non_snake_case)]
friction_fmu::export_fmu_library!(DRIVE, full);
