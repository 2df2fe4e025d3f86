//! The log each importer instance keeps of what its FMU logged, the same for FMI 2.0 and 3.0.

use std::sync::{Mutex, MutexGuard};

/// One message the FMU sent to its logger.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    /// The status the FMU logged with, as its integer (0 = OK ... 4 = Fatal in both standards).
    pub status: i32,
    pub category: String,
    pub text: String,
}

/// Where an instance's logger writes: one per importer instance of either standard, boxed (alone
/// or in the FMI 3.0 environment) so its address, passed to the FMU as the environment its
/// logger gets back, stays put while the instance lives.
#[derive(Default)]
pub(super) struct Sink {
    messages: Mutex<Vec<Message>>,
}

impl Sink {
    pub(super) fn lock(&self) -> MutexGuard<'_, Vec<Message>> {
        // A panicking test thread must not hide the log from the others.
        self.messages.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The messages logged so far, oldest first.
    pub(super) fn messages(&self) -> Vec<Message> {
        self.lock().clone()
    }

    /// The text of the last message logged, or "" if none.
    pub(super) fn last_text(&self) -> String {
        self.lock()
            .last()
            .map(|m| m.text.clone())
            .unwrap_or_default()
    }

    /// Removes and returns the messages logged so far.
    pub(super) fn take(&self) -> Vec<Message> {
        std::mem::take(&mut *self.lock())
    }
}

/// What `ImportedInstance::new` of either standard returns for a model this binary does not
/// contain: a log of one refusal with status `error`.
pub(super) fn no_model(model_identifier: &str, error: i32) -> Vec<Message> {
    vec![Message {
        status: error,
        category: "driver".into(),
        text: format!("no model {model_identifier} in this binary"),
    }]
}
