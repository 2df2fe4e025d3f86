//! Random FMI 3.0 call sequences, in-process through the exported `fmi3*` functions (via the
//! safe driver, src/importer/fmi3.rs), over every model: the FMU must survive every one.
//!
//! Each sequence instantiates one or two FMI 3.0 instances (sometimes with wrong arguments,
//! sometimes through fmi3InstantiateModelExchange or fmi3InstantiateScheduledExecution), often an
//! FMI 2.0 instance beside them, and makes up to 60 calls: every fmi3 function in any state, the
//! getters and setters of all 14 types with nValues right or wrong, value references known and
//! unknown, values NaN/inf/huge/negative/subnormal, steps 0/negative/NaN/1e-300/1 s,
//! communication points off the instance's time, FMU states of the other instance or freed,
//! serialized bytes truncated, bit-flipped, from another model or from the FMI 2.0 instance, or
//! corrupted and re-checksummed, NULL arguments, the functions of the modes these FMUs leave out,
//! calls after free, double free, every fmi3 function on freed, made-up and FMI 2.0 handles, and
//! every fmi2 function on a live FMI 3.0 handle.
//!
//! Checked after every call: no panic (a panic hook counts them, caught or not), the status is
//! an fmi3Status (0..=4), a getter or fmi3GetOutputDerivatives that returns OK returns finite
//! values, an OK fmi3DoStep ends where it was asked to and says so in lastSuccessfulTime, a call on
//! a freed instance is an error and logs nothing, a handle of the other standard or a freed one
//! is refused by every function and reaches no instance, and every non-OK status of a live
//! instance with a logger comes with a logged message that names the function.
//!
//! `FUZZ_SEED`, `FUZZ_SEQUENCES` (default 50 000) and `FUZZ_ONLY` as in tests/fuzz_support.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use friction_fmu::fmi2::ffi::Status as Status2;
use friction_fmu::fmi3::ffi::Status;
use friction_fmu::importer::fmi3::{
    calls_on_handle, free_foreign_handle, ImportedInstance, Instantiation, Interface, NullArgument,
    OnIntermediateUpdate, Unsupported, VALUE_TYPES,
};
use friction_fmu::importer::{self as fmi2, calls_on_component, free_foreign_component, State};
use friction_fmu::instance::calls::ValueType;
use friction_fmu::models::MODELS;
use friction_fmu::variables::variable::{Causality, Kind, ModelTable};
use fuzz_support::checks;
use fuzz_support::fmu_states::{self, FmuStates, Made, StateOp};
use fuzz_support::rng::Rng;
use fuzz_support::sequence::{self, Calls, Experiment};
use fuzz_support::values::{integer_value, real_value, step_size, value_references, SPECIAL};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

mod fmi3_description;
mod fuzz_support;

/// What one step of a sequence does.
#[derive(Clone, Copy, Debug)]
enum Op {
    /// fmi3EnterInitializationMode with valid arguments, to get past Instantiated more often.
    EnterInitializationValid,
    EnterInitialization,
    ExitInitialization,
    Terminate,
    Reset,
    Set(ValueType),
    Get(ValueType),
    DoStep,
    OutputDerivatives,
    /// An FMU-state call (tests/fuzz_support/fmu_states.rs).
    State(StateOp),
    Unsupported,
    DebugLogging,
    Null,
    /// fmi3FreeInstance; the handle is kept and used by later calls.
    Free,
    FreeTwice,
    Reinstantiate,
    /// Every fmi3 function on a handle that is no live FMI 3.0 instance.
    ForeignHandle,
    /// Every fmi2 function, and fmi2FreeInstance, on this live FMI 3.0 instance's handle.
    HandleToFmi2,
}

/// The random calls, each as often as it stands here (the FMU-state calls as in fuzz_support).
fn random_ops() -> Vec<Op> {
    let mut ops = vec![
        Op::EnterInitialization,
        Op::ExitInitialization,
        Op::Terminate,
        Op::Reset,
        Op::Set(ValueType::Float64),
        Op::Set(ValueType::Float64),
        Op::Set(ValueType::Float64),
        Op::Set(ValueType::Int32),
        Op::Set(ValueType::Int64),
        Op::Set(ValueType::Int64),
        Op::Set(ValueType::Float32),
        Op::Set(ValueType::Boolean),
        Op::Set(ValueType::String),
        Op::Set(ValueType::Binary),
        Op::Set(ValueType::Clock),
        Op::Set(ValueType::UInt64),
        Op::Get(ValueType::Float64),
        Op::Get(ValueType::Float64),
        Op::Get(ValueType::Float64),
        Op::Get(ValueType::Int32),
        Op::Get(ValueType::Int64),
        Op::Get(ValueType::Float32),
        Op::Get(ValueType::Boolean),
        Op::Get(ValueType::String),
        Op::Get(ValueType::Binary),
        Op::Get(ValueType::Clock),
        Op::Get(ValueType::Int8),
        Op::DoStep,
        Op::DoStep,
        Op::DoStep,
        Op::DoStep,
        Op::DoStep,
        Op::OutputDerivatives,
    ];
    ops.extend(fmu_states::RANDOM.map(Op::State));
    ops.extend([
        Op::Unsupported,
        Op::Unsupported,
        Op::DebugLogging,
        Op::Null,
        Op::Null,
        Op::Free,
        Op::FreeTwice,
        Op::Reinstantiate,
        Op::Reinstantiate,
        Op::ForeignHandle,
        Op::HandleToFmi2,
    ]);
    ops
}

