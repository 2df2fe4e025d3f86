//! The C types of the FMI 2.0 API (fmi2TypesPlatform.h, fmi2FunctionTypes.h).

use std::ffi::{c_char, c_int, c_void};

pub type Component = *mut c_void;
pub type ComponentEnvironment = *mut c_void;
pub type FmuState = *mut c_void;
pub type ValueReference = u32;
pub type Real = f64;
pub type Integer = c_int;
pub type Boolean = c_int;
pub type Char = c_char;
pub type FmiString = *const c_char;
pub type Byte = c_char;

pub const TRUE: Boolean = 1;
pub const FALSE: Boolean = 0;

/// fmi2Status
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
    Pending = 5,
}

/// fmi2Type
pub const MODEL_EXCHANGE: c_int = 0;
pub const CO_SIMULATION: c_int = 1;

/// fmi2StatusKind
pub const DO_STEP_STATUS: c_int = 0;
pub const PENDING_STATUS: c_int = 1;
pub const LAST_SUCCESSFUL_TIME: c_int = 2;
pub const TERMINATED: c_int = 3;

/// The variadic logger: called with a "%s" format and the message as its one argument.
pub type CallbackLogger =
    unsafe extern "C" fn(ComponentEnvironment, FmiString, Status, FmiString, FmiString, ...);
pub type CallbackAllocateMemory = unsafe extern "C" fn(usize, usize) -> *mut c_void;
pub type CallbackFreeMemory = unsafe extern "C" fn(*mut c_void);
pub type StepFinished = unsafe extern "C" fn(ComponentEnvironment, Status);

/// fmi2CallbackFunctions
#[repr(C)]
pub struct CallbackFunctions {
    pub logger: Option<CallbackLogger>,
    pub allocate_memory: Option<CallbackAllocateMemory>,
    pub free_memory: Option<CallbackFreeMemory>,
    pub step_finished: Option<StepFinished>,
    pub component_environment: ComponentEnvironment,
}

impl From<crate::instance::log::Status> for Status {
    fn from(status: crate::instance::log::Status) -> Status {
        use crate::instance::log::Status as S;
        match status {
            S::Ok => Status::Ok,
            S::Warning => Status::Warning,
            S::Discard => Status::Discard,
            S::Error => Status::Error,
            S::Fatal => Status::Fatal,
        }
    }
}
