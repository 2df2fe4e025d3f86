//! The FMU-state calls of a sequence, which both standards make alike: get, update, set and free
//! an FMU state, size and serialize one into a buffer of random room (keeping the bytes as raw
//! material for corrupted ones), and deserialize corrupted bytes, each on a state picked from
//! those the sequence made (freed, of the other instance, or NULL).

use super::checks::FmiStatus;
use super::rng::Rng;
use super::serialized::mutate;
use friction_fmu::importer::State;

/// One FMU-state call.
#[derive(Clone, Copy, Debug)]
pub enum StateOp {
    /// Get an FMU state, serialize it into the pool of bytes to corrupt, free it.
    SeedBytes,
    Get,
    Update,
    Set,
    Free,
    SerializedSize,
    Serialize,
    Deserialize,
    DeserializeInto,
}

/// The FMU-state calls among a sequence's random calls, each as often as it stands here.
pub const RANDOM: [StateOp; 12] = [
    StateOp::Get,
    StateOp::Get,
    StateOp::Update,
    StateOp::Set,
    StateOp::Set,
    StateOp::Free,
    StateOp::SerializedSize,
    StateOp::Serialize,
    StateOp::Serialize,
    StateOp::Deserialize,
    StateOp::Deserialize,
    StateOp::DeserializeInto,
];

/// The FMU-state functions of an instance of either standard (the importer's, src/importer).
pub trait FmuStates {
    type Status: FmiStatus;
    /// The C function `op` calls, as the standard spells it.
    fn function(op: StateOp) -> &'static str;
    /// The C function that sizes a serialized state.
    const SIZE_FUNCTION: &'static str;
    fn get_fmu_state(&mut self) -> Result<State, Self::Status>;
    fn update_fmu_state(&mut self, state: &mut State) -> Self::Status;
    fn set_fmu_state(&mut self, state: State) -> Self::Status;
    fn free_fmu_state(&mut self, state: &mut State) -> Self::Status;
    fn serialized_fmu_state_size(&mut self, state: State) -> (Self::Status, usize);
    fn serialize_fmu_state_into(&mut self, state: State, buffer: &mut [u8]) -> Self::Status;
    fn serialize_fmu_state(&mut self, state: State) -> Result<Vec<u8>, Self::Status>;
    fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<State, Self::Status>;
    fn deserialize_fmu_state_into(&mut self, bytes: &[u8], state: &mut State) -> Self::Status;
    fn last_message(&self) -> String;
}

/// Implements [`FmuStates`] for an importer's instance by its methods of the same names.
macro_rules! fmu_states {
    ($instance:ty, $status:ty, $size_function:literal, $function:expr) => {
        impl FmuStates for $instance {
            type Status = $status;
            const SIZE_FUNCTION: &'static str = $size_function;
            fn function(op: StateOp) -> &'static str {
                $function(op)
            }
            fn get_fmu_state(&mut self) -> Result<State, $status> {
                <$instance>::get_fmu_state(self)
            }
            fn update_fmu_state(&mut self, state: &mut State) -> $status {
                <$instance>::update_fmu_state(self, state)
            }
            fn set_fmu_state(&mut self, state: State) -> $status {
                <$instance>::set_fmu_state(self, state)
            }
            fn free_fmu_state(&mut self, state: &mut State) -> $status {
                <$instance>::free_fmu_state(self, state)
            }
            fn serialized_fmu_state_size(&mut self, state: State) -> ($status, usize) {
                <$instance>::serialized_fmu_state_size(self, state)
            }
            fn serialize_fmu_state_into(&mut self, state: State, buffer: &mut [u8]) -> $status {
                <$instance>::serialize_fmu_state_into(self, state, buffer)
            }
            fn serialize_fmu_state(&mut self, state: State) -> Result<Vec<u8>, $status> {
                <$instance>::serialize_fmu_state(self, state)
            }
            fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<State, $status> {
                <$instance>::deserialize_fmu_state(self, bytes)
            }
            fn deserialize_fmu_state_into(&mut self, bytes: &[u8], state: &mut State) -> $status {
                <$instance>::deserialize_fmu_state_into(self, bytes, state)
            }
            fn last_message(&self) -> String {
                <$instance>::last_message(self)
            }
        }
    };
}

fmu_states!(
    friction_fmu::importer::ImportedInstance,
    friction_fmu::fmi2::ffi::Status,
    "fmi2SerializedFMUstateSize",
    |op| match op {
        StateOp::SeedBytes | StateOp::Get | StateOp::Update => "fmi2GetFMUstate",
        StateOp::Set => "fmi2SetFMUstate",
        StateOp::Free => "fmi2FreeFMUstate",
        StateOp::SerializedSize => "fmi2SerializedFMUstateSize",
        StateOp::Serialize => "fmi2SerializeFMUstate",
        StateOp::Deserialize | StateOp::DeserializeInto => "fmi2DeSerializeFMUstate",
    }
);