impl Op {
    /// The C function the operation calls, for the "names the function" check.
    fn function(self) -> String {
        match self {
            Op::EnterInitializationValid | Op::EnterInitialization => {
                "fmi3EnterInitializationMode".into()
            }
            Op::ExitInitialization => "fmi3ExitInitializationMode".into(),
            Op::Terminate => "fmi3Terminate".into(),
            Op::Reset => "fmi3Reset".into(),
            Op::Set(t) => format!("fmi3Set{t:?}"),
            Op::Get(t) => format!("fmi3Get{t:?}"),
            Op::DoStep => "fmi3DoStep".into(),
            Op::OutputDerivatives => "fmi3GetOutputDerivatives".into(),
            Op::State(op) => <ImportedInstance as FmuStates>::function(op).into(),
            Op::DebugLogging => "fmi3SetDebugLogging".into(),
            // Named by the call actually made.
            Op::Unsupported | Op::Null | Op::ForeignHandle | Op::HandleToFmi2 => String::new(),
            Op::Free | Op::FreeTwice => "fmi3FreeInstance".into(),
            Op::Reinstantiate => "fmi3InstantiateCoSimulation".into(),
        }
    }
}

fn null_argument(rng: &mut Rng, state: State) -> NullArgument {
    use NullArgument::*;
    let all = [
        GetFloat64Values,
        SetFloat64Values,
        GetFloat64References,
        GetInt64Values,
        SetInt64Values,
        SetStringElement,
        GetBinarySizes,
        DebugLoggingCategories,
        GetFmuStateSlot,
        FreeFmuStateSlot,
        SerializedSizeOut(state),
        SerializeBuffer(state),
        DeserializeBytes,
        DeserializeSlot,
        DoStepOutput(rng.below(4) as u8),
        OutputDerivativeOrders,
        OutputDerivativeValues,
    ];
    rng.pick(&all)
}

/// nValues for `n` value references: mostly right, sometimes not.
fn n_values(rng: &mut Rng, n: usize) -> usize {
    if rng.chance(85) {
        n
    } else {
        rng.pick(&[0, n + 1, n.saturating_sub(1), 7])
    }
}

/// A value for the variable `vr` names (any type's setter is given it, converted with `as`).
fn value_for(rng: &mut Rng, table: &ModelTable, vr: u32) -> f64 {
    let var = table.variable(vr);
    match var.map(|v| v.kind) {
        Some(Kind::Real { .. }) => real_value(rng, table, var),
        Some(_) => f64::from(integer_value(rng, table, var)),
        None => rng.pick(SPECIAL),
    }
}

struct Slot {
    instance: ImportedInstance,
    table: &'static ModelTable,
    /// The time the fuzzer believes the instance is at (its own bookkeeping, not the FMU's).
    time: f64,
    /// Whether the instance was given a logMessage callback (without one it cannot explain).
    logs: bool,
    /// What its intermediate-update hook did, if it has one.
    hook: Arc<HookLog>,
}

impl Slot {
    /// Whether the instance is freed, through the driver or from inside its hook.
    fn freed(&self) -> bool {
        self.instance.is_freed() || self.hook.freed.load(Ordering::SeqCst)
    }
}

/// What an intermediate-update hook did, checked after each call of the sequence.
#[derive(Default)]
struct HookLog {
    /// The hook called fmi3FreeInstance.
    freed: AtomicBool,
    /// The functions it called that returned other than OK, each to be explained in the log.
    refused: Mutex<Vec<(String, Status)>>,
    /// Broken promises.
    failures: Mutex<Vec<String>>,
}

