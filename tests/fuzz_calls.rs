//! Random FMI call sequences, in-process through the exported `fmi2*` functions (via the safe
//! driver), over every model: the FMU must survive every one.
//!
//! Each sequence instantiates one or two instances (sometimes with wrong arguments) and makes up
//! to 60 calls: any exported function in any state, value references known and unknown, values
//! NaN/inf/huge/negative/subnormal, steps 0/negative/NaN/1e-300/1e-12/1 s, communication points
//! off the instance's time, FMU states of the other instance or freed, serialized bytes truncated,
//! bit-flipped, from another model, or corrupted and re-checksummed (so only the FMU's structural
//! checks stand between them and the instance), NULL arguments, calls after free, double free.
//!
//! Checked after every call: no panic (caught or not: a panic hook counts them), the status is
//! an fmi2Status (0..=4, never Pending), a getReal that returns OK returns finite values, a call
//! on a freed instance is an error, and every non-OK status of a live instance comes with a
//! logged message that names the function.
//!
//! A deterministic PRNG (splitmix64) makes every sequence reproducible:
//! `FUZZ_SEED` (default 0x5EED), `FUZZ_SEQUENCES` (default 100 000), `FUZZ_ONLY=<n>` reruns
//! sequence n alone and prints its calls.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status;
use friction_fmu::importer::{
    calls_on_null_component, free_null_instance, types_platform, version, ImportedInstance,
    Instantiation, NullArgument, State,
};
use friction_fmu::models::MODELS;
use friction_fmu::variables::values::check_value;
use friction_fmu::variables::variable::{Causality, Kind, ModelTable, Variable};
use std::io::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

struct Rng(u64);

impl Rng {
    /// splitmix64: tiny, fast, and good enough to spread choices evenly.
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }
}

/// The longest step the fuzzer takes, in default steps of the model.
///
/// Parameters such as a vibration frequency of 1e12 Hz or a velocity of 1e12 m/s are accepted
/// and ask for millions of integration steps: the FMU stops such a doStep at its work limit
/// (src/solve/mod.rs) with fmi2Discard, after about a second (tests/python/test_work_limit.py).
/// A second per call is too slow for 1e5 sequences, and the fuzzer hunts crashes, not slow
/// steps, so it keeps steps and accepted parameter values near the defaults (see `tame`).
const MAX_STEPS_PER_CALL: f64 = 20.0;

/// A value the FMU accepts for `var` is replaced by one within 10x of the variable's nominal
/// value (its start, or 1 if that is 0), keeping the sign; values the FMU refuses (NaN, inf,
/// out of range, not an item) are kept, as refusing them is what is being tested.
fn tame(rng: &mut Rng, table: &ModelTable, var: &Variable, value: f64) -> f64 {
    if check_value(table, var, value).is_err() || value == 0.0 {
        return value;
    }
    let start = match var.kind {
        Kind::Real { start, .. } => start,
        Kind::Integer { start, .. } => f64::from(start),
        Kind::Switch { .. } => return value,
    };
    let nominal = if start == 0.0 { 1.0 } else { start.abs() };
    let tamed = value.signum() * nominal * 10f64.powf(rng.unit() * 2.0 - 1.0);
    let tamed = match var.kind {
        Kind::Integer { .. } => tamed.round(),
        _ => tamed,
    };
    // Still inside the range (e.g. a tolerance whose maximum is near its default).
    if check_value(table, var, tamed).is_ok() {
        tamed
    } else {
        start
    }
}

const SPECIAL: &[f64] = &[
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    -1.0,
    1.0,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    1e-300,
    f64::MIN_POSITIVE,
    5e-324,
    1e-12,
];

fn real_value(rng: &mut Rng, table: &ModelTable, var: Option<&Variable>) -> f64 {
    let Some(var) = var else {
        return rng.pick(SPECIAL);
    };
    let (start, min, max) = match var.kind {
        Kind::Real {
            start, min, max, ..
        } => (start, min, max),
        _ => (0.0, f64::NEG_INFINITY, f64::INFINITY),
    };
    let nominal = if start == 0.0 { 1.0 } else { start };
    let value = match rng.below(6) {
        0 | 1 => rng.pick(SPECIAL),
        2 => min,
        3 => max,
        4 => start,
        _ => nominal * (rng.unit() * 4.0 - 1.0),
    };
    tame(rng, table, var, value)
}

fn integer_value(rng: &mut Rng, table: &ModelTable, var: Option<&Variable>) -> i32 {
    let special = [0, -1, 1, 2, 3, 4, 7, i32::MIN, i32::MAX];
    let Some(var) = var else {
        return rng.pick(&special);
    };
    let value = match var.kind {
        Kind::Integer { start, min, max } => match rng.below(4) {
            0 => rng.pick(&special),
            1 => min,
            2 => max,
            _ => start,
        },
        Kind::Switch { type_name, start } => {
            let items = table.enum_type(type_name).map_or(0, |e| e.items.len()) as i32;
            match rng.below(4) {
                0 => rng.pick(&special),
                1 => items + 1,
                2 => start,
                _ => 1 + rng.below(items.max(1) as usize) as i32,
            }
        }
        Kind::Real { .. } => rng.pick(&special),
    };
    tame(rng, table, var, f64::from(value)) as i32
}

