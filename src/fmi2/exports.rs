//! Every FMI 2.0 common and co-simulation function, exported with its C name.
//!
//! Each one: find the instance (a handle this library handed out and has not freed, else a
//! refusal instead of a crash), turn pointers into slices, dispatch to [`Instance`], turn its
//! outcome into an fmi2Status. They carry their C names; [`super::binary`]'s macro exports them
//! under those names.
#![allow(non_snake_case)]

use super::binary::Binary;
use super::dialect::FMI2;
use super::ffi::*;
use super::logger::Logger;
use crate::instance::calls::{Call, ValueType};
use crate::instance::log::CATEGORY_ERROR;
use crate::instance::{handles, snapshot, Instance, Status as Outcome};
use crate::models::Model;
use crate::variables::variable::Kind;
use crate::variant::registry::Loaded;
use std::ffi::{c_int, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Arc;

/// Runs `body` on the live FMI 2.0 instance `c` names (see [`handles::with_instance`]).
fn with_instance(c: Component, body: impl FnOnce(&mut Instance) -> Outcome) -> Status {
    handles::with_instance(c as usize, &FMI2, body).into()
}

/// A borrowed C string, or None for NULL or invalid UTF-8.
unsafe fn text<'a>(s: FmiString) -> Option<&'a str> {
    if s.is_null() {
        None
    } else {
        CStr::from_ptr(s).to_str().ok()
    }
}

/// A slice from a pointer and a length; NULL is only acceptable for an empty slice.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    if n == 0 {
        Some(&[])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts(p, n))
    }
}

unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    if n == 0 {
        Some(&mut [])
    } else if p.is_null() {
        None
    } else {
        Some(std::slice::from_raw_parts_mut(p, n))
    }
}

pub extern "C" fn fmi2GetTypesPlatform() -> FmiString {
    c"default".as_ptr()
}

pub extern "C" fn fmi2GetVersion() -> FmiString {
    c"2.0".as_ptr()
}

/// The model and GUID an fmuGUID names among what `binary` carries: a full model's, or else a
/// variant FMU's, whose resources/variant.toml must describe an interface with that GUID.
fn model_of_guid(
    binary: &Binary,
    guid: &str,
    resource_location: Option<&str>,
) -> Result<(&'static Model, &'static str, Option<Arc<Loaded>>), String> {
    let full: Vec<(&'static Model, &'static str)> = if binary.full_models {
        binary
            .models
            .iter()
            .filter_map(|m| super::guid(m.table.model_identifier).map(|g| (m, g)))
            .collect()
    } else {
        Vec::new()
    };
    if let Some(&(model, guid)) = full.iter().find(|(_, g)| *g == guid) {
        return Ok((model, guid, None));
    }
    let known: Vec<String> = full
        .iter()
        .map(|(m, g)| format!("{g} ({})", m.table.model_identifier))
        .collect();
    let this = if known.is_empty() {
        "this binary is a variant FMU's: expected the GUID of the variant in its resources"
            .to_string()
    } else {
        format!(
            "expected {} (is the modelDescription.xml from another build, or another FMU's?)",
            known.join(" or ")
        )
    };
    let Some(variants) = binary.variants else {
        return Err(format!(
            "fmuGUID \"{guid}\" matches no model of this binary: {this}"
        ));
    };
    variants(guid, resource_location, binary.models)
        // A variant's instance takes its GUID from the file.
        .map(|loaded| (loaded.variant.model, "", Some(loaded)))
        .map_err(|why| format!("fmuGUID \"{guid}\" matches no model of this binary: {this}; {why}"))
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
        let (model, guid, variant) = match model_of_guid(binary, guid, location) {
            Ok(found) => found,
            Err(message) => return refuse(message),
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
    with_instance(c, |instance| {
        let Some(categories) = slice(categories, n_categories) else {
            return instance.null_argument(Call::SetDebugLogging, "categories");
        };
        let mut names = Vec::with_capacity(categories.len());
        for &category in categories {
            match text(category) {
                Some(name) => names.push(name.to_string()),
                None => return instance.null_argument(Call::SetDebugLogging, "a category name"),
            }
        }
        instance.set_debug_logging(logging_on != FALSE, &names)
    })
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

fn is_real(kind: &Kind) -> bool {
    matches!(kind, Kind::Real { .. })
}

fn is_integer(kind: &Kind) -> bool {
    matches!(kind, Kind::Integer { .. } | Kind::Switch { .. })
}

fn is_none(_: &Kind) -> bool {
    false
}

/// Which variables an FMI getter or setter reaches, and its name for messages.
#[derive(Clone, Copy)]
struct Access {
    call: Call,
    accepts: fn(&Kind) -> bool,
    type_name: &'static str,
}

const fn access(call: Call, accepts: fn(&Kind) -> bool, type_name: &'static str) -> Access {
    Access {
        call,
        accepts,
        type_name,
    }
}

/// Shared body of the getters: `convert` writes the f64 values into the C array.
unsafe fn get_values<T>(
    c: Component,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *mut T,
    convert: fn(f64) -> T,
) -> Status {
    let Access {
        call,
        accepts,
        type_name,
    } = access;
    with_instance(c, |instance| {
        let (Some(vrs), Some(out)) = (slice(vr, nvr), slice_mut(value, nvr)) else {
            return instance.null_argument(call, "vr or value");
        };
        instance.get(
            call,
            vrs,
            &mut |i, x| out[i] = convert(x),
            accepts,
            type_name,
        )
    })
}

/// Shared body of the setters: `convert` reads the C array as f64 values.
unsafe fn set_values<T: Copy>(
    c: Component,
    access: Access,
    vr: *const ValueReference,
    nvr: usize,
    value: *const T,
    convert: fn(T) -> f64,
) -> Status {
    let Access {
        call,
        accepts,
        type_name,
    } = access;
    with_instance(c, |instance| {
        let function = instance.function(call);
        let (Some(vrs), Some(values)) = (slice(vr, nvr), slice(value, nvr)) else {
            return instance.null_argument(call, "vr or value");
        };
        instance.trace(|| format!("{function}(vr = {vrs:?})"));
        instance.set(call, vrs, &|i| convert(values[i]), accepts, type_name)
    })
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
            is_integer,
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
            is_integer,
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

/// The address of the FMU state a slot holds, None for NULL (a new state).
unsafe fn slot_address(slot: &FmuState) -> Option<usize> {
    (!slot.is_null()).then_some(*slot as usize)
}

/// Takes a snapshot into `*state` (a new one if `*state` is NULL, else overwriting one this
/// instance handed out).
///
/// # Safety
/// `state` points to an fmi2FMUstate.
pub unsafe extern "C" fn fmi2GetFMUstate(c: Component, state: *mut FmuState) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| "fmi2GetFMUstate()".into());
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::GetFMUstate, "FMUstate");
        };
        match instance.get_state(slot_address(slot)) {
            Ok(address) => {
                *slot = address as FmuState;
                Outcome::Ok
            }
            Err(status) => status,
        }
    })
}

