//! The promises every call keeps in both standards, checked after each call of a sequence: its
//! status is one of the standard's, a call on a freed instance is refused and logs nothing, a
//! refusal is explained in the log, and a value returned with OK is finite.

use friction_fmu::importer::Message;
use std::fmt::Debug;

/// fmi2Status and fmi3Status, which number OK .. Fatal alike (FMI 2.0 adds Pending).
pub trait FmiStatus: Copy + PartialEq + Debug {
    const OK: Self;
    const WARNING: Self;
    const ERROR: Self;
    fn code(self) -> i32;
}

/// Implements [`FmiStatus`] for a standard's status enum, whose variants are named alike.
macro_rules! fmi_status {
    ($status:ty) => {
        impl FmiStatus for $status {
            const OK: Self = Self::Ok;
            const WARNING: Self = Self::Warning;
            const ERROR: Self = Self::Error;
            fn code(self) -> i32 {
                self as i32
            }
        }
    };
}

fmi_status!(friction_fmu::fmi2::ffi::Status);
fmi_status!(friction_fmu::fmi3::ffi::Status);

/// Whether a message of Warning or worse names `function`: what explains a refusal.
pub fn explained<S: FmiStatus>(messages: &[Message], function: &str) -> bool {
    messages
        .iter()
        .any(|m| m.status >= S::WARNING.code() && m.text.contains(function))
}

/// Call `call` of a sequence, `function` with `description`, returned `status` and logged
/// `messages`: the status is one of the standard's (0..=4: never fmi2Pending, steps are
/// synchronous); on an instance that is not `live` (freed) it is Error with nothing logged; on a
/// live one that `logs` (has a logger, without which it cannot explain) anything but OK comes with
/// a message naming the function.
pub fn status_kept_its_promises<S: FmiStatus>(
    call: usize,
    function: &str,
    description: &str,
    status: S,
    live: bool,
    logs: bool,
    messages: &[Message],
) -> Result<(), String> {
    if !(0..=4).contains(&status.code()) {
        return Err(format!(
            "call {call}: {function}{description} returned {status:?} ({})",
            status.code()
        ));
    }
    if !live {
        if status != S::ERROR || !messages.is_empty() {
            return Err(format!(
                "call {call}: {function} on a freed instance gave {status:?} {messages:?}"
            ));
        }
    } else if status != S::OK && logs && !explained::<S>(messages, function) {
        return Err(format!(
            "call {call}: {function}{description} returned {status:?} without a message naming it: {messages:?}"
        ));
    }
    Ok(())
}

/// A getter that returns OK returns finite values.
pub fn finite_when_ok<S: FmiStatus>(
    call: usize,
    function: &str,
    description: &str,
    status: S,
    values: &[f64],
) -> Result<(), String> {
    if status == S::OK && values.iter().any(|x| !x.is_finite()) {
        return Err(format!(
            "call {call}: {function}{description} returned OK with a non-finite value"
        ));
    }
    Ok(())
}