/// Value references: mostly the model's own, sometimes unknown ones.
fn value_references(rng: &mut Rng, table: &ModelTable) -> Vec<u32> {
    let n = rng.pick(&[0, 1, 1, 1, 2, 3, 5]);
    (0..n)
        .map(|_| {
            if rng.chance(85) {
                table.variables[rng.below(table.variables.len())].value_reference
            } else {
                let random = rng.next() as u32;
                rng.pick(&[0, 5, 9, 99, 1000, u32::MAX, random])
            }
        })
        .collect()
}

fn step_size(rng: &mut Rng, table: &ModelTable) -> f64 {
    let h = table.default_experiment.step_size;
    let step = rng.pick(&[
        0.0,
        -0.0,
        -h,
        -1.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e-300,
        1e-12,
        1.0,
        h,
        h,
        h,
        h * 0.37,
        // Far shorter than the solvers' steps: TransverseFriction reads steps taken ahead.
        h * 0.1,
        h * 3.0,
    ]);
    if step.is_finite() && step > MAX_STEPS_PER_CALL * h {
        MAX_STEPS_PER_CALL * h
    } else {
        step
    }
}

/// The FMU's checksum of serialized states (FNV-1a 64), recomputed so that corrupted bytes get
/// past it and reach the structural checks behind it.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn mutate(rng: &mut Rng, pool: &[Vec<u8>]) -> (Vec<u8>, String) {
    let mut note = String::new();
    let mut bytes = if pool.is_empty() || rng.chance(5) {
        (0..rng.below(200)).map(|_| rng.next() as u8).collect()
    } else {
        pool[rng.below(pool.len())].clone()
    };
    match rng.below(8) {
        0 | 1 => {}
        2 => bytes.truncate(rng.below(bytes.len() + 1)),
        3 => {
            if !bytes.is_empty() {
                let i = rng.below(bytes.len());
                bytes[i] ^= 1 << rng.below(8);
            }
        }
        4 => bytes.extend((0..rng.below(16)).map(|_| rng.next() as u8)),
        _ => {
            // Overwrite an 8-byte number in the body with a special value, then fix the checksum.
            // One whole number: the serialized state is the magic word, its length, the GUID's
            // length and text, then 8-byte numbers, then the checksum.
            let guid_length = bytes
                .get(16..20)
                .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
            let first = 20 + guid_length;
            if bytes.len() >= first + 16 {
                let body = bytes.len() - 8;
                let at = first + 8 * rng.below((body - first) / 8);
                // Values the FMU must refuse, or harmless ones: an accepted 1e12 Hz or a
                // 1e-300 kg would make the next doStep endless (see MAX_STEPS_PER_CALL).
                let value = rng.pick(&[
                    f64::NAN,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    -1.0,
                    0.0,
                    -0.0,
                    1.0,
                    2.0,
                    3.5,
                    6.0,
                ]);
                bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
                note = format!(", {value} at byte {at}, checksum fixed");
                let sum = fnv1a(&bytes[..body]);
                bytes[body..].copy_from_slice(&sum.to_le_bytes());
            }
        }
    }
    (bytes, note)
}

/// The C name of each operation, for the "names the function" check.
#[derive(Clone, Copy, Debug)]
enum Op {
    /// fmi2SetupExperiment with valid arguments, to get past Instantiated more often.
    SetupExperimentValid,
    /// fmi2GetFMUstate, serialize it into the pool of bytes to corrupt, free it.
    SeedBytes,
    SetupExperiment,
    EnterInitialization,
    ExitInitialization,
    Terminate,
    Reset,
    SetReal,
    SetInteger,
    SetBoolean,
    SetString,
    GetReal,
    GetInteger,
    GetBoolean,
    GetString,
    DoStep,
    CancelStep,
    GetStatus,
    GetRealStatus,
    GetIntegerStatus,
    GetBooleanStatus,
    GetStringStatus,
    GetFmuState,
    UpdateFmuState,
    SetFmuState,
    FreeFmuState,
    SerializedSize,
    Serialize,
    Deserialize,
    DeserializeInto,
    DirectionalDerivative,
    InputDerivatives,
    OutputDerivatives,
    DebugLogging,
    Null,
    Free,
    FreeTwice,
    /// fmi2FreeInstance, then go on calling with the freed handle while other instances are made.
    FreeKeepingHandle,
    Reinstantiate,
}

