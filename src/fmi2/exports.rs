//! Every FMI 2.0 common and co-simulation function, exported with its C name.
//!
//! Each one: find the instance (a handle this library handed out and has not freed, else a
//! refusal instead of a crash), turn pointers into slices, dispatch to [`Instance`], turn its
//! outcome into an fmi2Status. They carry their C names; [`super::binary`]'s macro exports them
//! under those names.
#![allow(non_snake_case)]

use super::dialect::FMI2;
use super::ffi::*;
use super::logger::Logger;
use crate::boundary::args::{slice, slice_mut, text};
use crate::boundary::values::{self, access, is_integer_or_switch, is_none, is_real, Access};
use crate::boundary::{logging, states};
use crate::instance::calls::{Call, ValueType};
use crate::instance::library::Binary;
use crate::instance::log::CATEGORY_ERROR;
use crate::instance::{handles, Instance, Status as Outcome};
use std::ffi::c_int;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Runs `body` on the live FMI 2.0 instance `c` names (see [`handles::with_instance`]).
fn with_instance(c: Component, body: impl FnOnce(&mut Instance) -> Outcome) -> Status {
    handles::with_instance(c as usize, &FMI2, body).into()
}

pub extern "C" fn fmi2GetTypesPlatform() -> FmiString {
    c"default".as_ptr()
}

pub extern "C" fn fmi2GetVersion() -> FmiString {
    c"2.0".as_ptr()
}

/// fmi2Instantiate of a library that carries what `binary` says.
///
/// # Safety
/// Pointers as the FMI 2.0 standard defines them.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate(
    binary: &Binary,
    instance_name: FmiString,
    fmu_type: c_int,
    fmu_guid: FmiString,
    fmu_resource_location: FmiString,
    functions: *const CallbackFunctions,
    _visible: Boolean,
    logging_on: Boolean,
) -> Component {
    catch_unwind(AssertUnwindSafe(|| {
        // Without a logger nothing could ever be reported: refuse, as the standard requires one.
        let Some(functions) = functions.as_ref() else {
            return std::ptr::null_mut();
        };
        let Some(callback) = functions.logger else {
            return std::ptr::null_mut();
        };
        let name = text(instance_name).unwrap_or("");
        let logger = Logger::new(Some(callback), functions.component_environment, name);
        let refuse = |message: String| {
            logger.log(
                Status::Error,
                CATEGORY_ERROR,
                &format!("fmi2Instantiate: {message}"),
            );
            std::ptr::null_mut()
        };
        if !instance_name.is_null() && text(instance_name).is_none() {
            return refuse("instanceName is not valid UTF-8: expected a UTF-8 name".into());
        }
        // FMI 2.0, 2.1.5: at least one character that is not white space.
        if name.trim().is_empty() {
            return refuse(
                "instanceName is NULL, empty or only white space: expected a name with at least one other character".into(),
            );
        }
        if fmu_type != CO_SIMULATION {
            return refuse(format!(
                "fmuType = {fmu_type}: this FMU supports only fmi2CoSimulation ({CO_SIMULATION})"
            ));
        }
        let guid = text(fmu_guid).unwrap_or("");
        let location = text(fmu_resource_location);
        if let Some(location) = location {
            let absolute_path = location.starts_with('/');
            if !location.is_empty() && !location.starts_with("file:") && !absolute_path {
                return refuse(format!(
                    "fmuResourceLocation \"{location}\": expected a file: URI (or an absolute path)"
                ));
            }
        }
        let (model, guid, variant) = match binary.model_of(guid, location, "fmuGUID") {
            Ok(found) => found,
            Err(error) => return refuse(error.to_string()),
        };
        let mut instance = Instance::new(model, guid, &FMI2, Box::new(logger), logging_on != FALSE);
        if let Some(loaded) = variant {
            instance = instance.for_variant(loaded);
        }
        // Ids start at 1, so no handle is NULL.
        handles::register(instance) as Component
    }))
    .unwrap_or(std::ptr::null_mut())
}

/// # Safety
/// `c` from fmi2Instantiate; NULL, foreign or already freed handles are ignored.
pub unsafe extern "C" fn fmi2FreeInstance(c: Component) {
    handles::free(c as usize, &FMI2);
}

/// # Safety
/// Pointers as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: Component,
    logging_on: Boolean,
    n_categories: usize,
    categories: *const FmiString,
) -> Status {
    logging::set_debug_logging(
        c as usize,
        &FMI2,
        logging_on != FALSE,
        n_categories,
        categories,
    )
    .into()
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: Component,
    tolerance_defined: Boolean,
    tolerance: Real,
    start_time: Real,
    stop_time_defined: Boolean,
    stop_time: Real,
) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| {
            format!("fmi2SetupExperiment(startTime = {start_time}, stopTime = {stop_time})")
        });
        instance.setup_experiment(
            (tolerance_defined != FALSE).then_some(tolerance),
            start_time,
            (stop_time_defined != FALSE).then_some(stop_time),
        )
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Component) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi2EnterInitializationMode()".into());
        instance.enter_initialization_mode()
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Component) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi2ExitInitializationMode()".into());
        instance.exit_initialization_mode()
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2Terminate(c: Component) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi2Terminate()".into());
        instance.terminate()
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2Reset(c: Component) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi2Reset()".into());
        instance.reset()
    })
}

