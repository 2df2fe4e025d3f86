//! FMU states as both standards' importers pass them, and the results both make of the state
//! calls' statuses.

use crate::fmi2::ffi::FmuState;

/// An FMU state this driver got from an instance, as the bare address the FMU handed out.
///
/// A `State` carries no ownership: it may be stale (freed), belong to another instance, or be
/// made up with [`State::from_address`]; the FMU refuses each of those with an error.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct State(usize);

impl State {
    pub const NULL: State = State(0);

    pub fn from_address(address: usize) -> State {
        State(address)
    }

    pub fn address(self) -> usize {
        self.0
    }

    /// The state as both standards pass it (FMI 2.0's and FMI 3.0's FMU states are pointers).
    pub(super) fn pointer(self) -> FmuState {
        self.0 as FmuState
    }

    /// Passes the state to `call` as the FMU-state slot it may overwrite (fmi2/fmi3 Get, Free
    /// and DeSerialize) and keeps what the call leaves there: a new state, NULL, or itself.
    pub(super) fn through<S>(&mut self, call: impl FnOnce(&mut FmuState) -> S) -> S {
        let mut slot = self.pointer();
        let status = call(&mut slot);
        *self = State(slot as usize);
        status
    }
}

/// `value` if the call that gave it returned `ok`, else the call's status.
pub(super) fn ok_then<S: PartialEq, T>(status: S, ok: S, value: T) -> Result<T, S> {
    if status == ok {
        Ok(value)
    } else {
        Err(status)
    }
}

/// A state's bytes, as both standards serialize: `size` is what the size call returned, then
/// `serialize` fills a buffer of that size. The first status other than `ok` is the error.
pub(super) fn serialized<S: PartialEq>(
    ok: S,
    (status, size): (S, usize),
    serialize: impl FnOnce(&mut [u8]) -> S,
) -> Result<Vec<u8>, S> {
    if status != ok {
        return Err(status);
    }
    let mut bytes = vec![0; size];
    let status = serialize(&mut bytes);
    ok_then(status, ok, bytes)
}