const OPS: &[Op] = &[
    Op::SetupExperiment,
    Op::EnterInitialization,
    Op::ExitInitialization,
    Op::Terminate,
    Op::Reset,
    Op::SetReal,
    Op::SetReal,
    Op::SetReal,
    Op::SetInteger,
    Op::SetInteger,
    Op::SetBoolean,
    Op::SetString,
    Op::GetReal,
    Op::GetReal,
    Op::GetReal,
    Op::GetInteger,
    Op::GetBoolean,
    Op::GetString,
    Op::DoStep,
    Op::DoStep,
    Op::DoStep,
    Op::DoStep,
    Op::DoStep,
    Op::CancelStep,
    Op::GetStatus,
    Op::GetRealStatus,
    Op::GetIntegerStatus,
    Op::GetBooleanStatus,
    Op::GetStringStatus,
    Op::GetFmuState,
    Op::GetFmuState,
    Op::UpdateFmuState,
    Op::SetFmuState,
    Op::SetFmuState,
    Op::FreeFmuState,
    Op::SerializedSize,
    Op::Serialize,
    Op::Serialize,
    Op::Deserialize,
    Op::Deserialize,
    Op::DeserializeInto,
    Op::DirectionalDerivative,
    Op::InputDerivatives,
    Op::OutputDerivatives,
    Op::DebugLogging,
    Op::Null,
    Op::Free,
    Op::FreeTwice,
    Op::FreeKeepingHandle,
    Op::Reinstantiate,
    Op::Reinstantiate,
];

impl Op {
    fn function(self) -> &'static str {
        match self {
            Op::SetupExperiment | Op::SetupExperimentValid => "fmi2SetupExperiment",
            Op::SeedBytes => "fmi2GetFMUstate",
            Op::EnterInitialization => "fmi2EnterInitializationMode",
            Op::ExitInitialization => "fmi2ExitInitializationMode",
            Op::Terminate => "fmi2Terminate",
            Op::Reset => "fmi2Reset",
            Op::SetReal => "fmi2SetReal",
            Op::SetInteger => "fmi2SetInteger",
            Op::SetBoolean => "fmi2SetBoolean",
            Op::SetString => "fmi2SetString",
            Op::GetReal => "fmi2GetReal",
            Op::GetInteger => "fmi2GetInteger",
            Op::GetBoolean => "fmi2GetBoolean",
            Op::GetString => "fmi2GetString",
            Op::DoStep => "fmi2DoStep",
            Op::CancelStep => "fmi2CancelStep",
            Op::GetStatus => "fmi2GetStatus",
            Op::GetRealStatus => "fmi2GetRealStatus",
            Op::GetIntegerStatus => "fmi2GetIntegerStatus",
            Op::GetBooleanStatus => "fmi2GetBooleanStatus",
            Op::GetStringStatus => "fmi2GetStringStatus",
            Op::GetFmuState | Op::UpdateFmuState => "fmi2GetFMUstate",
            Op::SetFmuState => "fmi2SetFMUstate",
            Op::FreeFmuState => "fmi2FreeFMUstate",
            Op::SerializedSize => "fmi2SerializedFMUstateSize",
            Op::Serialize => "fmi2SerializeFMUstate",
            Op::Deserialize | Op::DeserializeInto => "fmi2DeSerializeFMUstate",
            Op::DirectionalDerivative => "fmi2GetDirectionalDerivative",
            Op::InputDerivatives => "fmi2SetRealInputDerivatives",
            Op::OutputDerivatives => "fmi2GetRealOutputDerivatives",
            Op::DebugLogging => "fmi2SetDebugLogging",
            Op::Null => "",
            Op::Free | Op::FreeTwice | Op::FreeKeepingHandle => "fmi2FreeInstance",
            Op::Reinstantiate => "fmi2Instantiate",
        }
    }
}

const NULL_ARGUMENTS: usize = 13;

fn null_argument(rng: &mut Rng, state: State) -> (NullArgument, &'static str) {
    use NullArgument::*;
    match rng.below(NULL_ARGUMENTS) {
        0 => (GetRealValues, "fmi2GetReal"),
        1 => (SetRealValues, "fmi2SetReal"),
        2 => (GetRealReferences, "fmi2GetReal"),
        3 => (DebugLoggingCategories, "fmi2SetDebugLogging"),
        4 => (GetFmuStateSlot, "fmi2GetFMUstate"),
        5 => (FreeFmuStateSlot, "fmi2FreeFMUstate"),
        6 => (SerializedSizeOut(state), "fmi2SerializedFMUstateSize"),
        7 => (SerializeBuffer(state), "fmi2SerializeFMUstate"),
        8 => (DeserializeBytes, "fmi2DeSerializeFMUstate"),
        9 => (DeserializeSlot, "fmi2DeSerializeFMUstate"),
        10 => (GetStatusValue, "fmi2GetStatus"),
        11 => (GetRealStatusValue, "fmi2GetRealStatus"),
        _ => (GetBooleanStatusValue, "fmi2GetBooleanStatus"),
    }
}

struct Slot {
    instance: ImportedInstance,
    table: &'static ModelTable,
    /// The time the fuzzer believes the instance is at (its own bookkeeping, not the FMU's).
    time: f64,
}