unsafe fn get_values<T>(
    c: Component,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut T,
    convert: fn(f64) -> T,
) -> Status {
    values::get_values(c as usize, &FMI2, access, vr, nvr, value, convert).into()
}

unsafe fn set_values<T: Copy>(
    c: Component,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *const T,
    convert: fn(T) -> f64,
) -> Status {
    values::set_values(c as usize, &FMI2, access, vr, nvr, value, convert).into()
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2GetReal(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut Real,
) -> Status {
    get_values(
        c,
        access(Call::Get(ValueType::Float64), is_real, "Real"),
        vr,
        nvr,
        value,
        |x| x,
    )
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2GetInteger(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut Integer,
) -> Status {
    get_values(
        c,
        access(
            Call::Get(ValueType::Int32),
            is_integer_or_switch,
            "Integer or Enumeration",
        ),
        vr,
        nvr,
        value,
        |x| x as Integer,
    )
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no Boolean variables.
pub unsafe extern "C" fn fmi2GetBoolean(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut Boolean,
) -> Status {
    get_values(
        c,
        access(Call::Get(ValueType::Boolean), is_none, "Boolean"),
        vr,
        nvr,
        value,
        |x| x as Boolean,
    )
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no String variables.
pub unsafe extern "C" fn fmi2GetString(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut FmiString,
) -> Status {
    get_values(
        c,
        access(Call::Get(ValueType::String), is_none, "String"),
        vr,
        nvr,
        value,
        |_| std::ptr::null(),
    )
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2SetReal(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const Real,
) -> Status {
    set_values(
        c,
        access(Call::Set(ValueType::Float64), is_real, "Real"),
        vr,
        nvr,
        value,
        |x| x,
    )
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2SetInteger(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const Integer,
) -> Status {
    set_values(
        c,
        access(
            Call::Set(ValueType::Int32),
            is_integer_or_switch,
            "Integer or Enumeration",
        ),
        vr,
        nvr,
        value,
        f64::from,
    )
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no Boolean variables.
pub unsafe extern "C" fn fmi2SetBoolean(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const Boolean,
) -> Status {
    set_values(
        c,
        access(Call::Set(ValueType::Boolean), is_none, "Boolean"),
        vr,
        nvr,
        value,
        f64::from,
    )
}

/// # Safety
/// Arrays of `nvr` elements; this FMU has no String variables.
pub unsafe extern "C" fn fmi2SetString(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    value: *const FmiString,
) -> Status {
    set_values(
        c,
        access(Call::Set(ValueType::String), is_none, "String"),
        vr,
        nvr,
        value,
        |_| 0.0,
    )
}

/// Takes a snapshot into `*state` (a new one if `*state` is NULL, else overwriting one this
/// instance handed out).
///
/// # Safety
/// `state` points to an fmi2FMUstate.
pub unsafe extern "C" fn fmi2GetFMUstate(c: Component, state: *mut FmuState) -> Status {
    states::get(c as usize, &FMI2, state).into()
}

/// # Safety
/// `state` from fmi2GetFMUstate.
pub unsafe extern "C" fn fmi2SetFMUstate(c: Component, state: FmuState) -> Status {
    states::set(c as usize, &FMI2, state).into()
}

/// # Safety
/// `state` points to an fmi2FMUstate from this instance.
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Component, state: *mut FmuState) -> Status {
    states::free(c as usize, &FMI2, state).into()
}

/// # Safety
/// `state` from fmi2GetFMUstate; `size` points to a size_t.
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: Component,
    state: FmuState,
    size: *mut usize,
) -> Status {
    states::serialized_size(c as usize, &FMI2, state, size).into()
}

/// # Safety
/// `bytes` has room for `size` bytes.
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Component,
    state: FmuState,
    bytes: *mut Byte,
    size: usize,
) -> Status {
    states::serialize(c as usize, &FMI2, state, bytes as *mut u8, size).into()
}

/// # Safety
/// `bytes` holds `size` bytes; `state` points to an fmi2FMUstate.
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Component,
    bytes: *const Byte,
    size: usize,
    state: *mut FmuState,
) -> Status {
    states::deserialize(c as usize, &FMI2, bytes as *const u8, size, state).into()
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: Component,
    _unknown: *const ValueReference,
    _n_unknown: usize,
    _known: *const ValueReference,
    _n_known: usize,
    _dv_known: *const Real,
    _dv_unknown: *mut Real,
) -> Status {
    with_instance(c, |instance| {
        // A call in the wrong state is refused as such first, naming the state.
        instance.unsupported(
            Call::GetDirectionalDerivative,
            "fmi2GetDirectionalDerivative is not supported (providesDirectionalDerivative = false)",
        )
    })
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    order: *const Integer,
    value: *const Real,
) -> Status {
    with_instance(c, |instance| {
        let (Some(vrs), Some(orders), Some(values)) =
            (slice(vr, nvr), slice(order, nvr), slice(value, nvr))
        else {
            return instance.null_argument(Call::SetRealInputDerivatives, "vr, order or value");
        };
        instance.trace(|| format!("fmi2SetRealInputDerivatives(vr = {vrs:?}, order = {orders:?})"));
        instance.set_input_derivatives(vrs, orders, values)
    })
}

/// # Safety
/// Arrays of `nvr` elements, as the FMI 2.0 standard defines them.
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: Component,
    vr: *const ValueReference,
    nvr: usize,
    order: *const Integer,
    value: *mut Real,
) -> Status {
    with_instance(c, |instance| {
        let (Some(vrs), Some(orders), Some(out)) =
            (slice(vr, nvr), slice(order, nvr), slice_mut(value, nvr))
        else {
            return instance.null_argument(Call::GetRealOutputDerivatives, "vr, order or value");
        };
        instance.get_output_derivatives(vrs, orders, out)
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2DoStep(
    c: Component,
    current_communication_point: Real,
    communication_step_size: Real,
    _no_set_prior_state: Boolean,
) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| {
            format!("fmi2DoStep(t = {current_communication_point}, h = {communication_step_size})")
        });
        instance.do_step(current_communication_point, communication_step_size)
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2CancelStep(c: Component) -> Status {
    with_instance(c, |instance| {
        // No step is ever pending: the phase check refuses it in every phase.
        instance
            .check_phase(Call::CancelStep)
            .err()
            .unwrap_or(Outcome::Ok)
    })
}

/// # Safety
/// `value` points to an fmi2Status.
pub unsafe extern "C" fn fmi2GetStatus(c: Component, kind: c_int, value: *mut Status) -> Status {
    with_instance(c, |instance| {
        if let Err(status) = instance.check_phase(Call::GetStatus) {
            return status;
        }
        let Some(value) = value.as_mut() else {
            return instance.null_argument(Call::GetStatus, "value");
        };
        if kind != DO_STEP_STATUS {
            return instance.error(&format!("fmi2GetStatus: status kind {kind} is not an fmi2Status kind: expected fmi2DoStepStatus ({DO_STEP_STATUS})"));
        }
        // Steps are synchronous: the status of the last one is all there is to tell.
        *value = if instance.step_discarded() {
            Status::Discard
        } else {
            Status::Ok
        };
        Outcome::Ok
    })
}

/// # Safety
/// `value` points to an fmi2Real.
pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: c_int, value: *mut Real) -> Status {
    with_instance(c, |instance| {
        if let Err(status) = instance.check_phase(Call::GetRealStatus) {
            return status;
        }
        let Some(value) = value.as_mut() else {
            return instance.null_argument(Call::GetRealStatus, "value");
        };
        if kind != LAST_SUCCESSFUL_TIME {
            return instance.error(&format!("fmi2GetRealStatus: status kind {kind}: expected fmi2LastSuccessfulTime ({LAST_SUCCESSFUL_TIME})"));
        }
        *value = instance.last_successful_time();
        Outcome::Ok
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: Component,
    kind: c_int,
    _value: *mut Integer,
) -> Status {
    with_instance(c, |instance| {
        instance.unsupported(
            Call::GetIntegerStatus,
            &format!(
                "fmi2GetIntegerStatus: status kind {kind}: no Integer status is defined by FMI 2.0"
            ),
        )
    })
}

/// # Safety
/// `value` points to an fmi2Boolean.
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: Component,
    kind: c_int,
    value: *mut Boolean,
) -> Status {
    with_instance(c, |instance| {
        if let Err(status) = instance.check_phase(Call::GetBooleanStatus) {
            return status;
        }
        let Some(value) = value.as_mut() else {
            return instance.null_argument(Call::GetBooleanStatus, "value");
        };
        if kind != TERMINATED {
            return instance.error(&format!(
                "fmi2GetBooleanStatus: status kind {kind}: expected fmi2Terminated ({TERMINATED})"
            ));
        }
        // The slave asks to end once it has reached the stop time, or has ended.
        *value = if instance.asks_to_end() { TRUE } else { FALSE };
        Outcome::Ok
    })
}

/// # Safety
/// `c` from fmi2Instantiate.
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: Component,
    kind: c_int,
    _value: *mut FmiString,
) -> Status {
    with_instance(c, |instance| {
        instance.unsupported(
            Call::GetStringStatus,
            &format!(
                "fmi2GetStringStatus: status kind {kind}: fmi2PendingStatus ({PENDING_STATUS}) is the only one, and no step is ever pending here"
            ),
        )
    })
}