fmu_states!(
    friction_fmu::importer::fmi3::ImportedInstance,
    friction_fmu::fmi3::ffi::Status,
    "fmi3SerializedFMUStateSize",
    |op| match op {
        StateOp::SeedBytes | StateOp::Get | StateOp::Update => "fmi3GetFMUState",
        StateOp::Set => "fmi3SetFMUState",
        StateOp::Free => "fmi3FreeFMUState",
        StateOp::SerializedSize => "fmi3SerializedFMUStateSize",
        StateOp::Serialize => "fmi3SerializeFMUState",
        StateOp::Deserialize | StateOp::DeserializeInto => "fmi3DeserializeFMUState",
    }
);

/// The FMU states and serialized bytes a sequence has made, which its calls pick from.
pub struct Made {
    /// FMU states, valid or not: NULL, freed ones, the other instance's.
    pub states: Vec<State>,
    /// Serialized states, raw material for corrupted ones.
    pub blobs: Vec<Vec<u8>>,
}

impl Made {
    pub fn new() -> Made {
        Made {
            states: vec![State::NULL],
            blobs: Vec::new(),
        }
    }

    /// Keeps a serialized state, in place of a random one once there are 64.
    fn keep(&mut self, rng: &mut Rng, bytes: Vec<u8>) {
        if self.blobs.len() < 64 {
            self.blobs.push(bytes);
        } else {
            let i = rng.below(self.blobs.len());
            self.blobs[i] = bytes;
        }
    }
}

/// What an FMU-state call returned, and what names it in a report.
pub struct Called<S> {
    pub status: S,
    /// The function that returned the status (the sizing one, when serializing stopped there).
    pub function: &'static str,
    pub description: String,
}

/// Makes call `call` of a sequence, `op` on `instance` with `state`; Err for a broken promise (a
/// buffer of enough room refused).
pub fn call<I: FmuStates>(
    op: StateOp,
    instance: &mut I,
    rng: &mut Rng,
    state: State,
    made: &mut Made,
    call: usize,
    verbose: bool,
) -> Result<Called<I::Status>, String> {
    let mut function = I::function(op);
    let mut description = String::new();
    let ok = <I::Status as FmiStatus>::OK;
    let status = match op {
        StateOp::SeedBytes => match instance.get_fmu_state() {
            Ok(mut state) => {
                let bytes = instance.serialize_fmu_state(state);
                made.blobs.extend(bytes);
                instance.free_fmu_state(&mut state)
            }
            Err(status) => status,
        },
        StateOp::Get => match instance.get_fmu_state() {
            Ok(state) => {
                made.states.push(state);
                ok
            }
            Err(status) => status,
        },
        StateOp::Update => {
            let mut target = state;
            description = format!("({:#x})", state.address());
            let status = instance.update_fmu_state(&mut target);
            made.states.push(target);
            status
        }
        StateOp::Set => {
            description = format!("({:#x})", state.address());
            instance.set_fmu_state(state)
        }
        StateOp::Free => {
            let mut target = state;
            description = format!("({:#x})", state.address());
            instance.free_fmu_state(&mut target)
        }
        StateOp::SerializedSize => instance.serialized_fmu_state_size(state).0,
        StateOp::Serialize => {
            let (status, size) = instance.serialized_fmu_state_size(state);
            if status != ok {
                function = I::SIZE_FUNCTION;
                status
            } else {
                let room = match rng.below(4) {
                    0 => 0,
                    1 => size.saturating_sub(1 + rng.below(size.max(1))),
                    _ => size + rng.below(3) * 8,
                };
                let mut bytes = vec![0; room];
                let status = instance.serialize_fmu_state_into(state, &mut bytes);
                if status == ok {
                    bytes.truncate(size);
                    made.keep(rng, bytes);
                } else if room >= size {
                    return Err(format!(
                        "call {call}: {function} refused a buffer of {room} >= {size} bytes: {}",
                        instance.last_message()
                    ));
                }
                status
            }
        }
        StateOp::Deserialize | StateOp::DeserializeInto => {
            let (bytes, note) = mutate(rng, &made.blobs);
            description = format!("({} bytes{note})", bytes.len());
            if verbose {
                print_serialized(&bytes);
            }
            if let StateOp::Deserialize = op {
                match instance.deserialize_fmu_state(&bytes) {
                    Ok(state) => {
                        made.states.push(state);
                        ok
                    }
                    Err(status) => status,
                }
            } else {
                let mut target = state;
                let status = instance.deserialize_fmu_state_into(&bytes, &mut target);
                made.states.push(target);
                status
            }
        }
    };
    Ok(Called {
        status,
        function,
        description,
    })
}

/// Prints serialized bytes for a rerun with FUZZ_ONLY: the 8-byte numbers of the body (laid out as
/// `mutate` says), then every byte.
fn print_serialized(bytes: &[u8]) {
    let guid_length = bytes
        .get(16..20)
        .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
    let numbers: Vec<f64> = bytes
        .get(20 + guid_length..bytes.len().saturating_sub(8))
        .unwrap_or(&[])
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    println!("     numbers {numbers:?}");
    println!(
        "     hex {}",
        bytes.iter().map(|b| format!("{b:02x}")).collect::<String>()
    );
}
