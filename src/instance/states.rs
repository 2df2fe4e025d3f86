//! FMU states: taken, restored, freed, serialized and read back. The importer holds a state by
//! its address; the instance owns the state and accepts only addresses it handed out and has not
//! freed, so a freed or foreign state is refused instead of read.

use super::calls::Call;
use super::snapshot::{self, Snapshot};
use super::{Instance, Status};

/// The address the importer holds for a state.
fn address(state: &Snapshot) -> usize {
    state as *const Snapshot as usize
}

impl Instance {
    /// Where this instance keeps the state at `address`, if it handed it out.
    fn state_index(&self, address: usize) -> Option<usize> {
        self.snapshots
            .iter()
            .position(|s| self::address(s) == address)
    }

    /// The state at `address`, or a refusal naming `call`.
    fn own_state(&self, call: Call, address: usize) -> Result<&Snapshot, Status> {
        match self.state_index(address) {
            Some(i) => Ok(&self.snapshots[i]),
            None => Err(self.error(&format!(
                "{}: the FMUstate was not made by this instance (or was freed): expected a state from {} or {} of this instance",
                self.function(call),
                self.function(Call::GetFMUstate),
                self.function(Call::DeSerializeFMUstate)
            ))),
        }
    }

    /// Keeps `state` at `slot` (a state of this instance, overwritten) or as a new state (None);
    /// returns its address.
    fn keep_state(&mut self, state: Snapshot, slot: Option<usize>) -> usize {
        match slot.and_then(|a| self.state_index(a)) {
            Some(i) => {
                *self.snapshots[i] = state;
                address(&self.snapshots[i])
            }
            None => {
                let state = Box::new(state);
                let at = address(&state);
                self.snapshots.push(state);
                at
            }
        }
    }

    /// Takes the instance's state into `slot`: None for a new state, else a state of this
    /// instance to overwrite. Returns the state's address.
    pub fn get_state(&mut self, slot: Option<usize>) -> Result<usize, Status> {
        self.check_phase(Call::GetFMUstate)?;
        if slot.is_some_and(|a| self.state_index(a).is_none()) {
            let function = self.function(Call::GetFMUstate);
            return Err(self.error(&format!(
                "{function}: *FMUstate is neither NULL nor a state of this instance: expected NULL or a state from {function} of this instance"
            )));
        }
        let state = Snapshot::take(self);
        Ok(self.keep_state(state, slot))
    }

    /// Puts the instance back to the state at `address`.
    pub fn set_state(&mut self, address: usize) -> Status {
        if let Err(status) = self.check_phase(Call::SetFMUstate) {
            return status;
        }
        if let Err(status) = self.own_state(Call::SetFMUstate, address) {
            return status;
        }
        // Out of the list while it restores the instance (no copy), and back after.
        let Some(i) = self.state_index(address) else {
            return Status::Error;
        };
        let state = self.snapshots.swap_remove(i);
        let restored = state.restore(self);
        self.snapshots.push(state);
        match restored {
            Ok(()) => Status::Ok,
            Err(message) => {
                let function = self.function(Call::SetFMUstate);
                self.error(&format!("{function}: {message}"))
            }
        }
    }

    /// Frees the state at `address`.
    pub fn free_state(&mut self, address: usize) -> Status {
        if let Err(status) = self.check_phase(Call::FreeFMUstate) {
            return status;
        }
        match self.own_state(Call::FreeFMUstate, address) {
            Ok(_) => {
                self.snapshots.retain(|s| self::address(s) != address);
                Status::Ok
            }
            Err(status) => status,
        }
    }

    /// The size of the state at `address` in bytes.
    pub fn serialized_state_size(&self, address: usize) -> Result<usize, Status> {
        self.check_phase(Call::SerializedFMUstateSize)?;
        Ok(self
            .own_state(Call::SerializedFMUstateSize, address)?
            .to_bytes()
            .len())
    }

    /// The bytes of the state at `address`, which must fit in `size` bytes.
    pub fn serialize_state(&self, address: usize, size: usize) -> Result<Vec<u8>, Status> {
        self.check_phase(Call::SerializeFMUstate)?;
        let data = self.own_state(Call::SerializeFMUstate, address)?.to_bytes();
        if size < data.len() {
            return Err(self.error(&format!(
                "{}: size = {size} is too small: expected {} bytes ({})",
                self.function(Call::SerializeFMUstate),
                data.len(),
                self.function(Call::SerializedFMUstateSize)
            )));
        }
        Ok(data)
    }

    /// Checks the first [`snapshot::HEADER`] bytes (or fewer) of serialized state before the
    /// rest is read: a `size` beyond the length they declare is refused here, so nothing past
    /// the data's end is read.
    pub fn check_serialized_header(&self, header: &[u8], size: usize) -> Result<(), Status> {
        self.check_phase(Call::DeSerializeFMUstate)?;
        match snapshot::declared_length(header) {
            Some(length) if length != size as u64 => Err(self.error(&format!(
                "{}: the serialized FMU state is not valid: size = {size}, but it says it is {length} bytes long; expected the size {} gave",
                self.function(Call::DeSerializeFMUstate),
                self.function(Call::SerializedFMUstateSize)
            ))),
            _ => Ok(()),
        }
    }

    /// Reads serialized state into `slot` (as [`Instance::get_state`]); returns its address.
    pub fn deserialize_state(
        &mut self,
        bytes: &[u8],
        slot: Option<usize>,
    ) -> Result<usize, Status> {
        self.check_phase(Call::DeSerializeFMUstate)?;
        let sizes = self.function(Call::SerializedFMUstateSize);
        match Snapshot::from_bytes(bytes, self.guid(), self.id, sizes) {
            Ok(state) => Ok(self.keep_state(state, slot)),
            Err(message) => {
                let function = self.function(Call::DeSerializeFMUstate);
                Err(self.error(&format!("{function}: {message}")))
            }
        }
    }
}
