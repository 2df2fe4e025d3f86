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
//! sequence n alone and prints its calls (tests/fuzz_support).
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
use friction_fmu::variables::variable::{Causality, ModelTable, Variable};
use fuzz_support::checks;
use fuzz_support::fmu_states::{self, FmuStates, Made, StateOp};
use fuzz_support::rng::Rng;
use fuzz_support::sequence::{self, Calls, Experiment};
use fuzz_support::serialized::fnv1a;
use fuzz_support::values::{integer_value, real_value, step_size, value_references};

mod fuzz_support;

/// The C name of each operation, for the "names the function" check.
#[derive(Clone, Copy, Debug)]
enum Op {
    /// fmi2SetupExperiment with valid arguments, to get past Instantiated more often.
    SetupExperimentValid,
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
    /// An FMU-state call (tests/fuzz_support/fmu_states.rs).
    State(StateOp),
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

/// The random calls, each as often as it stands here (the FMU-state calls as in fuzz_support).
fn random_ops() -> Vec<Op> {
    let mut ops = vec![
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
    ];
    ops.extend(fmu_states::RANDOM.map(Op::State));
    ops.extend([
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
    ]);
    ops
}

impl Op {
    fn function(self) -> &'static str {
        match self {
            Op::SetupExperiment | Op::SetupExperimentValid => "fmi2SetupExperiment",
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
            Op::State(op) => <ImportedInstance as FmuStates>::function(op),
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
    let mut rng = sequence::rng_of(seed, index);
    let (_, mut slots) = sequence::first_two(&mut rng, instantiate)?;
    let mut made = Made::new();
    let calls = Calls::new(
        &mut rng,
        slots.len(),
        |rng| rng.pick(&[Op::SetReal, Op::SetInteger]),
        &[
            Op::SetupExperimentValid,
            Op::EnterInitialization,
            Op::ExitInitialization,
        ],
        Op::State(StateOp::SeedBytes),
    );
    let ops = random_ops();
    for call in 0..calls.count {
        let (k, op) = calls.get(call, &mut rng, slots.len(), &ops);
        if let Op::Reinstantiate = op {
            let freed = |s: &Slot| s.instance.is_freed();
            sequence::reinstantiate(&mut rng, &mut slots, k, freed, instantiate)?;
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
        let state = rng.pick(&made.states);
        let live = !slot.instance.is_freed();
        let mut function = op.function();
        let mut description = String::new();
        let status: Option<Status> = match op {
            Op::SetupExperimentValid | Op::SetupExperiment => {
                let experiment = match op {
                    Op::SetupExperimentValid => Experiment::valid(&mut rng, table),
                    _ => Experiment::random(&mut rng, table),
                };
                description = experiment.describe();
                let Experiment {
                    tolerance,
                    start,
                    stop,
                } = experiment;
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
                checks::finite_when_ok(call, function, &description, status, &values)?;
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
                let t = sequence::communication_point(&mut rng, slot.time, h);
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
            Op::State(op) => {
                let called = fmu_states::call(
                    op,
                    &mut slot.instance,
                    &mut rng,
                    state,
                    &mut made,
                    call,
                    verbose,
                )?;
                function = called.function;
                description = called.description;
                Some(called.status)
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
                let categories = sequence::debug_categories(&mut rng);
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
        // Every instance of this fuzzer has a logger.
        checks::status_kept_its_promises(
            call,
            function,
            &description,
            status,
            live,
            true,
            &messages,
        )?;
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

#[test]
fn random_call_sequences_never_crash_panic_or_lie() {
    fuzz_support::runner::run(sequence, 100_000);
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