fn instantiate(rng: &mut Rng, table: &'static ModelTable, name: &str) -> Result<Slot, String> {
    let mut arguments =
        Instantiation::new(table.model_identifier, name).ok_or("model has no GUID")?;
    arguments.logging_on = rng.chance(20);
    if rng.chance(10) {
        match rng.below(6) {
            0 => arguments.instance_name = None,
            1 => arguments.instance_name = Some(String::new()),
            2 => arguments.fmu_type = rng.pick(&[0, 2, -1, i32::MAX]),
            3 => arguments.guid = None,
            4 => arguments.guid = Some("{not-a-guid}".into()),
            _ => arguments.resource_location = Some("http://example.com/resources".into()),
        }
        let expect_refusal = arguments.instance_name.as_deref() != Some(name)
            || arguments.fmu_type != 1
            || arguments.guid.as_deref() != friction_fmu::fmi2::guid(table.model_identifier)
            || arguments.resource_location.is_some();
        return match ImportedInstance::instantiate(&arguments) {
            Ok(_) if expect_refusal => Err(format!("instantiated with {arguments:?}")),
            Ok(instance) => Ok(Slot {
                instance,
                table,
                time: 0.0,
            }),
            Err(log) if log.iter().any(|m| m.text.contains("fmi2Instantiate")) => {
                Err(String::new())
            }
            Err(log) => Err(format!("refused {arguments:?} without a message: {log:?}")),
        };
    }
    ImportedInstance::instantiate(&arguments)
        .map(|instance| Slot {
            instance,
            table,
            time: 0.0,
        })
        .map_err(|log| format!("instantiate {}: {log:?}", table.model_identifier))
}

