//! The intermediate-update callbacks importers gave their FMI 3.0 instances, by handle: called by
//! fmi3DoStep at the end of each internal step, with no borrow of the instance held, so that the
//! importer can read outputs and set inputs from inside the callback.

use super::ffi::{InstanceEnvironment, IntermediateUpdateCallback};
use std::sync::Mutex;

/// (handle, callback, instance environment as an address).
static UPDATES: Mutex<Vec<(usize, IntermediateUpdateCallback, usize)>> = Mutex::new(Vec::new());

fn updates() -> std::sync::MutexGuard<'static, Vec<(usize, IntermediateUpdateCallback, usize)>> {
    UPDATES.lock().unwrap_or_else(|e| e.into_inner())
}

/// Keeps `callback` for the instance `handle`.
pub fn register(
    handle: usize,
    callback: IntermediateUpdateCallback,
    environment: InstanceEnvironment,
) {
    updates().push((handle, callback, environment as usize));
}

/// The callback of the instance `handle`, if its importer gave one.
pub fn of(handle: usize) -> Option<(IntermediateUpdateCallback, InstanceEnvironment)> {
    updates()
        .iter()
        .find(|(h, _, _)| *h == handle)
        .map(|&(_, callback, environment)| (callback, environment as InstanceEnvironment))
}

/// Forgets the callback of a freed instance; the list's memory goes with the last one.
pub fn forget(handle: usize) {
    let mut updates = updates();
    updates.retain(|(h, _, _)| *h != handle);
    if updates.is_empty() {
        *updates = Vec::new();
    }
}