/// # Safety
/// `state` from fmi2GetFMUstate.
pub unsafe extern "C" fn fmi2SetFMUstate(c: Component, state: FmuState) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| format!("fmi2SetFMUstate({state:?})"));
        instance.set_state(state as usize)
    })
}

/// # Safety
/// `state` points to an fmi2FMUstate from this instance.
pub unsafe extern "C" fn fmi2FreeFMUstate(c: Component, state: *mut FmuState) -> Status {
    with_instance(c, |instance| {
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::FreeFMUstate, "FMUstate");
        };
        let Some(address) = slot_address(slot) else {
            return instance
                .check_phase(Call::FreeFMUstate)
                .err()
                .unwrap_or(Outcome::Ok);
        };
        let status = instance.free_state(address);
        if status == Outcome::Ok {
            *slot = std::ptr::null_mut();
        }
        status
    })
}

/// # Safety
/// `state` from fmi2GetFMUstate; `size` points to a size_t.
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: Component,
    state: FmuState,
    size: *mut usize,
) -> Status {
    with_instance(c, |instance| {
        let Some(size) = size.as_mut() else {
            return instance.null_argument(Call::SerializedFMUstateSize, "size");
        };
        match instance.serialized_state_size(state as usize) {
            Ok(length) => {
                *size = length;
                Outcome::Ok
            }
            Err(status) => status,
        }
    })
}

/// # Safety
/// `bytes` has room for `size` bytes.
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: Component,
    state: FmuState,
    bytes: *mut Byte,
    size: usize,
) -> Status {
    with_instance(c, |instance| {
        let data = match instance.serialize_state(state as usize, size) {
            Ok(data) => data,
            Err(status) => return status,
        };
        let Some(out) = slice_mut(bytes as *mut u8, data.len()) else {
            return instance.null_argument(Call::SerializeFMUstate, "serializedState");
        };
        out.copy_from_slice(&data);
        Outcome::Ok
    })
}

/// # Safety
/// `bytes` holds `size` bytes; `state` points to an fmi2FMUstate.
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: Component,
    bytes: *const Byte,
    size: usize,
    state: *mut FmuState,
) -> Status {
    with_instance(c, |instance| {
        instance.trace(|| format!("fmi2DeSerializeFMUstate(size = {size})"));
        // The header first: a size beyond the length it declares is refused before the data
        // is read that far.
        let Some(header) = slice(bytes as *const u8, size.min(snapshot::HEADER)) else {
            return instance.null_argument(Call::DeSerializeFMUstate, "serializedState");
        };
        if let Err(status) = instance.check_serialized_header(header, size) {
            return status;
        }
        let Some(data) = slice(bytes as *const u8, size) else {
            return instance.null_argument(Call::DeSerializeFMUstate, "serializedState");
        };
        let Some(slot) = state.as_mut() else {
            return instance.null_argument(Call::DeSerializeFMUstate, "FMUstate");
        };
        match instance.deserialize_state(data, slot_address(slot)) {
            Ok(address) => {
                *slot = address as FmuState;
                Outcome::Ok
            }
            Err(status) => status,
        }
    })
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