/// Runs sequence `index`; the error describes the first broken promise.
fn sequence(seed: u64, index: u64, verbose: bool) -> Result<(), String> {
    // Serialized states made in this sequence, raw material for corrupted ones.
    let mut blobs: Vec<Vec<u8>> = Vec::new();
    let blobs = &mut blobs;
    let mut rng = Rng(seed ^ index.wrapping_mul(0xD6E8_FEB8_6659_FD93));
    let first = MODELS[rng.below(MODELS.len())].table;
    let second = if rng.chance(70) {
        first
    } else {
        MODELS[rng.below(MODELS.len())].table
    };
    let mut slots: Vec<Option<Slot>> = Vec::new();
    for (k, table) in [first, second].into_iter().enumerate() {
        match instantiate(&mut rng, table, &format!("fuzz{k}")) {
            Ok(slot) => slots.push(Some(slot)),
            Err(e) if e.is_empty() => slots.push(None),
            Err(e) => return Err(e),
        }
    }
    let mut states: Vec<State> = vec![State::NULL];
    // Most sequences first bring their instances to StepComplete (with some parameters set on
    // the way), so that the random calls after that reach the stepping phases often.
    let mut plan = Vec::new();
    for k in 0..slots.len() {
        if rng.chance(75) {
            plan.extend((0..rng.below(4)).map(|_| (k, rng.pick(&[Op::SetReal, Op::SetInteger]))));
            plan.extend([
                (k, Op::SetupExperimentValid),
                (k, Op::EnterInitialization),
                (k, Op::ExitInitialization),
            ]);
        }
        if rng.chance(50) {
            plan.push((k, Op::SeedBytes));
        }
    }
    let calls = plan.len() + 1 + rng.below(60);
    for call in 0..calls {
        let (k, op) = match plan.get(call) {
            Some(&planned) => planned,
            None => (rng.below(slots.len()), rng.pick(OPS)),
        };
        if let Op::Reinstantiate = op {
            let table = MODELS[rng.below(MODELS.len())].table;
            // A slot whose instance was freed keeps its handle beside the new instance (which
            // may take the freed memory), so later calls test that the handle stays dead.
            let keep = slots[k].as_ref().is_some_and(|s| s.instance.is_freed()) && slots.len() < 4;
            match instantiate(&mut rng, table, "again") {
                Ok(slot) if keep => slots.push(Some(slot)),
                Ok(slot) => slots[k] = Some(slot),
                Err(e) if e.is_empty() => {}
                Err(e) => return Err(e),
            }
            continue;
        }
        let Some(slot) = slots[k].as_mut() else {
            continue;
        };
        let table = slot.table;
        if verbose {
            // Before the call too, so a hanging call shows which it is.
            println!("{call:3}: [{k}] {op:?} ...");
        }
        let state = rng.pick(&states);
        let live = !slot.instance.is_freed();
        let mut function = op.function();
        let mut description = String::new();
        let status: Option<Status> = match op {
            Op::SetupExperimentValid => {
                let stop = rng.chance(50).then_some(table.default_experiment.stop_time);
                description = format!("(None, 0, {stop:?})");
                let status = slot.instance.setup_experiment(None, 0.0, stop);
                if status == Status::Ok {
                    slot.time = 0.0;
                }
                Some(status)
            }
            Op::SeedBytes => match slot.instance.get_fmu_state() {
                Ok(mut state) => {
                    let bytes = slot.instance.serialize_fmu_state(state);
                    blobs.extend(bytes);
                    Some(slot.instance.free_fmu_state(&mut state))
                }
                Err(status) => Some(status),
            },
            Op::SetupExperiment => {
                let tolerance = rng.chance(50).then(|| rng.pick(SPECIAL).abs());
                let start = if rng.chance(70) {
                    0.0
                } else {
                    rng.pick(SPECIAL)
                };
                let stop = rng.chance(40).then(|| {
                    if rng.chance(70) {
                        start + table.default_experiment.stop_time
                    } else {
                        rng.pick(SPECIAL)
                    }
                });
                description = format!("({tolerance:?}, {start}, {stop:?})");
                let status = slot.instance.setup_experiment(tolerance, start, stop);
                if status == Status::Ok {
                    slot.time = start;
                }
                Some(status)
            }
            Op::EnterInitialization => Some(slot.instance.enter_initialization_mode()),
            Op::ExitInitialization => Some(slot.instance.exit_initialization_mode()),
            Op::Terminate => Some(slot.instance.terminate()),
            Op::Reset => {
                slot.time = 0.0;
                Some(slot.instance.reset())
            }
            Op::SetReal | Op::SetInteger | Op::SetBoolean | Op::SetString => {
                let vrs = value_references(&mut rng, table);
                let vars: Vec<Option<&Variable>> =
                    vrs.iter().map(|&vr| table.variable(vr)).collect();
                match op {
                    Op::SetReal => {
                        let values: Vec<f64> = vars
                            .iter()
                            .map(|v| real_value(&mut rng, table, *v))
                            .collect();
                        description = format!("({vrs:?}, {values:?})");
                        Some(slot.instance.set_real(&vrs, &values))
                    }
                    Op::SetInteger => {
                        let values: Vec<i32> = vars
                            .iter()
                            .map(|v| integer_value(&mut rng, table, *v))
                            .collect();
                        description = format!("({vrs:?}, {values:?})");
                        Some(slot.instance.set_integer(&vrs, &values))
                    }
                    Op::SetBoolean => {
                        let values: Vec<bool> = vrs.iter().map(|_| rng.chance(50)).collect();
                        Some(slot.instance.set_boolean(&vrs, &values))
                    }
                    _ => {
                        let values: Vec<&str> =
                            vrs.iter().map(|_| rng.pick(&["", "x", "%s%n%p"])).collect();
                        Some(slot.instance.set_string(&vrs, &values))
                    }
                }
            }
            Op::GetReal => {
                let vrs = value_references(&mut rng, table);
                let (status, values) = slot.instance.get_real(&vrs);
                description = format!("({vrs:?}) = {values:?}");
                if status == Status::Ok && values.iter().any(|x| !x.is_finite()) {
                    return Err(format!(
                        "call {call}: fmi2GetReal{description} returned OK with a non-finite value"
                    ));
                }
                Some(status)
            }
            Op::GetInteger => {
                let vrs = value_references(&mut rng, table);
                Some(slot.instance.get_integer(&vrs).0)
            }
            Op::GetBoolean => {
                let vrs = value_references(&mut rng, table);
                Some(slot.instance.get_boolean(&vrs).0)
            }
            Op::GetString => {
                let vrs = value_references(&mut rng, table);
                Some(slot.instance.get_string(&vrs))
            }
            Op::DoStep => {
                let h = step_size(&mut rng, table);
                let t = if rng.chance(85) {
                    slot.time
                } else {
                    rng.pick(&[
                        slot.time + 1e-3,
                        slot.time - h,
                        f64::NAN,
                        f64::INFINITY,
                        0.0,
                        -1.0,
                        slot.time * (1.0 + 1e-15),
                    ])
                };
                description = format!("(t = {t}, h = {h})");
                if verbose {
                    println!("     {description}");
                }
                let status = slot.instance.do_step(t, h, rng.chance(50));
                if status == Status::Ok {
                    slot.time = t + h;
                }
                Some(status)
            }
            Op::CancelStep => Some(slot.instance.cancel_step()),
            Op::GetStatus => Some(slot.instance.get_status(rng.pick(&[0, 1, 2, 3, -1, 99])).0),
            Op::GetRealStatus => {
                let (status, time) = slot
                    .instance
                    .get_real_status(rng.pick(&[2, 2, 0, 1, 3, 77]));
                if status == Status::Ok && time.is_finite() {
                    // A restored FMU state may have moved the instance's time.
                    slot.time = time;
                }
                Some(status)
            }
            Op::GetIntegerStatus => {
                Some(slot.instance.get_integer_status(rng.pick(&[0, 1, 2, 3])).0)
            }
            Op::GetBooleanStatus => {
                Some(slot.instance.get_boolean_status(rng.pick(&[3, 3, 0, -5])).0)
            }
            Op::GetStringStatus => Some(slot.instance.get_string_status(rng.pick(&[1, 0, 4]))),
            Op::GetFmuState => match slot.instance.get_fmu_state() {
                Ok(state) => {
                    states.push(state);
                    Some(Status::Ok)
                }
                Err(status) => Some(status),
            },
            Op::UpdateFmuState => {
                let mut target = state;
                description = format!("({:#x})", state.address());
                let status = slot.instance.update_fmu_state(&mut target);
                states.push(target);
                Some(status)
            }
            Op::SetFmuState => {
                description = format!("({:#x})", state.address());
                let status = slot.instance.set_fmu_state(state);
                Some(status)
            }
            Op::FreeFmuState => {
                let mut target = state;
                description = format!("({:#x})", state.address());
                Some(slot.instance.free_fmu_state(&mut target))
            }
            Op::SerializedSize => Some(slot.instance.serialized_fmu_state_size(state).0),
            Op::Serialize => {
                let (status, size) = slot.instance.serialized_fmu_state_size(state);
                if status != Status::Ok {
                    function = "fmi2SerializedFMUstateSize";
                    Some(status)
                } else {
                    let room = match rng.below(4) {
                        0 => 0,
                        1 => size.saturating_sub(1 + rng.below(size.max(1))),
                        _ => size + rng.below(3) * 8,
                    };
                    let mut bytes = vec![0; room];
                    let status = slot.instance.serialize_fmu_state_into(state, &mut bytes);
                    if status == Status::Ok {
                        bytes.truncate(size);
                        if blobs.len() < 64 {
                            blobs.push(bytes);
                        } else {
                            let i = rng.below(blobs.len());
                            blobs[i] = bytes;
                        }
                    } else if room >= size {
                        return Err(format!(
                            "call {call}: fmi2SerializeFMUstate refused a buffer of {room} >= {size} bytes: {}",
                            slot.instance.last_message()
                        ));
                    }
                    Some(status)
                }
            }
            Op::Deserialize | Op::DeserializeInto => {
                let (bytes, note) = mutate(&mut rng, blobs);
                description = format!("({} bytes{note})", bytes.len());
                if verbose && bytes.len() > 20 {
                    let start = 12
                        + u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize;
                    let numbers: Vec<f64> = bytes
                        .get(start..bytes.len() - 8)
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
                if let Op::Deserialize = op {
                    match slot.instance.deserialize_fmu_state(&bytes) {
                        Ok(state) => {
                            states.push(state);
                            Some(Status::Ok)
                        }
                        Err(status) => Some(status),
                    }
                } else {
                    let mut target = state;
                    let status = slot
                        .instance
                        .deserialize_fmu_state_into(&bytes, &mut target);
                    states.push(target);
                    Some(status)
                }
            }
            Op::DirectionalDerivative => {
                let unknowns = value_references(&mut rng, table);
                let knowns = value_references(&mut rng, table);
                let seed = vec![1.0; knowns.len()];
                Some(
                    slot.instance
                        .get_directional_derivative(&unknowns, &knowns, &seed)
                        .0,
                )
            }
            Op::InputDerivatives => {
                let vrs = value_references(&mut rng, table);
                let orders = vec![1; vrs.len()];
                let values = vec![0.5; vrs.len()];
                Some(
                    slot.instance
                        .set_real_input_derivatives(&vrs, &orders, &values),
                )
            }
            Op::OutputDerivatives => {
                let vrs = value_references(&mut rng, table);
                let orders = vec![1; vrs.len()];
                Some(slot.instance.get_real_output_derivatives(&vrs, &orders))
            }
            Op::DebugLogging => {
                let n = rng.below(3);
                let categories: Vec<&str> = (0..n)
                    .map(|_| {
                        rng.pick(&["logCalls", "logStatusError", "logStatusWarning", "nope", ""])
                    })
                    .collect();
                Some(slot.instance.set_debug_logging(rng.chance(50), &categories))
            }
            Op::Null => {
                let (which, name) = null_argument(&mut rng, state);
                function = name;
                description = format!("{which:?}");
                Some(slot.instance.call_with_null(which))
            }
            Op::Free => {
                slot.instance.free();
                None
            }
            Op::FreeTwice => {
                slot.instance.free_twice();
                None
            }
            Op::FreeKeepingHandle => {
                slot.instance.free_keeping_the_handle();
                None
            }
            Op::Reinstantiate => unreachable!("handled above"),
        };
        let messages = slot.instance.take_messages();
        if verbose {
            println!("{call:3}: [{k}] {function}{description} -> {status:?} {messages:?}");
        }
        let Some(status) = status else { continue };
        if status == Status::Pending {
            return Err(format!(
                "call {call}: {function}{description} returned fmi2Pending"
            ));
        }
        if !live {
            if status != Status::Error || !messages.is_empty() {
                return Err(format!(
                    "call {call}: {function} on a freed instance gave {status:?} {messages:?}"
                ));
            }
        } else if status != Status::Ok
            && !messages
                .iter()
                .any(|m| m.status >= Status::Warning as i32 && m.text.contains(function))
        {
            return Err(format!(
                "call {call}: {function}{description} returned {status:?} without a message naming it: {messages:?}"
            ));
        }
    }
    if rng.chance(1) {
        free_null_instance();
        for (name, status) in calls_on_null_component() {
            if status != Status::Error {
                return Err(format!("{name}(NULL) returned {status:?}"));
            }
        }
    }
    Ok(())
}

static PANICS: AtomicUsize = AtomicUsize::new(0);
static PANIC_MESSAGES: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Counts every panic, also those the FMU catches at its C boundary (still a bug there).
fn count_panics() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.fetch_add(1, Ordering::SeqCst);
            let mut messages = PANIC_MESSAGES.lock().unwrap_or_else(|e| e.into_inner());
            if messages.len() < 5 {
                messages.push(info.to_string());
            }
            default(info);
        }));
    });
}