/// A hook that calls the FMU back from inside fmi3DoStep, at random, as an importer's
/// intermediateUpdate callback might: allowed calls (getters, setters) and calls FMI 3.0 does not
/// allow there (steps, resets, FMU states, termination, freeing the instance).
fn hook(seed: u64, table: &'static ModelTable, log: Arc<HookLog>) -> OnIntermediateUpdate {
    let mut rng = Rng(seed);
    let mut states = vec![State::NULL];
    Box::new(move |fmu: &mut ImportedInstance, time: f64| {
        if log.freed.load(Ordering::SeqCst) || !rng.chance(30) {
            return;
        }
        let state = rng.pick(&states);
        let (function, status): (String, Status) = match rng.below(13) {
            0..=2 => {
                let vrs = value_references(&mut rng, table);
                let (status, values) = fmu.get_float64(&vrs);
                if status == Status::Ok && values.iter().any(|x| !x.is_finite()) {
                    lock(&log.failures).push(format!(
                        "at t = {time}: fmi3GetFloat64({vrs:?}) = {values:?}: OK, not finite"
                    ));
                }
                ("fmi3GetFloat64".into(), status)
            }
            3 | 4 => {
                let vrs = value_references(&mut rng, table);
                let values: Vec<f64> = vrs
                    .iter()
                    .map(|&vr| value_for(&mut rng, table, vr))
                    .collect();
                let t = rng.pick(&[ValueType::Float64, ValueType::Int32, ValueType::Int64]);
                (format!("fmi3Set{t:?}"), fmu.set(t, &vrs, &values))
            }
            5 => match fmu.get_fmu_state() {
                Ok(state) => {
                    states.push(state);
                    ("fmi3GetFMUState".into(), Status::Ok)
                }
                Err(status) => ("fmi3GetFMUState".into(), status),
            },
            6 => ("fmi3SetFMUState".into(), fmu.set_fmu_state(state)),
            7 => ("fmi3Reset".into(), fmu.reset()),
            8 => ("fmi3Terminate".into(), fmu.terminate()),
            9 => {
                let h = table.default_experiment.step_size;
                ("fmi3DoStep".into(), fmu.do_step(time, h, false).0)
            }
            10 => (
                "fmi3EnterInitializationMode".into(),
                fmu.enter_initialization_mode(None, 0.0, None),
            ),
            11 => {
                let orders = [1];
                let vr = [table.variables[rng.below(table.variables.len())].value_reference];
                let (status, values) = fmu.get_output_derivatives(&vr, &orders, 1);
                if status == Status::Ok && !values[0].is_finite() {
                    lock(&log.failures).push(format!(
                        "at t = {time}: fmi3GetOutputDerivatives({vr:?}) = {values:?}: OK, not finite"
                    ));
                }
                ("fmi3GetOutputDerivatives".into(), status)
            }
            _ => {
                fmu.free();
                log.freed.store(true, Ordering::SeqCst);
                return;
            }
        };
        if status != Status::Ok {
            lock(&log.refused).push((function, status));
        }
    })
}

fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|e| e.into_inner())
}

/// An FMI 3.0 instance; Err("") when the FMU rightly refused wrong arguments, Err(why) when it
/// broke a promise.
fn instantiate(rng: &mut Rng, mut table: &'static ModelTable, name: &str) -> Result<Slot, String> {
    let mut arguments =
        Instantiation::new(table.model_identifier, name).ok_or("model has no token")?;
    arguments.logging_on = rng.chance(20);
    // What the FMU accepts whatever it is.
    arguments.visible = rng.chance(50);
    arguments.early_return_allowed = rng.chance(30);
    arguments.intermediate_update = rng.chance(30);
    if rng.chance(20) {
        let vrs = value_references(rng, table);
        arguments.required_intermediate_variables = vrs;
    }
    if rng.chance(5) {
        arguments.log_message = false;
    }
    if rng.chance(10) {
        arguments.resource_path = Some(rng.pick(&["/tmp/", "", "C:\\x\\", "file:///r"]).into());
    }
    if rng.chance(12) {
        match rng.below(8) {
            0 => arguments.instance_name = None,
            1 => arguments.instance_name = Some(rng.pick(&["", " \t"]).into()),
            2 => arguments.instantiation_token = None,
            3 => arguments.instantiation_token = Some("{not-a-token}".into()),
            4 => {
                // Another model's token: this library carries every model, so it instantiates
                // that model.
                table = sequence::any_model(rng);
                arguments.instantiation_token =
                    friction_fmu::fmi2::guid(table.model_identifier).map(String::from);
            }
            5 => arguments.event_mode_used = true,
            6 => arguments.interface = Interface::ModelExchange,
            _ => arguments.interface = Interface::ScheduledExecution,
        }
    }
    let expect_refusal = arguments
        .instance_name
        .as_deref()
        .is_none_or(|n| n.trim().is_empty())
        || arguments.instantiation_token.as_deref()
            != friction_fmu::fmi2::guid(table.model_identifier)
        || arguments.event_mode_used
        || arguments.interface != Interface::CoSimulation;
    let logs = arguments.log_message;
    let with_hook = arguments.intermediate_update && rng.chance(60);
    let hook_seed = rng.next();
    match ImportedInstance::instantiate(&arguments) {
        Ok(_) if expect_refusal => Err(format!("instantiated with {arguments:?}")),
        Ok(mut instance) => {
            let log = Arc::new(HookLog::default());
            if with_hook {
                instance.on_intermediate_update(Some(hook(hook_seed, table, log.clone())));
            }
            Ok(Slot {
                instance,
                table,
                time: 0.0,
                logs,
                hook: log,
            })
        }
        Err(_) if !expect_refusal => Err(format!("refused {arguments:?}")),
        Err(log)
            if !logs
                || log
                    .iter()
                    .any(|m| m.text.contains(arguments.interface.function())) =>
        {
            Err(String::new())
        }
        Err(log) => Err(format!(
            "refused {arguments:?} without a message naming the function: {log:?}"
        )),
    }
}

