//! Messages to the importer's logger. The message is always passed as the argument of a "%s"
//! format, so a '%' in a variable name or value can never be read as a format directive.

use super::ffi::{CallbackLogger, ComponentEnvironment, Status};
use std::ffi::CString;

pub const CATEGORY_ERROR: &str = "logStatusError";
pub const CATEGORY_WARNING: &str = "logStatusWarning";
pub const CATEGORY_CALLS: &str = "logCalls";

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

/// The message with every number that Rust's `{}` spells out in more than 21 characters (1e300
/// as 301 digits, 1e-300 as 300 zeros and a 1) in scientific notation instead.
pub fn readable_numbers(message: &str) -> String {
    const LONGEST: usize = 21;
    let mut out = String::with_capacity(message.len());
    let mut run = String::new();
    let flush = |run: &mut String, out: &mut String| {
        // A run can end on a sentence's full stop: keep it out of the number.
        let number = run.strip_suffix('.').unwrap_or(run);
        match number.parse::<f64>() {
            Ok(x) if number.len() > LONGEST => {
                out.push_str(&format!("{x:e}"));
                out.push_str(&run[number.len()..]);
            }
            _ => out.push_str(run),
        }
        run.clear();
    };
    for ch in message.chars() {
        if ch.is_ascii_digit() || ch == '.' {
            run.push(ch);
        } else {
            flush(&mut run, &mut out);
            out.push(ch);
        }
    }
    flush(&mut run, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::readable_numbers;

    #[test]
    fn long_numbers_become_scientific_and_the_rest_stays() {
        let huge = format!("h = {} s.", 1e300);
        assert_eq!(readable_numbers(&huge), "h = 1e300 s.");
        let tiny = format!("m = -{} kg: expected", 2.2250738585072014e-308);
        assert_eq!(
            readable_numbers(&tiny),
            "m = -2.2250738585072014e-308 kg: expected"
        );
        let plain = "t = 0.06283185307179587 by 1e-5, v1.2.3, 12345678901234567890 ok";
        assert_eq!(readable_numbers(plain), plain);
    }
}