fn env_number(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(text) => {
            let text = text.trim();
            let parsed = match text.strip_prefix("0x") {
                Some(hex) => u64::from_str_radix(hex, 16),
                None => text.parse(),
            };
            parsed.unwrap_or_else(|_| panic!("{name}={text}: expected a number"))
        }
        Err(_) => default,
    }
}

/// A sequence that has not finished after this long is reported as hung, and the process ends
/// (a hung FMU call cannot be interrupted, and a stalled CI job says nothing).
const HANG_SECONDS: u64 = 60;

/// Runs `count` sequences from `seed` on every core; returns the failures (sequence, message).
fn fuzz(seed: u64, count: u64) -> Vec<(u64, String)> {
    count_panics();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let failures = Mutex::new(Vec::new());
    // Per thread: the sequence it runs and when it started it (seconds since `started`).
    let running: Vec<(AtomicU64, AtomicU64)> = (0..threads)
        .map(|_| (AtomicU64::new(u64::MAX), AtomicU64::new(0)))
        .collect();
    let done = AtomicBool::new(false);
    let started = Instant::now();
    std::thread::scope(|scope| {
        let (running, done) = (&running, &done);
        scope.spawn(move || {
            while !done.load(Ordering::SeqCst) {
                std::thread::sleep(Duration::from_millis(200));
                let now = started.elapsed().as_secs();
                for (index, since) in running {
                    let index = index.load(Ordering::SeqCst);
                    if index != u64::MAX && now > since.load(Ordering::SeqCst) + HANG_SECONDS {
                        // Straight to stderr: the test harness captures eprintln!.
                        let _ = writeln!(
                            std::io::stderr(),
                            "fuzz: sequence {index} has run for over {HANG_SECONDS} s: a hung call \
                             (rerun it with FUZZ_SEED={seed:#x} FUZZ_ONLY={index} -- --nocapture)"
                        );
                        std::process::exit(101);
                    }
                }
            }
        });
        let workers: Vec<_> = (0..threads)
            .map(|thread| {
                let failures = &failures;
                let (slot_index, slot_since) = &running[thread as usize];
                scope.spawn(move || {
                    let mut index = thread;
                    while index < count {
                        slot_since.store(started.elapsed().as_secs(), Ordering::SeqCst);
                        slot_index.store(index, Ordering::SeqCst);
                        let outcome =
                            catch_unwind(AssertUnwindSafe(|| sequence(seed, index, false)));
                        slot_index.store(u64::MAX, Ordering::SeqCst);
                        let failure = match outcome {
                            Ok(Ok(())) => None,
                            Ok(Err(message)) => Some(message),
                            Err(_) => Some("panicked (see the panic message above)".to_string()),
                        };
                        if let Some(message) = failure {
                            let mut failures = failures.lock().unwrap_or_else(|e| e.into_inner());
                            failures.push((index, message));
                            if failures.len() >= 10 {
                                return;
                            }
                        }
                        index += threads;
                    }
                })
            })
            .collect();
        for worker in workers {
            let _ = worker.join();
        }
        done.store(true, Ordering::SeqCst);
    });
    failures.into_inner().unwrap_or_else(|e| e.into_inner())
}