/// Every call was refused with an error status; else the first that was not.
fn all_refused(calls: impl IntoIterator<Item = (String, i32)>) -> Result<(), String> {
    match calls
        .into_iter()
        .find(|(_, status)| *status != Status::Error as i32)
    {
        None => Ok(()),
        Some((name, status)) => Err(format!("{name} returned {status} on a foreign handle")),
    }
}

/// Every fmi3 function on `handle` (see [`calls_on_handle`]), for [`all_refused`].
fn fmi3_calls_on(handle: usize) -> impl Iterator<Item = (String, i32)> {
    calls_on_handle(handle)
        .into_iter()
        .map(|(name, status)| (name, status as i32))
}

/// Every fmi2 function on `handle` (see [`calls_on_component`]), for [`all_refused`].
fn fmi2_calls_on(handle: usize) -> impl Iterator<Item = (String, i32)> {
    calls_on_component(handle)
        .into_iter()
        .map(|(name, status)| (name.to_string(), status as i32))
}

/// Runs sequence `index`; the error describes the first broken promise.
fn sequence(seed: u64, index: u64, verbose: bool) -> Result<(), String> {
    let mut rng = sequence::rng_of(seed, index);
    let (first, mut slots) = sequence::first_two(&mut rng, instantiate)?;
    let mut made = Made::new();
    // An FMI 2.0 instance beside them, whose handle the FMI 3.0 functions must refuse.
    let mut twin = if rng.chance(40) {
        let mut twin = fmi2::ImportedInstance::new(first.model_identifier, "twin")
            .map_err(|log| format!("fmi2Instantiate: {log:?}"))?;
        if rng.chance(50) {
            twin.initialize();
            if let Ok(mut state) = twin.get_fmu_state() {
                made.blobs.extend(twin.serialize_fmu_state(state));
                twin.free_fmu_state(&mut state);
            }
        }
        twin.take_messages();
        Some(twin)
    } else {
        None
    };
    let mut freed_handles: Vec<usize> = Vec::new();
    let calls = Calls::new(
        &mut rng,
        slots.len(),
        |rng| Op::Set(rng.pick(&[ValueType::Float64, ValueType::Int32, ValueType::Int64])),
        &[Op::EnterInitializationValid, Op::ExitInitialization],
        Op::State(StateOp::SeedBytes),
    );
    let ops = random_ops();
    for call in 0..calls.count {
        let (k, op) = calls.get(call, &mut rng, slots.len(), &ops);
        if let Op::Reinstantiate = op {
            let replaced =
                sequence::reinstantiate(&mut rng, &mut slots, k, Slot::freed, instantiate)?;
            // The replaced instance is dropped, which frees it: its handle must stay refused.
            freed_handles.extend(replaced.map(|old| old.instance.handle()));
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
        let live = !slot.freed();
        let mut function = op.function();
        let mut description = String::new();
        let status: Option<Status> = match op {
            Op::EnterInitializationValid | Op::EnterInitialization => {
                let experiment = match op {
                    Op::EnterInitializationValid => Experiment::valid(&mut rng, table),
                    _ => Experiment::random(&mut rng, table),
                };
                description = experiment.describe();
                let Experiment {
                    tolerance,
                    start,
                    stop,
                } = experiment;
                let status = slot
                    .instance
                    .enter_initialization_mode(tolerance, start, stop);
                if status == Status::Ok {
                    slot.time = start;
                }
                Some(status)
            }
            Op::ExitInitialization => Some(slot.instance.exit_initialization_mode()),
            Op::Terminate => Some(slot.instance.terminate()),
            Op::Reset => {
                slot.time = 0.0;
                Some(slot.instance.reset())
            }
            Op::Set(t) => {
                let vrs = value_references(&mut rng, table);
                let n = n_values(&mut rng, vrs.len());
                let values: Vec<f64> = (0..n)
                    .map(|i| match vrs.get(i) {
                        Some(&vr) => value_for(&mut rng, table, vr),
                        None => rng.pick(SPECIAL),
                    })
                    .collect();
                description = format!("({vrs:?}, {values:?})");
                Some(slot.instance.set(t, &vrs, &values))
            }
            Op::Get(t) => {
                let vrs = value_references(&mut rng, table);
                let n = n_values(&mut rng, vrs.len());
                let (status, values) = slot.instance.get(t, &vrs, n);
                description = format!("({vrs:?}, nValues = {n}) = {values:?}");
                checks::finite_when_ok(call, &function, &description, status, &values)?;
                Some(status)
            }
            Op::DoStep => {
                let h = step_size(&mut rng, table);
                let t = sequence::communication_point(&mut rng, slot.time, h);
                description = format!("(t = {t}, h = {h})");
                if verbose {
                    println!("     {description}");
                }
                let (status, outcome) = slot.instance.do_step(t, h, rng.chance(50));
                description = format!("{description} = {outcome:?}");
                if live && status <= Status::Discard {
                    // Never an event or an early return (hasEventMode = false, no early return).
                    if outcome.event_handling_needed || outcome.early_return {
                        return Err(format!("call {call}: fmi3DoStep{description}"));
                    }
                    if !outcome.last_successful_time.is_finite() {
                        return Err(format!(
                            "call {call}: fmi3DoStep{description}: lastSuccessfulTime not finite"
                        ));
                    }
                }
                if status == Status::Ok {
                    let end = t + h;
                    if (outcome.last_successful_time - end).abs() > 1e-12 * end.abs().max(1.0) {
                        return Err(format!(
                            "call {call}: fmi3DoStep{description} returned OK, lastSuccessfulTime is not t + h = {end}"
                        ));
                    }
                    slot.time = end;
                } else if status == Status::Discard {
                    slot.time = outcome.last_successful_time;
                }
                Some(status)
            }
            Op::OutputDerivatives => {
                let vrs = value_references(&mut rng, table);
                let orders: Vec<i32> = vrs.iter().map(|_| rng.pick(&[1, 1, 2, 0, -1, 3])).collect();
                let n = n_values(&mut rng, vrs.len());
                let (status, values) = slot.instance.get_output_derivatives(&vrs, &orders, n);
                description = format!("({vrs:?}, {orders:?}, nValues = {n}) = {values:?}");
                checks::finite_when_ok(call, &function, &description, status, &values)?;
                Some(status)
            }
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
                function = called.function.into();
                description = called.description;
                Some(called.status)
            }
            Op::Unsupported => {
                let which = rng.pick(&Unsupported::ALL);
                function = which.function();
                Some(slot.instance.call_unsupported(which))
            }
            Op::DebugLogging => {
                let categories = sequence::debug_categories(&mut rng);
                description = format!("({categories:?})");
                Some(slot.instance.set_debug_logging(rng.chance(50), &categories))
            }
            Op::Null => {
                let which = null_argument(&mut rng, state);
                function = which.function().into();
                description = format!("({which:?})");
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
            Op::Reinstantiate => unreachable!("handled above"),
            Op::ForeignHandle => {
                // Only handles that can never be a live FMI 3.0 instance: handles are ids that
                // are never reused, and other threads' instances must not be reached.
                let mut foreign = vec![0, usize::MAX, 0xdead_beef_0000];
                foreign.extend(freed_handles.iter().copied());
                foreign.extend(twin.as_ref().map(|t| t.handle()));
                if !live {
                    foreign.push(slot.instance.handle());
                }
                let handle = rng.pick(&foreign);
                description = format!("(handle {handle:#x})");
                if verbose {
                    println!("     {description}");
                }
                all_refused(fmi3_calls_on(handle))
                    .map_err(|e| format!("call {call}: {e} {handle:#x}"))?;
                free_foreign_handle(handle);
                if let Some(twin) = twin.as_mut() {
                    let messages = twin.take_messages();
                    if !messages.is_empty() {
                        return Err(format!(
                            "call {call}: fmi3 calls on {handle:#x} reached the FMI 2.0 instance: {messages:?}"
                        ));
                    }
                    // Still alive: the fmi3FreeInstance above did not end it.
                    if twin.set_debug_logging(false, &[]) != Status2::Ok {
                        return Err(format!(
                            "call {call}: fmi3FreeInstance({handle:#x}) ended the FMI 2.0 instance: {:?}",
                            twin.take_messages()
                        ));
                    }
                }
                None
            }
            Op::HandleToFmi2 => {
                let handle = slot.instance.handle();
                all_refused(fmi2_calls_on(handle))
                    .map_err(|e| format!("call {call}: {e} (the FMI 3.0 handle {handle:#x})"))?;
                free_foreign_component(handle);
                let messages = slot.instance.take_messages();
                if !messages.is_empty() {
                    return Err(format!(
                        "call {call}: fmi2 calls on an FMI 3.0 handle reached it: {messages:?}"
                    ));
                }
                // Still alive (if it was): fmi2FreeInstance did not end it.
                function = "fmi3SetDebugLogging".into();
                description = " after fmi2FreeInstance on the FMI 3.0 handle".into();
                Some(slot.instance.set_debug_logging(false, &[]))
            }
        };
        let messages = slot.instance.take_messages();
        if verbose {
            println!("{call:3}: [{k}] {function}{description} -> {status:?} {messages:?}");
        }
        // What the intermediate-update hook called from inside this call.
        if let Some(failure) = lock(&slot.hook.failures).first() {
            return Err(format!(
                "call {call}: {function}{description}: hook: {failure}"
            ));
        }
        for (inner, inner_status) in std::mem::take(&mut *lock(&slot.hook.refused)) {
            if slot.logs && !checks::explained::<Status>(&messages, &inner) {
                return Err(format!(
                    "call {call}: {function}{description}: the hook's {inner} returned {inner_status:?} without a message naming it: {messages:?}"
                ));
            }
        }
        let Some(status) = status else { continue };
        // Freed by the hook inside this call: what followed could not be logged.
        let live = live && !slot.freed();
        // Freed by the hook during or before this call and refused: whatever was logged before.
        let refused_after_the_hook_freed_it =
            slot.freed() && !slot.instance.is_freed() && status == Status::Error;
        if !refused_after_the_hook_freed_it {
            checks::status_kept_its_promises(
                call,
                &function,
                &description,
                status,
                live,
                slot.logs,
                &messages,
            )?;
        }
    }
    // Freed handles stay refused after the sequence made and freed other instances.
    for handle in freed_handles {
        all_refused(fmi3_calls_on(handle)).map_err(|e| format!("at the end: {e}"))?;
    }
    if rng.chance(2) {
        free_foreign_handle(0);
        all_refused(fmi3_calls_on(0)).map_err(|e| format!("NULL: {e}"))?;
    }
    Ok(())
}

#[test]
fn random_fmi3_call_sequences_never_crash_panic_or_lie() {
    fuzz_support::runner::run(sequence, 50_000);
}

#[test]
fn version() {
    assert_eq!(friction_fmu::importer::fmi3::version(), "3.0");
}

/// Every fmi3 function is covered by this fuzzer: the 14 types' getters and setters, the
/// functions of the modes left out, and the rest by name (what `sequence` calls).
#[test]
fn every_fmi3_function_is_fuzzed() {
    let others = [
        "fmi3GetVersion",
        "fmi3SetDebugLogging",
        "fmi3InstantiateModelExchange",
        "fmi3InstantiateCoSimulation",
        "fmi3InstantiateScheduledExecution",
        "fmi3FreeInstance",
        "fmi3EnterInitializationMode",
        "fmi3ExitInitializationMode",
        "fmi3Terminate",
        "fmi3Reset",
        "fmi3GetFMUState",
        "fmi3SetFMUState",
        "fmi3FreeFMUState",
        "fmi3SerializedFMUStateSize",
        "fmi3SerializeFMUState",
        "fmi3DeserializeFMUState",
        "fmi3GetOutputDerivatives",
        "fmi3DoStep",
    ];
    assert_eq!(
        2 * VALUE_TYPES.len() + Unsupported::ALL.len() + others.len(),
        75,
        "FMI 3.0 has 75 functions"
    );
}

// --- targeted checks of what the fuzzer checks at random ---

fn outputs(table: &ModelTable) -> Vec<u32> {
    table
        .variables
        .iter()
        .filter(|v| v.causality == Causality::Output && matches!(v.kind, Kind::Real { .. }))
        .map(|v| v.value_reference)
        .collect()
}

fn initialized(table: &ModelTable, name: &str) -> ImportedInstance {
    let mut instance = ImportedInstance::new(table.model_identifier, name).expect("instantiate");
    assert_eq!(
        instance.initialize(),
        Status::Ok,
        "{:?}",
        instance.messages()
    );
    instance
}

/// A freed handle is refused and touches nothing, also when instances made after it run: no
/// fmi3 function on it reaches the next instance, and freeing it again ends nothing.
#[test]
fn a_freed_fmi3_handle_never_reaches_the_next_instance() {
    for table in MODELS.iter().map(|m| m.table) {
        let step = table.default_experiment.step_size;
        let mut freed = initialized(table, "freed");
        let handle = freed.handle();
        freed.free();
        let mut next = initialized(table, "next");
        assert_ne!(next.handle(), handle, "a freed handle was handed out again");
        let (status, _) = freed.do_step(0.0, step, true);
        assert_eq!(status, Status::Error);
        assert_eq!(freed.reset(), Status::Error);
        assert_eq!(
            freed.set_float64(&outputs(table)[..1], &[1.0]),
            Status::Error
        );
        all_refused(fmi3_calls_on(handle)).unwrap();
        freed.free();
        assert!(freed.messages().is_empty(), "{:?}", freed.messages());
        // The next instance is where it was, at t = 0, alive, and was told nothing.
        assert!(next.messages().is_empty(), "{:?}", next.messages());
        assert_eq!(next.do_step(0.0, step, true).0, Status::Ok);
        let (status, outcome) = next.do_step(step, step, true);
        assert_eq!(status, Status::Ok, "{:?}", next.messages());
        assert_eq!(outcome.last_successful_time, 2.0 * step);
    }
}

/// Each standard refuses the other's handles: every fmi3 function on a live FMI 2.0 instance's
/// handle, every fmi2 function on a live FMI 3.0 instance's, and each FreeInstance on the other's,
/// leave both instances as they were.
#[test]
fn a_handle_of_one_standard_is_refused_by_the_other() {
    for table in MODELS.iter().map(|m| m.table) {
        let step = table.default_experiment.step_size;
        let vrs = outputs(table);
        let mut fmi2_instance = fmi2::ImportedInstance::new(table.model_identifier, "two").unwrap();
        assert_eq!(fmi2_instance.initialize(), Status2::Ok);
        let mut fmi3_instance = initialized(table, "three");

        all_refused(fmi3_calls_on(fmi2_instance.handle())).unwrap();
        free_foreign_handle(fmi2_instance.handle());
        all_refused(fmi2_calls_on(fmi3_instance.handle())).unwrap();
        free_foreign_component(fmi3_instance.handle());

        assert!(fmi2_instance.messages().is_empty());
        assert!(fmi3_instance.messages().is_empty());
        // Both still at t = 0 and alive, and they agree.
        assert_eq!(fmi2_instance.do_step(0.0, step, true), Status2::Ok);
        assert_eq!(fmi3_instance.do_step(0.0, step, true).0, Status::Ok);
        let (status2, values2) = fmi2_instance.get_real(&vrs);
        let (status3, values3) = fmi3_instance.get_float64(&vrs);
        assert_eq!((status2, status3), (Status2::Ok, Status::Ok));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&values2), bits(&values3), "{}", table.model_identifier);
    }
}

