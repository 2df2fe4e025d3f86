//! Every FMI 3.0 function, with its C name.
//!
//! Co-simulation works in full; what FMI 3.0 declares for model exchange, scheduled execution,
//! event mode, configuration mode, clocks and dependencies is refused with a message saying
//! which capability the modelDescription.xml leaves out. [`super::binary`]'s macro exports them
//! under their C names.
#![allow(non_snake_case)]

use super::dialect::FMI3;
use super::ffi::*;
use super::logger::Logger;
use super::updates;
use crate::boundary::args::{slice, slice_mut, text};
use crate::boundary::values::{self, access, is_integer_or_switch, is_none, is_real, Access};
use crate::boundary::{logging, states};
use crate::instance::calls::{Call, ValueType};
use crate::instance::library::Binary;
use crate::instance::log::{LogSink, CATEGORY_ERROR};
use crate::instance::{handles, Instance, Stepped};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Runs `body` on the live FMI 3.0 instance `c` names (see [`handles::with_instance`]).
fn with_instance(c: FmiInstance, body: impl FnOnce(&mut Instance) -> Status) -> Status {
    handles::with_instance(c as usize, &FMI3, body)
}

/// Refuses what these FMUs do not offer, naming the function and why.
fn unsupported(c: FmiInstance, function: &str, why: &str) -> Status {
    with_instance(c, |instance| {
        instance.unsupported(Call::Unsupported, &format!("{function}: {why}"))
    })
}

const NO_EVENT_MODE: &str =
    "not supported: this FMU has no event mode (hasEventMode = false), so it is never in Event Mode";
const CO_SIMULATION_ONLY: &str =
    "not supported: this FMU implements co-simulation only (no ModelExchange element)";
const NO_CLOCKS: &str = "not supported: this FMU has no clocks";
const NO_DEPENDENCIES: &str =
    "not supported: this FMU gives no per-element dependencies (providesPerElementDependencies = false); its ModelStructure lists them";

pub extern "C" fn fmi3GetVersion() -> FmiString {
    c"3.0".as_ptr()
}

/// # Safety
/// Pointers as the FMI 3.0 standard defines them.
pub unsafe extern "C" fn fmi3SetDebugLogging(
    c: FmiInstance,
    logging_on: Boolean,
    n_categories: usize,
    categories: *const FmiString,
) -> Status {
    logging::set_debug_logging(
        c as usize,
        &FMI3,
        logging_on != FALSE,
        n_categories,
        categories,
    )
}

/// fmi3InstantiateCoSimulation of a library that carries what `binary` says. Event mode is
/// refused (hasEventMode = false); early return is never taken, so allowing it changes nothing.
///
/// # Safety
/// Pointers as the FMI 3.0 standard defines them.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate_co_simulation(
    binary: &Binary,
    instance_name: FmiString,
    instantiation_token: FmiString,
    resource_path: FmiString,
    _visible: Boolean,
    logging_on: Boolean,
    event_mode_used: Boolean,
    _early_return_allowed: Boolean,
    _required_intermediate_variables: *const ValueReference,
    _n_required_intermediate_variables: usize,
    environment: InstanceEnvironment,
    log_message: Option<LogMessageCallback>,
    intermediate_update: Option<IntermediateUpdateCallback>,
) -> FmiInstance {
    catch_unwind(AssertUnwindSafe(|| {
        let logger = Logger::new(log_message, environment);
        let refuse = |message: String| {
            logger.log(
                Status::Error,
                CATEGORY_ERROR,
                &format!("fmi3InstantiateCoSimulation: {message}"),
            );
            std::ptr::null_mut()
        };
        if !instance_name.is_null() && text(instance_name).is_none() {
            return refuse("instanceName is not valid UTF-8: expected a UTF-8 name".into());
        }
        let name = text(instance_name).unwrap_or("");
        if name.trim().is_empty() {
            return refuse(
                "instanceName is NULL, empty or only white space: expected a name with at least one other character".into(),
            );
        }
        if event_mode_used != FALSE {
            return refuse(
                "eventModeUsed = true: this FMU has no event mode (hasEventMode = false): expected false".into(),
            );
        }
        let token = text(instantiation_token).unwrap_or("");
        let path = text(resource_path);
        let (model, guid, variant) = match binary.model_of(token, path, "instantiationToken") {
            Ok(found) => found,
            Err(error) => return refuse(error.to_string()),
        };
        let mut instance = Instance::new(model, guid, &FMI3, Box::new(logger), logging_on != FALSE);
        if let Some(loaded) = variant {
            instance = instance.for_variant(loaded);
        }
        // Ids start at 1, so no handle is NULL.
        let handle = handles::register(instance);
        if let Some(callback) = intermediate_update {
            updates::register(handle, callback, environment);
        }
        handle as FmiInstance
    }))
    .unwrap_or(std::ptr::null_mut())
}