#[test]
fn random_call_sequences_never_crash_panic_or_lie() {
    let seed = env_number("FUZZ_SEED", 0x5EED);
    if let Ok(only) = std::env::var("FUZZ_ONLY") {
        let index = env_number("FUZZ_ONLY", 0);
        println!("FUZZ_ONLY={only}");
        let result = sequence(seed, index, true);
        assert_eq!(result, Ok(()));
        return;
    }
    let count = env_number("FUZZ_SEQUENCES", 100_000);
    let started = Instant::now();
    let mut failures = fuzz(seed, count);
    failures.sort();
    println!(
        "{count} sequences (seed {seed:#x}) in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let panics = PANICS.load(Ordering::SeqCst);
    let panic_messages = PANIC_MESSAGES.lock().map(|m| m.clone()).unwrap_or_default();
    assert!(
        failures.is_empty() && panics == 0,
        "{} failing sequences (rerun one with FUZZ_SEED={seed:#x} FUZZ_ONLY=<n> -- --nocapture), \
         {panics} panics {panic_messages:?}:\n{}",
        failures.len(),
        failures
            .iter()
            .map(|(i, m)| format!("  sequence {i}: {m}"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn version_and_platform() {
    assert_eq!(version(), "2.0");
    assert_eq!(types_platform(), "default");
}

// --- regressions: what the fuzzer found, each reduced to its cause ---

fn outputs(table: &ModelTable) -> Vec<u32> {
    table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| v.value_reference)
        .collect()
}

/// A serialized state with number `index` (0 = phase, 1 = start time, ..., 6.. = values) set to
/// `value` and the checksum made to match.
fn forge(bytes: &[u8], index: usize, value: f64) -> Vec<u8> {
    let mut bytes = bytes.to_vec();
    // Magic word (8), length (8), GUID length (4), GUID.
    let guid_length = u32::from_le_bytes([bytes[16], bytes[17], bytes[18], bytes[19]]) as usize;
    let at = 20 + guid_length + 8 * index;
    bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
    let body = bytes.len() - 8;
    let sum = fnv1a(&bytes[..body]);
    bytes[body..].copy_from_slice(&sum.to_le_bytes());
    bytes
}

fn initialized(table: &ModelTable) -> ImportedInstance {
    let mut instance =
        ImportedInstance::new(table.model_identifier, "regression").expect("instantiate");
    assert_eq!(instance.initialize(), Status::Ok);
    instance
}

/// Sequence 1198 (seed 0x5EED): at startTime = f64::MAX, LongitudinalFriction's vr and
/// TransverseFriction's FF are NaN, and fmi2GetReal returned them with fmi2OK.
#[test]
fn regression_get_real_refuses_outputs_that_are_not_finite() {
    for table in MODELS.iter().map(|m| m.table) {
        let mut instance = ImportedInstance::new(table.model_identifier, "regression").unwrap();
        assert_eq!(instance.setup_experiment(None, f64::MAX, None), Status::Ok);
        assert_eq!(instance.enter_initialization_mode(), Status::Ok);
        let (status, values) = instance.get_real(&outputs(table));
        match status {
            Status::Ok => assert!(values.iter().all(|x| x.is_finite()), "{values:?}"),
            _ => {
                assert_eq!(status, Status::Error);
                let message = instance.last_message();
                assert!(message.contains("fmi2GetReal") && message.contains("finite"));
            }
        }
    }
}

/// Sequence 9603 (seed 0x5EED): serialized bytes with a matching checksum and a start time of
/// -inf were loaded, and the next fmi2DoStep of DryFrictionOscillator never returned.
#[test]
fn regression_serialized_state_with_bad_times_is_refused() {
    for table in MODELS.iter().map(|m| m.table) {
        let mut instance = initialized(table);
        let mut state = instance.get_fmu_state().unwrap();
        let bytes = instance.serialize_fmu_state(state).unwrap();
        assert_eq!(instance.free_fmu_state(&mut state), Status::Ok);
        for (index, value) in [
            (1, f64::NEG_INFINITY),
            (1, f64::NAN),
            (3, f64::INFINITY),
            (3, -1.0),
        ] {
            let forged = forge(&bytes, index, value);
            assert_eq!(instance.deserialize_fmu_state(&forged), Err(Status::Error));
            let message = instance.last_message();
            assert!(
                message.contains("fmi2DeSerializeFMUstate") && message.contains("times"),
                "{message}"
            );
        }
        // The unforged bytes load: the refusals were about the times.
        let mut state = instance.deserialize_fmu_state(&bytes).unwrap();
        assert_eq!(instance.set_fmu_state(state), Status::Ok);
        assert_eq!(instance.free_fmu_state(&mut state), Status::Ok);
    }
}

/// Found with the re-checksummed corruption: a NaN parameter in serialized bytes reached the
/// simulation through fmi2SetFMUstate (and with it NaN outputs).
#[test]
fn regression_serialized_state_with_bad_values_is_refused() {
    for table in MODELS.iter().map(|m| m.table) {
        let mut instance = initialized(table);
        let mut state = instance.get_fmu_state().unwrap();
        let bytes = instance.serialize_fmu_state(state).unwrap();
        assert_eq!(instance.free_fmu_state(&mut state), Status::Ok);
        for (position, var) in table.variables.iter().enumerate() {
            if var.causality != Causality::Parameter {
                continue;
            }
            let mut forged = instance
                .deserialize_fmu_state(&forge(&bytes, 6 + position, f64::NAN))
                .expect("the bytes are well-formed; the value is checked on restore");
            assert_eq!(
                instance.set_fmu_state(forged),
                Status::Error,
                "{}",
                var.name
            );
            let message = instance.last_message();
            assert!(
                message.contains("fmi2SetFMUstate") && message.contains(var.name),
                "{message}"
            );
            assert_eq!(instance.free_fmu_state(&mut forged), Status::Ok);
        }
    }
}

/// A freed handle is refused and touches nothing, also when the next instance takes the freed
/// one's memory: fmi2DoStep, fmi2Reset and a second fmi2FreeInstance on it once advanced, reset
/// and ended the next instance.
#[test]
fn regression_a_freed_handle_never_reaches_the_next_instance() {
    let table = MODELS[MODELS.len() - 1].table;
    let step = table.default_experiment.step_size;
    let mut freed = initialized(table);
    freed.free_keeping_the_handle();
    let mut next = initialized(table);
    assert_eq!(freed.do_step(0.0, step, true), Status::Error);
    assert_eq!(freed.reset(), Status::Error);
    freed.free_keeping_the_handle();
    // The next instance is where it was, at t = 0, and alive.
    assert_eq!(next.do_step(0.0, step, true), Status::Ok);
    assert_eq!(next.do_step(step, step, true), Status::Ok);
}
