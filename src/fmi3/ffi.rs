//! The C types of the FMI 3.0 API (fmi3PlatformTypes.h, fmi3FunctionTypes.h).

use std::ffi::{c_char, c_void};

pub type FmiInstance = *mut c_void;
pub type InstanceEnvironment = *mut c_void;
pub type FmuState = *mut c_void;
pub type ValueReference = u32;
pub type FmiString = *const c_char;
pub type Byte = u8;
pub type BinaryValue = *const u8;
/// fmi3Boolean is C's `bool`: read as a byte, so that a value other than 0 or 1 from the
/// importer is not undefined behaviour here.
pub type Boolean = u8;
pub type Clock = u8;

pub const TRUE: Boolean = 1;
pub const FALSE: Boolean = 0;

/// fmi3Status: the instance's own status, whose numbers are FMI 3.0's.
pub use crate::instance::log::Status;

/// fmi3DependencyKind and fmi3IntervalQualifier, as plain C enums.
pub type DependencyKind = std::ffi::c_int;
pub type IntervalQualifier = std::ffi::c_int;

pub type LogMessageCallback =
    unsafe extern "C" fn(InstanceEnvironment, Status, FmiString, FmiString);
pub type ClockUpdateCallback = unsafe extern "C" fn(InstanceEnvironment);
pub type LockPreemptionCallback = unsafe extern "C" fn();
pub type UnlockPreemptionCallback = unsafe extern "C" fn();
pub type IntermediateUpdateCallback = unsafe extern "C" fn(
    InstanceEnvironment,
    f64,
    Boolean,
    Boolean,
    Boolean,
    Boolean,
    *mut Boolean,
    *mut f64,
);