/// Says why there is no instance, through the callback the importer gave, and returns NULL.
unsafe fn refuse_instantiation(
    function: &str,
    environment: InstanceEnvironment,
    log_message: Option<LogMessageCallback>,
    why: &str,
) -> FmiInstance {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        Logger::new(log_message, environment).log(
            Status::Error,
            CATEGORY_ERROR,
            &format!("{function}: {why}"),
        );
    }));
    std::ptr::null_mut()
}

/// # Safety
/// Pointers as the FMI 3.0 standard defines them.
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    _instance_name: FmiString,
    _instantiation_token: FmiString,
    _resource_path: FmiString,
    _visible: Boolean,
    _logging_on: Boolean,
    environment: InstanceEnvironment,
    log_message: Option<LogMessageCallback>,
) -> FmiInstance {
    refuse_instantiation(
        "fmi3InstantiateModelExchange",
        environment,
        log_message,
        CO_SIMULATION_ONLY,
    )
}

/// # Safety
/// Pointers as the FMI 3.0 standard defines them.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    _instance_name: FmiString,
    _instantiation_token: FmiString,
    _resource_path: FmiString,
    _visible: Boolean,
    _logging_on: Boolean,
    environment: InstanceEnvironment,
    log_message: Option<LogMessageCallback>,
    _clock_update: Option<ClockUpdateCallback>,
    _lock_preemption: Option<LockPreemptionCallback>,
    _unlock_preemption: Option<UnlockPreemptionCallback>,
) -> FmiInstance {
    refuse_instantiation(
        "fmi3InstantiateScheduledExecution",
        environment,
        log_message,
        "not supported: this FMU implements co-simulation only (no ScheduledExecution element)",
    )
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation; NULL, foreign or already freed handles are ignored.
pub unsafe extern "C" fn fmi3FreeInstance(c: FmiInstance) {
    handles::free(c as usize, &FMI3);
    updates::forget(c as usize);
}

/// Sets the experiment up and enters initialization, as FMI 2.0's two calls do.
///
/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    c: FmiInstance,
    tolerance_defined: Boolean,
    tolerance: f64,
    start_time: f64,
    stop_time_defined: Boolean,
    stop_time: f64,
) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| {
            format!("fmi3EnterInitializationMode(startTime = {start_time}, stopTime = {stop_time})")
        });
        let status = instance.setup_experiment(
            (tolerance_defined != FALSE).then_some(tolerance),
            start_time,
            (stop_time_defined != FALSE).then_some(stop_time),
        );
        if status != Status::Ok {
            return status;
        }
        instance.enter_initialization_mode()
    })
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3ExitInitializationMode(c: FmiInstance) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi3ExitInitializationMode()".into());
        instance.exit_initialization_mode()
    })
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EnterEventMode(c: FmiInstance) -> Status {
    unsupported(c, "fmi3EnterEventMode", NO_EVENT_MODE)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3Terminate(c: FmiInstance) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi3Terminate()".into());
        instance.terminate()
    })
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3Reset(c: FmiInstance) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi3Reset()".into());
        instance.reset()
    })
}

/// Every variable here is a scalar: as many values as value references.
fn check_count(c: FmiInstance, call: Call, nvr: usize, n_values: usize) -> Option<Status> {
    (n_values != nvr).then(|| {
        with_instance(c, |instance| {
            let function = instance.function(call);
            instance.error(&format!(
                "{function}: nValues = {n_values} for {nvr} value references: expected {nvr} (every variable of this FMU is a scalar)"
            ))
        })
    })
}

/// The FMI 3.0 getter of one type: `accepts` says which variables it reaches.
unsafe fn get_values<T>(
    c: FmiInstance,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut T,
    n_values: usize,
    convert: fn(f64) -> T,
) -> Status {
    if let Some(status) = check_count(c, access.call, nvr, n_values) {
        return status;
    }
    values::get_values(c as usize, &FMI3, access, vr, nvr, value, convert)
}