/// Every fmi3 function refuses NULL as the instance.
#[test]
fn every_fmi3_function_refuses_a_null_instance() {
    free_foreign_handle(0);
    let calls: Vec<_> = fmi3_calls_on(0).collect();
    assert_eq!(
        calls.len(),
        13 + 2 * VALUE_TYPES.len() + Unsupported::ALL.len()
    );
    all_refused(calls).unwrap();
}

/// A getter or setter whose nValues differs from nValueReferences is refused with a message
/// naming it, for a variable of its own type.
#[test]
fn a_wrong_n_values_is_refused_with_a_message() {
    let table = MODELS[0].table;
    let mut instance = initialized(table, "n_values");
    let vr = outputs(table)[0];
    for n in [0, 2, 5] {
        let (status, _) = instance.get(ValueType::Float64, &[vr], n);
        assert_eq!(status, Status::Error, "nValues = {n}");
        let message = instance.last_message();
        assert!(
            message.contains("fmi3GetFloat64") && message.contains("nValues"),
            "{message}"
        );
    }
    assert_eq!(instance.get(ValueType::Float64, &[vr], 1).0, Status::Ok);
}

/// Every variable is read and written through the getter and setter of the type the committed
/// FMI 3.0 modelDescription.xml declares it with (as an importer that reads the XML calls them),
/// and refused through the other integer and float types'.
#[test]
fn every_variable_goes_through_the_type_its_model_description_declares() {
    let types = [
        ValueType::Float64,
        ValueType::Int32,
        ValueType::Int64,
        ValueType::Boolean,
    ];
    let mut failures = Vec::new();
    for table in MODELS.iter().map(|m| m.table) {
        let id = table.model_identifier;
        // Values are read in Initialization Mode and written in Instantiated, before it.
        let mut reader = ImportedInstance::new(id, "reader").unwrap();
        assert_eq!(
            reader.enter_initialization_mode(None, 0.0, None),
            Status::Ok
        );
        let mut writer = ImportedInstance::new(id, "writer").unwrap();
        for declared in fmi3_description::variables(id) {
            let vr = [declared.value_reference];
            for t in types {
                let expected = if t == declared.value_type {
                    Status::Ok
                } else {
                    Status::Error
                };
                let (status, values) = reader.get(t, &vr, 1);
                if status != expected {
                    failures.push(format!(
                        "{id}.{} ({:?}): fmi3Get{t:?} returned {status:?}: {}",
                        declared.name,
                        declared.value_type,
                        reader.last_message()
                    ));
                }
                let settable = ["parameter", "input"].contains(&declared.causality.as_str());
                if settable && t == declared.value_type && status == Status::Ok {
                    let status = writer.set(t, &vr, &values);
                    if status != Status::Ok {
                        failures.push(format!(
                            "{id}.{} ({:?}): fmi3Set{t:?} returned {status:?}: {}",
                            declared.name,
                            declared.value_type,
                            writer.last_message()
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Everything the FMUs leave out is refused with a message naming the function, in any phase.
#[test]
fn every_unsupported_function_is_refused_with_a_message_naming_it() {
    let table = MODELS[0].table;
    let mut instance = ImportedInstance::new(table.model_identifier, "unsupported").unwrap();
    for phase in 0..2 {
        if phase == 1 {
            assert_eq!(instance.initialize(), Status::Ok);
        }
        for which in Unsupported::ALL {
            assert_eq!(instance.call_unsupported(which), Status::Error, "{which:?}");
            let message = instance.last_message();
            assert!(message.contains(&which.function()), "{which:?}: {message}");
        }
    }
}

/// An importer may call the FMU back from its intermediateUpdate callback, also with calls FMI 3.0
/// does not allow there: fmi3DoStep, fmi3Reset, fmi3FreeInstance. The nested step and the reset
/// are refused with a message; freeing the instance ends the step with an error, after which
/// the handle is refused like any freed one.
#[test]
fn calls_from_inside_an_intermediate_update_are_refused_or_end_the_step_safely() {
    let mut called = 0;
    for table in MODELS.iter().map(|m| m.table) {
        let id = table.model_identifier;
        // Long enough to take several internal steps.
        let step = table.default_experiment.step_size * 20.0;
        let mut arguments = Instantiation::new(id, "hooked").unwrap();
        arguments.intermediate_update = true;

        // A nested step and a reset from inside the callback, in the second step (the solvers
        // know their internal step from the first).
        let mut fmu = ImportedInstance::instantiate(&arguments).unwrap();
        assert_eq!(fmu.initialize(), Status::Ok);
        assert_eq!(fmu.do_step(0.0, step, true).0, Status::Ok);
        let before = fmu.intermediate_updates();
        let refused = Arc::new(Mutex::new(Vec::new()));
        let seen = refused.clone();
        fmu.on_intermediate_update(Some(Box::new(move |inner, time| {
            let nested = inner.do_step(time, 1e-6, false).0;
            let reset = inner.reset();
            lock(&seen).push((nested, reset));
        })));
        let (status, outcome) = fmu.do_step(step, step, true);
        assert_eq!(status, Status::Ok, "{id}: {:?}", fmu.messages());
        assert_eq!(outcome.last_successful_time, 2.0 * step);
        if fmu.intermediate_updates() == before {
            continue;
        }
        called += 1;
        let messages = fmu.take_messages();
        for &(nested, reset) in lock(&refused).iter() {
            assert_eq!((nested, reset), (Status::Error, Status::Error), "{id}");
        }
        for function in ["fmi3DoStep", "fmi3Reset"] {
            assert!(
                messages.iter().any(|m| m.text.starts_with(function)),
                "{id}: {messages:?}"
            );
        }

        // Freeing the instance from inside the callback.
        let mut fmu = ImportedInstance::instantiate(&arguments).unwrap();
        assert_eq!(fmu.initialize(), Status::Ok);
        assert_eq!(fmu.do_step(0.0, step, true).0, Status::Ok);
        fmu.on_intermediate_update(Some(Box::new(|inner, _| inner.free())));
        let handle = fmu.handle();
        assert_eq!(fmu.do_step(step, step, true).0, Status::Error, "{id}");
        all_refused(fmi3_calls_on(handle)).unwrap();
    }
    assert!(
        called > 0,
        "no model called the intermediateUpdate callback"
    );
}
