//! Messages to an FMI 3.0 importer's logMessage callback. FMI 3.0 passes the message as it is
//! (no format string), so a '%' in it is plain text.

use super::ffi::{FmiString, InstanceEnvironment, LogMessageCallback};
use crate::instance::log::{readable_numbers, LogSink, Status};
use std::ffi::CString;

pub struct Logger {
    callback: Option<LogMessageCallback>,
    environment: InstanceEnvironment,
}

fn c_string(text: &str) -> CString {
    // Interior NULs would cut the message short; show them instead.
    CString::new(text.replace('\0', "\\0")).unwrap_or_default()
}

impl Logger {
    /// A logger that calls `callback` with `environment`; None logs nothing (FMI 3.0 lets an
    /// importer pass no callback).
    pub fn new(callback: Option<LogMessageCallback>, environment: InstanceEnvironment) -> Self {
        Logger {
            callback,
            environment,
        }
    }
}

impl LogSink for Logger {
    fn log(&self, status: Status, category: &str, message: &str) {
        if let Some(callback) = self.callback {
            let category = c_string(category);
            let message = c_string(&readable_numbers(message));
            let (category, message): (FmiString, FmiString) = (category.as_ptr(), message.as_ptr());
            // SAFETY: the importer promised a valid callback for the instance's lifetime; every
            // pointer passed lives until it returns.
            unsafe { callback(self.environment, status, category, message) };
        }
    }
}