/// The FMI 3.0 setter of one type.
unsafe fn set_values<T: Copy>(
    c: FmiInstance,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *const T,
    n_values: usize,
    convert: fn(T) -> f64,
) -> Status {
    if let Some(status) = check_count(c, access.call, nvr, n_values) {
        return status;
    }
    values::set_values(c as usize, &FMI3, access, vr, nvr, value, convert)
}

/// The getter and setter of one FMI 3.0 type: C names, the type's [`ValueType`], its C type,
/// which variables it reaches, and the conversions from and to f64.
macro_rules! typed_access {
    ($get:ident, $set:ident, $vt:ident, $t:ty, $accepts:expr, $to:expr, $from:expr) => {
        /// # Safety
        /// Arrays of `n_value_references` and `n_values` elements, as FMI 3.0 defines them.
        pub unsafe extern "C" fn $get(
            c: FmiInstance,
            vr: *const ValueReference,
            nvr: usize,
            value: *mut $t,
            n_values: usize,
        ) -> Status {
            let access = access(Call::Get(ValueType::$vt), $accepts, stringify!($vt));
            get_values(c, access, vr, nvr, value, n_values, $to)
        }

        /// # Safety
        /// Arrays of `n_value_references` and `n_values` elements, as FMI 3.0 defines them.
        pub unsafe extern "C" fn $set(
            c: FmiInstance,
            vr: *const ValueReference,
            nvr: usize,
            value: *const $t,
            n_values: usize,
        ) -> Status {
            let access = access(Call::Set(ValueType::$vt), $accepts, stringify!($vt));
            set_values(c, access, vr, nvr, value, n_values, $from)
        }
    };
}

typed_access!(
    fmi3GetFloat64,
    fmi3SetFloat64,
    Float64,
    f64,
    is_real,
    |x| x,
    |x| x
);
typed_access!(
    fmi3GetInt32,
    fmi3SetInt32,
    Int32,
    i32,
    is_integer_or_switch,
    |x| x as i32,
    f64::from
);
typed_access!(
    fmi3GetInt64,
    fmi3SetInt64,
    Int64,
    i64,
    is_none,
    |x| x as i64,
    |x| x as f64
);
typed_access!(
    fmi3GetFloat32,
    fmi3SetFloat32,
    Float32,
    f32,
    is_none,
    |x| x as f32,
    f64::from
);
typed_access!(
    fmi3GetInt8,
    fmi3SetInt8,
    Int8,
    i8,
    is_none,
    |x| x as i8,
    f64::from
);
typed_access!(
    fmi3GetUInt8,
    fmi3SetUInt8,
    UInt8,
    u8,
    is_none,
    |x| x as u8,
    f64::from
);
typed_access!(
    fmi3GetInt16,
    fmi3SetInt16,
    Int16,
    i16,
    is_none,
    |x| x as i16,
    f64::from
);
typed_access!(
    fmi3GetUInt16,
    fmi3SetUInt16,
    UInt16,
    u16,
    is_none,
    |x| x as u16,
    f64::from
);
typed_access!(
    fmi3GetUInt32,
    fmi3SetUInt32,
    UInt32,
    u32,
    is_none,
    |x| x as u32,
    f64::from
);
typed_access!(
    fmi3GetUInt64,
    fmi3SetUInt64,
    UInt64,
    u64,
    is_none,
    |x| x as u64,
    |x| x as f64
);
typed_access!(
    fmi3GetBoolean,
    fmi3SetBoolean,
    Boolean,
    Boolean,
    is_none,
    |x| x as u8,
    f64::from
);
typed_access!(
    fmi3GetString,
    fmi3SetString,
    String,
    FmiString,
    is_none,
    |_| std::ptr::null(),
    |_| 0.0
);

/// # Safety
/// Arrays as FMI 3.0 defines them; this FMU has no Binary variables.
pub unsafe extern "C" fn fmi3GetBinary(
    c: FmiInstance,
    vr: *const ValueReference,
    nvr: usize,
    value_sizes: *mut usize,
    value: *mut BinaryValue,
    n_values: usize,
) -> Status {
    let access = access(Call::Get(ValueType::Binary), is_none, "Binary");
    let status = get_values(c, access, vr, nvr, value, n_values, |_| std::ptr::null());
    if status == Status::Ok {
        if let Some(sizes) = slice_mut(value_sizes, n_values) {
            sizes.fill(0);
        }
    }
    status
}

