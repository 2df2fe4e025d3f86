//! The FMU-state calls' shared bodies: the importer holds a state as a pointer, which is the
//! address the instance handed out for it.

use super::args::{slice, slice_mut};
use crate::instance::calls::{Call, Dialect};
use crate::instance::{handles, snapshot, Status};
use std::ffi::c_void;

type State = *mut c_void;

/// The address of the state a slot holds, None for NULL (a new state).
fn slot_address(slot: State) -> Option<usize> {
    (!slot.is_null()).then_some(slot as usize)
}

/// Takes a state into `*state` (a new one if `*state` is NULL, else overwriting one this
/// instance handed out).
///
/// # Safety
/// `state` is NULL or points to a state pointer.
pub unsafe fn get(handle: usize, dialect: &'static Dialect, state: *mut State) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        instance.trace(|| format!("{}()", instance.function(Call::GetFMUstate)));
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::GetFMUstate, "FMUstate");
        };
        match instance.get_state(slot_address(*slot)) {
            Ok(address) => {
                *slot = address as State;
                Status::Ok
            }
            Err(status) => status,
        }
    })
}

/// # Safety
/// None: `state` is only compared with the addresses the instance handed out.
pub unsafe fn set(handle: usize, dialect: &'static Dialect, state: State) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        instance.trace(|| format!("{}({state:?})", instance.function(Call::SetFMUstate)));
        instance.set_state(state as usize)
    })
}

/// # Safety
/// `state` is NULL or points to a state pointer.
pub unsafe fn free(handle: usize, dialect: &'static Dialect, state: *mut State) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::FreeFMUstate, "FMUstate");
        };
        let Some(address) = slot_address(*slot) else {
            return instance
                .check_phase(Call::FreeFMUstate)
                .err()
                .unwrap_or(Status::Ok);
        };
        let status = instance.free_state(address);
        if status == Status::Ok {
            *slot = std::ptr::null_mut();
        }
        status
    })
}

/// # Safety
/// `size` is NULL or points to a size_t.
pub unsafe fn serialized_size(
    handle: usize,
    dialect: &'static Dialect,
    state: State,
    size: *mut usize,
) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        let Some(size) = size.as_mut() else {
            return instance.null_argument(Call::SerializedFMUstateSize, "size");
        };
        match instance.serialized_state_size(state as usize) {
            Ok(length) => {
                *size = length;
                Status::Ok
            }
            Err(status) => status,
        }
    })
}

/// # Safety
/// `bytes` is NULL or has room for `size` bytes.
pub unsafe fn serialize(
    handle: usize,
    dialect: &'static Dialect,
    state: State,
    bytes: *mut u8,
    size: usize,
) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        let data = match instance.serialize_state(state as usize, size) {
            Ok(data) => data,
            Err(status) => return status,
        };
        let Some(out) = slice_mut(bytes, data.len()) else {
            return instance.null_argument(Call::SerializeFMUstate, "serializedState");
        };
        out.copy_from_slice(&data);
        Status::Ok
    })
}

/// # Safety
/// `bytes` is NULL or holds `size` bytes; `state` is NULL or points to a state pointer.
pub unsafe fn deserialize(
    handle: usize,
    dialect: &'static Dialect,
    bytes: *const u8,
    size: usize,
    state: *mut State,
) -> Status {
    handles::with_instance(handle, dialect, |instance| {
        let function = instance.function(Call::DeSerializeFMUstate);
        instance.trace(|| format!("{function}(size = {size})"));
        // The header first: a size beyond the length it declares is refused before the data
        // is read that far.
        let Some(header) = slice(bytes, size.min(snapshot::HEADER)) else {
            return instance.null_argument(Call::DeSerializeFMUstate, "serializedState");
        };
        if let Err(status) = instance.check_serialized_header(header, size) {
            return status;
        }
        let Some(data) = slice(bytes, size) else {
            return instance.null_argument(Call::DeSerializeFMUstate, "serializedState");
        };
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::DeSerializeFMUstate, "FMUstate");
        };
        match instance.deserialize_state(data, slot_address(*slot)) {
            Ok(address) => {
                *slot = address as State;
                Status::Ok
            }
            Err(status) => status,
        }
    })
}
