//! Messages to an FMI 2.0 importer's logger. The message is always passed as the argument of a
//! "%s" format, so a '%' in a variable name or value can never be read as a format directive.

use super::ffi::{CallbackLogger, ComponentEnvironment, Status};
use crate::instance::log::{self, readable_numbers, LogSink};
use std::ffi::CString;

pub struct Logger {
    callback: Option<CallbackLogger>,
    environment: ComponentEnvironment,
    instance_name: CString,
}

fn c_string(text: &str) -> CString {
    // Interior NULs would cut the message short; show them instead.
    CString::new(text.replace('\0', "\\0")).unwrap_or_default()
}

impl Logger {
    pub fn new(
        callback: Option<CallbackLogger>,
        environment: ComponentEnvironment,
        instance_name: &str,
    ) -> Self {
        Logger {
            callback,
            environment,
            instance_name: c_string(instance_name),
        }
    }

    pub fn log(&self, status: Status, category: &str, message: &str) {
        if let Some(callback) = self.callback {
            let category = c_string(category);
            let message = c_string(&readable_numbers(message));
            // SAFETY: the importer promised a valid logger for the instance's lifetime
            // (fmi2Instantiate refuses a NULL one); every pointer passed lives until it returns.
            unsafe {
                callback(
                    self.environment,
                    self.instance_name.as_ptr(),
                    status,
                    category.as_ptr(),
                    c"%s".as_ptr(),
                    message.as_ptr(),
                );
            }
        }
    }
}

impl LogSink for Logger {
    fn log(&self, status: log::Status, category: &str, message: &str) {
        Logger::log(self, status.into(), category, message);
    }
}