/// # Safety
/// Arrays as FMI 3.0 defines them; this FMU has no Binary variables.
pub unsafe extern "C" fn fmi3SetBinary(
    c: FmiInstance,
    vr: *const ValueReference,
    nvr: usize,
    _value_sizes: *const usize,
    value: *const BinaryValue,
    n_values: usize,
) -> Status {
    let access = access(Call::Set(ValueType::Binary), is_none, "Binary");
    set_values(c, access, vr, nvr, value, n_values, |_| 0.0)
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no clocks.
pub unsafe extern "C" fn fmi3GetClock(
    c: FmiInstance,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut Clock,
) -> Status {
    let access = access(Call::Get(ValueType::Clock), is_none, "Clock");
    get_values(c, access, vr, nvr, value, nvr, |_| FALSE)
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no clocks.
pub unsafe extern "C" fn fmi3SetClock(
    c: FmiInstance,
    vr: *const ValueReference,
    nvr: usize,
    value: *const Clock,
) -> Status {
    let access = access(Call::Set(ValueType::Clock), is_none, "Clock");
    set_values(c, access, vr, nvr, value, nvr, f64::from)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
    c: FmiInstance,
    _value_reference: ValueReference,
    _n_dependencies: *mut usize,
) -> Status {
    unsupported(c, "fmi3GetNumberOfVariableDependencies", NO_DEPENDENCIES)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetVariableDependencies(
    c: FmiInstance,
    _dependent: ValueReference,
    _element_indices_of_dependent: *mut usize,
    _independents: *mut ValueReference,
    _element_indices_of_independents: *mut usize,
    _dependency_kinds: *mut DependencyKind,
    _n_dependencies: usize,
) -> Status {
    unsupported(c, "fmi3GetVariableDependencies", NO_DEPENDENCIES)
}

/// # Safety
/// `state` points to an fmi3FMUState.
pub unsafe extern "C" fn fmi3GetFMUState(c: FmiInstance, state: *mut FmuState) -> Status {
    states::get(c as usize, &FMI3, state)
}

/// # Safety
/// `state` from fmi3GetFMUState.
pub unsafe extern "C" fn fmi3SetFMUState(c: FmiInstance, state: FmuState) -> Status {
    states::set(c as usize, &FMI3, state)
}

/// # Safety
/// `state` points to an fmi3FMUState from this instance.
pub unsafe extern "C" fn fmi3FreeFMUState(c: FmiInstance, state: *mut FmuState) -> Status {
    states::free(c as usize, &FMI3, state)
}

/// # Safety
/// `size` points to a size_t.
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    c: FmiInstance,
    state: FmuState,
    size: *mut usize,
) -> Status {
    states::serialized_size(c as usize, &FMI3, state, size)
}

/// # Safety
/// `bytes` has room for `size` bytes.
pub unsafe extern "C" fn fmi3SerializeFMUState(
    c: FmiInstance,
    state: FmuState,
    bytes: *mut Byte,
    size: usize,
) -> Status {
    states::serialize(c as usize, &FMI3, state, bytes, size)
}

/// # Safety
/// `bytes` holds `size` bytes; `state` points to an fmi3FMUState.
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    c: FmiInstance,
    bytes: *const Byte,
    size: usize,
    state: *mut FmuState,
) -> Status {
    states::deserialize(c as usize, &FMI3, bytes, size, state)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    c: FmiInstance,
    _unknowns: *const ValueReference,
    _n_unknowns: usize,
    _knowns: *const ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> Status {
    with_instance(c, |instance| {
        instance.unsupported(
            Call::GetDirectionalDerivative,
            "fmi3GetDirectionalDerivative: not supported (providesDirectionalDerivatives = false)",
        )
    })
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3GetAdjointDerivative(
    c: FmiInstance,
    _unknowns: *const ValueReference,
    _n_unknowns: usize,
    _knowns: *const ValueReference,
    _n_knowns: usize,
    _seed: *const f64,
    _n_seed: usize,
    _sensitivity: *mut f64,
    _n_sensitivity: usize,
) -> Status {
    unsupported(
        c,
        "fmi3GetAdjointDerivative",
        "not supported (providesAdjointDerivatives = false)",
    )
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EnterConfigurationMode(c: FmiInstance) -> Status {
    unsupported(
        c,
        "fmi3EnterConfigurationMode",
        "not supported: this FMU has no structural parameters",
    )
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3ExitConfigurationMode(c: FmiInstance) -> Status {
    unsupported(
        c,
        "fmi3ExitConfigurationMode",
        "not supported: this FMU has no structural parameters",
    )
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetIntervalDecimal(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _intervals: *mut f64,
    _qualifiers: *mut IntervalQualifier,
) -> Status {
    unsupported(c, "fmi3GetIntervalDecimal", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetIntervalFraction(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
    _qualifiers: *mut IntervalQualifier,
) -> Status {
    unsupported(c, "fmi3GetIntervalFraction", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetShiftDecimal(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _shifts: *mut f64,
) -> Status {
    unsupported(c, "fmi3GetShiftDecimal", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetShiftFraction(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
) -> Status {
    unsupported(c, "fmi3GetShiftFraction", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetIntervalDecimal(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _intervals: *const f64,
) -> Status {
    unsupported(c, "fmi3SetIntervalDecimal", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetIntervalFraction(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> Status {
    unsupported(c, "fmi3SetIntervalFraction", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetShiftDecimal(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _shifts: *const f64,
) -> Status {
    unsupported(c, "fmi3SetShiftDecimal", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetShiftFraction(
    c: FmiInstance,
    _vr: *const ValueReference,
    _nvr: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> Status {
    unsupported(c, "fmi3SetShiftFraction", NO_CLOCKS)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(c: FmiInstance) -> Status {
    unsupported(c, "fmi3EvaluateDiscreteStates", NO_EVENT_MODE)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    c: FmiInstance,
    _discrete_states_need_update: *mut Boolean,
    _terminate_simulation: *mut Boolean,
    _nominals_changed: *mut Boolean,
    _values_changed: *mut Boolean,
    _next_event_time_defined: *mut Boolean,
    _next_event_time: *mut f64,
) -> Status {
    unsupported(c, "fmi3UpdateDiscreteStates", NO_EVENT_MODE)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(c: FmiInstance) -> Status {
    unsupported(c, "fmi3EnterContinuousTimeMode", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
    c: FmiInstance,
    _no_set_fmu_state_prior_to_current_point: Boolean,
    _enter_event_mode: *mut Boolean,
    _terminate_simulation: *mut Boolean,
) -> Status {
    unsupported(c, "fmi3CompletedIntegratorStep", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetTime(c: FmiInstance, _time: f64) -> Status {
    unsupported(c, "fmi3SetTime", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3SetContinuousStates(
    c: FmiInstance,
    _states: *const f64,
    _n: usize,
) -> Status {
    unsupported(c, "fmi3SetContinuousStates", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
    c: FmiInstance,
    _derivatives: *mut f64,
    _n: usize,
) -> Status {
    unsupported(c, "fmi3GetContinuousStateDerivatives", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetEventIndicators(
    c: FmiInstance,
    _indicators: *mut f64,
    _n: usize,
) -> Status {
    unsupported(c, "fmi3GetEventIndicators", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetContinuousStates(
    c: FmiInstance,
    _states: *mut f64,
    _n: usize,
) -> Status {
    unsupported(c, "fmi3GetContinuousStates", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
    c: FmiInstance,
    _nominals: *mut f64,
    _n: usize,
) -> Status {
    unsupported(c, "fmi3GetNominalsOfContinuousStates", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(c: FmiInstance, _n: *mut usize) -> Status {
    unsupported(c, "fmi3GetNumberOfEventIndicators", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(c: FmiInstance, _n: *mut usize) -> Status {
    unsupported(c, "fmi3GetNumberOfContinuousStates", CO_SIMULATION_ONLY)
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3EnterStepMode(c: FmiInstance) -> Status {
    unsupported(
        c,
        "fmi3EnterStepMode",
        "not needed: without event mode, fmi3ExitInitializationMode enters Step Mode",
    )
}

/// # Safety
/// Arrays of `nvr` and `n_values` elements, as FMI 3.0 defines them.
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    c: FmiInstance,
    vr: *const ValueReference,
    nvr: usize,
    order: *const i32,
    value: *mut f64,
    n_values: usize,
) -> Status {
    if let Some(status) = check_count(c, Call::GetRealOutputDerivatives, nvr, n_values) {
        return status;
    }
    with_instance(c, |instance| {
        let (Some(vrs), Some(orders), Some(out)) =
            (slice(vr, nvr), slice(order, nvr), slice_mut(value, nvr))
        else {
            return instance.null_argument(Call::GetRealOutputDerivatives, "vr, order or value");
        };
        instance.get_output_derivatives(vrs, orders, out)
    })
}

/// Steps synchronously: never an event, never an early return; lastSuccessfulTime is where
/// the step ended, or, on fmi3Discard, the time the instance was rolled back to. An importer that
/// gave an intermediate-update callback is called back at the end of each internal step inside
/// the step, where it may read outputs and set inputs.
///
/// # Safety
/// The four output pointers point to their types.
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn fmi3DoStep(
    c: FmiInstance,
    current_communication_point: f64,
    communication_step_size: f64,
    _no_set_fmu_state_prior_to_current_point: Boolean,
    event_handling_needed: *mut Boolean,
    terminate_simulation: *mut Boolean,
    early_return: *mut Boolean,
    last_successful_time: *mut f64,
) -> Status {
    let update = updates::of(c as usize);
    let outputs = (
        event_handling_needed,
        terminate_simulation,
        early_return,
        last_successful_time,
    );
    let status = with_instance(c, |instance| {
        instance.trace(|| {
            format!("fmi3DoStep(t = {current_communication_point}, h = {communication_step_size})")
        });
        let flags = [event_handling_needed, terminate_simulation, early_return];
        if flags.iter().any(|p| p.is_null()) || last_successful_time.is_null() {
            return instance.null_argument(
                Call::DoStep,
                "eventHandlingNeeded, terminateSimulation, earlyReturn or lastSuccessfulTime",
            );
        }
        if update.is_some() {
            instance.begin_step_with_updates(current_communication_point, communication_step_size)
        } else {
            let status = instance.do_step(current_communication_point, communication_step_size);
            write_step_outcome(instance, outputs);
            status
        }
    });
    let Some((callback, environment)) = update else {
        return status;
    };
    let status = if status == Status::Ok {
        internal_steps(c, callback, environment)
    } else {
        status
    };
    // After the internal steps, in a second look-up: the callback may not run under a borrow.
    let _ = with_instance(c, |instance| {
        write_step_outcome(instance, outputs);
        Status::Ok
    });
    status
}

/// Writes fmi3DoStep's out-arguments where they are not NULL (the call refuses NULL ones before
/// it steps): no event, no termination, no early return, and the instance's lastSuccessfulTime.
unsafe fn write_step_outcome(
    instance: &Instance,
    (event, terminate, early, last): (*mut Boolean, *mut Boolean, *mut Boolean, *mut f64),
) {
    if let (Some(event), Some(terminate), Some(early), Some(last)) = (
        event.as_mut(),
        terminate.as_mut(),
        early.as_mut(),
        last.as_mut(),
    ) {
        *event = FALSE;
        *terminate = FALSE;
        *early = FALSE;
        *last = instance.last_successful_time();
    }
}

/// Takes the step begun on `c` one internal step at a time, calling `callback` between them
/// with no borrow of the instance held; returns the step's status.
unsafe fn internal_steps(
    c: FmiInstance,
    callback: IntermediateUpdateCallback,
    environment: InstanceEnvironment,
) -> Status {
    loop {
        let mut stepped = Stepped::Done(Status::Error);
        with_instance(c, |instance| {
            stepped = instance.next_internal_step();
            Status::Ok
        });
        match stepped {
            Stepped::At(time) => {
                let (mut early, mut early_time) = (FALSE, time);
                // Inputs may be set, outputs read; the internal step is finished; this FMU never
                // returns early.
                callback(
                    environment,
                    time,
                    TRUE,
                    TRUE,
                    TRUE,
                    FALSE,
                    &mut early,
                    &mut early_time,
                );
            }
            Stepped::Done(status) => return status,
        }
    }
}

/// # Safety
/// `c` from fmi3InstantiateCoSimulation.
pub unsafe extern "C" fn fmi3ActivateModelPartition(
    c: FmiInstance,
    _clock_reference: ValueReference,
    _activation_time: f64,
) -> Status {
    unsupported(
        c,
        "fmi3ActivateModelPartition",
        "not supported: this FMU implements co-simulation only (no ScheduledExecution element)",
    )
}
