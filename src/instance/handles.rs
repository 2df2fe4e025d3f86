//! The handles importers hold, for both standards: an instance is reached only through a handle
//! this library handed out and has not freed, and only by the standard that made it.
//!
//! The handle is the instance's id, never reused, not its address: the allocator may give a
//! freed instance's address to the next one, and a freed handle must not come to stand for it.
//! Calls on anything else (freed, NULL, garbage, another standard's) are refused. No panic
//! crosses the C boundary: every call runs under `catch_unwind`.

use super::calls::{Call, Dialect};
use super::log::Status;
use super::phase::Phase;
use super::Instance;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;

/// A live instance: its handle, its address, and the standard that made it.
struct Live {
    handle: usize,
    address: usize,
    dialect: &'static Dialect,
}

static LIVE: Mutex<Vec<Live>> = Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<Live>> {
    // A panic while holding the lock cannot leave the list inconsistent: recover it.
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Hands the instance out; its handle (its id, which is never 0) is what the importer holds.
pub fn register(instance: Instance) -> usize {
    let handle = instance.id as usize;
    let dialect = instance.dialect;
    let address = Box::into_raw(Box::new(instance)) as usize;
    live().push(Live {
        handle,
        address,
        dialect,
    });
    handle
}

/// Runs `body` on the live instance `handle` names for `dialect`'s standard, catching panics so
/// none crosses into the importer; fmi2Error-like [`Status::Error`] for anything else (there is
/// no instance, so no logger to tell).
pub fn with_instance(
    handle: usize,
    dialect: &'static Dialect,
    body: impl FnOnce(&mut Instance) -> Status,
) -> Status {
    let address = live()
        .iter()
        .find(|live| live.handle == handle && std::ptr::eq(live.dialect, dialect))
        .map(|live| live.address);
    let Some(address) = address else {
        return Status::Error;
    };
    // SAFETY: the handle is in LIVE, so `address` is a Box<Instance> registered and not freed
    // yet; both standards forbid calling one instance from two threads at once.
    #[allow(unsafe_code)]
    let instance = unsafe { &mut *(address as *mut Instance) };
    match catch_unwind(AssertUnwindSafe(|| body(&mut *instance))) {
        Ok(status) => status,
        Err(_) => {
            instance.phase = Phase::Error;
            let reset = (dialect.function)(Call::Reset);
            let free = &reset[..reset.len().saturating_sub("Reset".len())];
            instance.error(&format!(
                "internal error (a bug in the FMU): the instance is in error state; call {reset} or {free}FreeInstance"
            ))
        }
    }
}

/// Frees the instance `handle` names for `dialect`'s standard, with the FMU states it handed
/// out; NULL, foreign or already freed handles are ignored.
pub fn free(handle: usize, dialect: &'static Dialect) {
    let removed = {
        let mut live = live();
        let removed = live
            .iter()
            .position(|l| l.handle == handle && std::ptr::eq(l.dialect, dialect))
            .map(|i| live.swap_remove(i).address);
        // The list's memory goes with the last instance, so unloading the library leaks nothing.
        if live.is_empty() {
            *live = Vec::new();
        }
        removed
    };
    if let Some(address) = removed {
        let _ = catch_unwind(AssertUnwindSafe(|| {
            // SAFETY: it was live, and only this call could remove it.
            #[allow(unsafe_code)]
            drop(unsafe { Box::from_raw(address as *mut Instance) });
            crate::variant::registry::release_unused();
        }));
    }
}
