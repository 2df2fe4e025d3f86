//! A safe, in-process FMI 2.0 importer: calls this crate's exported `fmi2*` functions directly,
//! the way a co-simulation master calls them through `dlsym`, without loading a shared library.
//!
//! It exists so that tests, fuzzers and benchmarks can drive an FMU from safe code (its own
//! `unsafe` is the calls into `src/fmi2/`, which validates every pointer). Each
//! [`ImportedInstance`] owns one FMU instance, as a master sees it, and the log of the messages
//! that instance sent to its logger; `&mut self` on every call gives the FMI rule "one instance
//! is never called from two threads at once" for free.
//!
//! Besides the well-behaved calls, the driver offers the ill-behaved ones an importer can make:
//! arbitrary value references, FMU states as bare addresses ([`State::from_address`]), buffers
//! too small, NULL arrays ([`ImportedInstance::call_with_null`]), calls after
//! `fmi2FreeInstance`, a second `fmi2FreeInstance` ([`ImportedInstance::free_twice`]), calls on
//! NULL ([`calls_on_null_component`]).
//! They stay memory-safe because the FMU validates every pointer against the lists of instances
//! and states it handed out; that validation is what such calls test.
//!
//! [`fmi3`] is the same for the FMI 3.0 functions.
//!
//! Built only for Linux on x86-64 and aarch64: see the logger (`record`) for why.
#![cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]

use crate::fmi2::exports::*;
use crate::fmi2::ffi::{self, CallbackFunctions, CallbackLogger, FmuState, Status};
use crate::instance::library::Binary;
use c_strings::{c_pointer, c_strings, c_text, lossy};
use messages::{no_model, Sink};
use state::{ok_then, serialized};
use std::ffi::{c_char, c_int, c_void};
use std::sync::{Mutex, MutexGuard};

mod c_strings;
pub mod fmi3;
mod messages;
mod state;

pub use messages::Message;
pub use state::State;

/// The logger, with the FMI signature's variadic tail spelled as the one `const char*` argument
/// this FMU ever passes (it always logs with the format "%s"; see `logger.rs`).
///
/// Stable Rust cannot define a variadic function, so [`logger`] transmutes this one to the
/// variadic [`CallbackLogger`] type. That is sound where a variadic callee finds its variadic
/// arguments exactly where a non-variadic callee finds the same fixed arguments: the System V
/// x86-64 and the AAPCS64 (Linux) calling conventions, to which the driver is restricted below.
/// It is not so on Apple arm64 or Windows x64, where variadic arguments go elsewhere. The C
/// logger of the `fmi` dev-dependency is not an option: this module is part of the library, which
/// other library code (the `report` command) uses too, and dev-dependencies are not linked there.
extern "C" fn record(
    environment: *mut c_void,
    _instance_name: *const c_char,
    status: c_int,
    category: *const c_char,
    format: *const c_char,
    argument: *const c_char,
) {
    if environment.is_null() {
        return;
    }
    // Read the variadic argument only when the format says there is one.
    let format_text = lossy(format);
    let text = if format_text == "%s" {
        lossy(argument)
    } else {
        format_text
    };
    // SAFETY: the environment is the address of the `Sink` of the `ImportedInstance` that owns
    // this FMU instance; the sink outlives the FMU instance (freed in `Drop` before the sink).
    let sink = unsafe { &*(environment as *const Sink) };
    sink.lock().push(Message {
        status,
        category: lossy(category),
        text,
    });
}

fn logger() -> CallbackLogger {
    type Fixed = extern "C" fn(
        *mut c_void,
        *const c_char,
        c_int,
        *const c_char,
        *const c_char,
        *const c_char,
    );
    // SAFETY: see `record`: on these targets a variadic call with one pointer argument after
    // the format passes it exactly as the sixth fixed pointer argument; fmi2Status is a C int.
    unsafe { std::mem::transmute::<Fixed, CallbackLogger>(record as Fixed) }
}

/// Serialises instantiation with [`ImportedInstance::free_twice`], so that between the two frees
/// no other driver instance can be allocated at the address just freed (the second free would
/// end it).
static ALLOCATION: Mutex<()> = Mutex::new(());

fn allocation() -> MutexGuard<'static, ()> {
    ALLOCATION.lock().unwrap_or_else(|e| e.into_inner())
}

/// Which argument [`ImportedInstance::call_with_null`] passes as NULL, and to which function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NullArgument {
    /// fmi2GetReal with one value reference and a NULL value array.
    GetRealValues,
    /// fmi2SetReal with one value reference and a NULL value array.
    SetRealValues,
    /// fmi2GetReal with a NULL value-reference array of length 1.
    GetRealReferences,
    /// fmi2SetDebugLogging with one category and a NULL category array.
    DebugLoggingCategories,
    /// fmi2GetFMUstate with a NULL `FMUstate*`.
    GetFmuStateSlot,
    /// fmi2FreeFMUstate with a NULL `FMUstate*`.
    FreeFmuStateSlot,
    /// fmi2SerializedFMUstateSize of `state` with a NULL `size*`.
    SerializedSizeOut(State),
    /// fmi2SerializeFMUstate of `state` with a NULL buffer of size 1000.
    SerializeBuffer(State),
    /// fmi2DeSerializeFMUstate with NULL bytes of size 8.
    DeserializeBytes,
    /// fmi2DeSerializeFMUstate of valid-length bytes into a NULL `FMUstate*`.
    DeserializeSlot,
    /// fmi2GetStatus(fmi2DoStepStatus) with a NULL value.
    GetStatusValue,
    /// fmi2GetRealStatus(fmi2LastSuccessfulTime) with a NULL value.
    GetRealStatusValue,
    /// fmi2GetBooleanStatus(fmi2Terminated) with a NULL value.
    GetBooleanStatusValue,
}

/// Arguments of `fmi2Instantiate`, each of which may be made wrong on purpose.
#[derive(Clone, Debug)]
pub struct Instantiation {
    /// None passes NULL.
    pub instance_name: Option<String>,
    /// 1 is fmi2CoSimulation.
    pub fmu_type: i32,
    /// None passes NULL.
    pub guid: Option<String>,
    /// None passes NULL.
    pub resource_location: Option<String>,
    pub logging_on: bool,
}

impl Instantiation {
    /// The right arguments for `model_identifier` (its GUID), named `instance_name`; None for a
    /// model this binary does not contain.
    pub fn new(model_identifier: &str, instance_name: &str) -> Option<Instantiation> {
        Some(Instantiation {
            instance_name: Some(instance_name.to_string()),
            fmu_type: ffi::CO_SIMULATION,
            guid: Some(crate::fmi2::guid(model_identifier)?.to_string()),
            resource_location: None,
            logging_on: false,
        })
    }
}

/// One FMU instance of this crate, called in-process, with its log.
///
/// Dropping it frees the FMU instance (and, through the FMU, every state it still holds).
pub struct ImportedInstance {
    /// The address fmi2Instantiate returned; after a free, the address of `sink` instead, which
    /// can never be an instance's, so later calls exercise the FMU's "not an instance" refusal
    /// without the risk of reaching an instance allocated since at the freed address.
    component: usize,
    freed: bool,
    sink: Box<Sink>,
}

// SAFETY: FMI 2.0 lets an instance be called from any thread as long as calls on it do not
// overlap; `&mut self` on every call guarantees that, and the FMU instance holds no thread-bound
// data (simulations are `Send`, the logger environment is this instance's own `Sink`).
unsafe impl Send for ImportedInstance {}

impl ImportedInstance {
    /// Instantiates `model_identifier` as a co-simulation slave named `instance_name`.
    /// The error is the log of the refusal (empty if the FMU could not log at all).
    pub fn new(
        model_identifier: &str,
        instance_name: &str,
    ) -> Result<ImportedInstance, Vec<Message>> {
        match Instantiation::new(model_identifier, instance_name) {
            Some(arguments) => ImportedInstance::instantiate(&arguments),
            None => Err(no_model(model_identifier, Status::Error as i32)),
        }
    }

    /// fmi2Instantiate with the given arguments.
    pub fn instantiate(arguments: &Instantiation) -> Result<ImportedInstance, Vec<Message>> {
        let sink = Box::<Sink>::default();
        let callbacks = CallbackFunctions {
            logger: Some(logger()),
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: &*sink as *const Sink as *mut c_void,
        };
        let name = c_text(&arguments.instance_name);
        let guid = c_text(&arguments.guid);
        let location = c_text(&arguments.resource_location);
        let component = {
            let _allocation = allocation();
            // SAFETY: every pointer is NULL or a live C string / struct for the whole call; the
            // FMU copies what it keeps (the logger and environment stay valid: see `record`).
            unsafe {
                instantiate(
                    &Binary::ALL,
                    c_pointer(&name),
                    arguments.fmu_type,
                    c_pointer(&guid),
                    c_pointer(&location),
                    &callbacks,
                    ffi::FALSE,
                    c_int::from(arguments.logging_on),
                )
            }
        };
        if component.is_null() {
            return Err(sink.take());
        }
        Ok(ImportedInstance {
            component: component as usize,
            freed: false,
            sink,
        })
    }

    fn c(&self) -> ffi::Component {
        self.component as ffi::Component
    }

    /// The handle fmi2Instantiate returned; after a free, an address that is no instance's.
    pub fn handle(&self) -> usize {
        self.component
    }

    /// The messages logged so far, oldest first.
    pub fn messages(&self) -> Vec<Message> {
        self.sink.messages()
    }

    /// The text of the last message logged, or "" if none.
    pub fn last_message(&self) -> String {
        self.sink.last_text()
    }

    /// Removes and returns the messages logged so far.
    pub fn take_messages(&mut self) -> Vec<Message> {
        self.sink.take()
    }

    /// Whether fmi2FreeInstance has been called through this driver instance.
    pub fn is_freed(&self) -> bool {
        self.freed
    }

    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        let names = c_strings(categories);
        let pointers: Vec<ffi::FmiString> = names.iter().map(|c| c.as_ptr()).collect();
        // SAFETY: `pointers` holds `len` live C strings.
        unsafe {
            fmi2SetDebugLogging(
                self.c(),
                c_int::from(logging_on),
                pointers.len(),
                pointers.as_ptr(),
            )
        }
    }

    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Status {
        // SAFETY: plain values; the component is validated by the FMU.
        unsafe {
            fmi2SetupExperiment(
                self.c(),
                c_int::from(tolerance.is_some()),
                tolerance.unwrap_or(0.0),
                start_time,
                c_int::from(stop_time.is_some()),
                stop_time.unwrap_or(0.0),
            )
        }
    }

    pub fn enter_initialization_mode(&mut self) -> Status {
        // SAFETY: the component is validated by the FMU.
        unsafe { fmi2EnterInitializationMode(self.c()) }
    }

    pub fn exit_initialization_mode(&mut self) -> Status {
        // SAFETY: as above.
        unsafe { fmi2ExitInitializationMode(self.c()) }
    }

    /// setupExperiment(start 0, no stop), enter and exit initialisation mode: the worst status.
    pub fn initialize(&mut self) -> Status {
        let setup = self.setup_experiment(None, 0.0, None);
        let enter = self.enter_initialization_mode();
        let exit = self.exit_initialization_mode();
        setup.max(enter).max(exit)
    }

    pub fn terminate(&mut self) -> Status {
        // SAFETY: as above.
        unsafe { fmi2Terminate(self.c()) }
    }

    pub fn reset(&mut self) -> Status {
        // SAFETY: as above.
        unsafe { fmi2Reset(self.c()) }
    }

    /// fmi2GetReal into `values`.
    ///
    /// # Panics
    /// If `values` is shorter than `vrs` (a bug in the caller, not an FMI error).
    pub fn get_real_into(&mut self, vrs: &[u32], values: &mut [f64]) -> Status {
        assert!(values.len() >= vrs.len(), "values shorter than vrs");
        // SAFETY: both arrays hold at least `vrs.len()` elements.
        unsafe { fmi2GetReal(self.c(), vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) }
    }

    /// fmi2GetReal; the values are only meaningful when the status is OK.
    pub fn get_real(&mut self, vrs: &[u32]) -> (Status, Vec<f64>) {
        let mut values = vec![0.0; vrs.len()];
        let status = self.get_real_into(vrs, &mut values);
        (status, values)
    }

    /// fmi2GetInteger (also reads Enumerations).
    pub fn get_integer(&mut self, vrs: &[u32]) -> (Status, Vec<i32>) {
        let mut values = vec![0; vrs.len()];
        // SAFETY: both arrays hold `vrs.len()` elements.
        let status =
            unsafe { fmi2GetInteger(self.c(), vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (status, values)
    }

    /// fmi2GetBoolean (fmi2Boolean is a C int: 0 false, else true).
    pub fn get_boolean(&mut self, vrs: &[u32]) -> (Status, Vec<i32>) {
        let mut values = vec![0; vrs.len()];
        // SAFETY: both arrays hold `vrs.len()` elements.
        let status =
            unsafe { fmi2GetBoolean(self.c(), vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (status, values)
    }

    /// fmi2GetString: only the status, as this FMU has no String variables to read.
    pub fn get_string(&mut self, vrs: &[u32]) -> Status {
        let mut values: Vec<ffi::FmiString> = vec![std::ptr::null(); vrs.len()];
        // SAFETY: both arrays hold `vrs.len()` elements.
        unsafe { fmi2GetString(self.c(), vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) }
    }

    /// fmi2SetReal.
    ///
    /// # Panics
    /// If the slices differ in length (a bug in the caller, not an FMI error).
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Status {
        assert_eq!(vrs.len(), values.len(), "one value per value reference");
        // SAFETY: both arrays hold `vrs.len()` elements.
        unsafe { fmi2SetReal(self.c(), vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    /// fmi2SetInteger (also sets Enumerations). Panics as [`ImportedInstance::set_real`].
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Status {
        assert_eq!(vrs.len(), values.len(), "one value per value reference");
        // SAFETY: both arrays hold `vrs.len()` elements.
        unsafe { fmi2SetInteger(self.c(), vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    /// fmi2SetBoolean. Panics as [`ImportedInstance::set_real`].
    pub fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Status {
        assert_eq!(vrs.len(), values.len(), "one value per value reference");
        let values: Vec<ffi::Boolean> = values.iter().map(|&b| c_int::from(b)).collect();
        // SAFETY: both arrays hold `vrs.len()` elements.
        unsafe { fmi2SetBoolean(self.c(), vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    /// fmi2SetString. Panics as [`ImportedInstance::set_real`].
    pub fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Status {
        assert_eq!(vrs.len(), values.len(), "one value per value reference");
        let texts = c_strings(values);
        let pointers: Vec<ffi::FmiString> = texts.iter().map(|t| t.as_ptr()).collect();
        // SAFETY: both arrays hold `vrs.len()` elements; the strings live for the call.
        unsafe { fmi2SetString(self.c(), vrs.as_ptr(), vrs.len(), pointers.as_ptr()) }
    }

    pub fn do_step(
        &mut self,
        current_communication_point: f64,
        communication_step_size: f64,
        no_set_fmu_state_prior: bool,
    ) -> Status {
        // SAFETY: plain values; the component is validated by the FMU.
        unsafe {
            fmi2DoStep(
                self.c(),
                current_communication_point,
                communication_step_size,
                c_int::from(no_set_fmu_state_prior),
            )
        }
    }

    pub fn cancel_step(&mut self) -> Status {
        // SAFETY: the component is validated by the FMU.
        unsafe { fmi2CancelStep(self.c()) }
    }

    /// fmi2GetStatus(kind): the call's status and the status it reported.
    pub fn get_status(&mut self, kind: i32) -> (Status, Status) {
        let mut value = Status::Ok;
        // SAFETY: `value` is a valid fmi2Status to write to.
        let status = unsafe { fmi2GetStatus(self.c(), kind, &mut value) };
        (status, value)
    }

    /// fmi2GetRealStatus(kind), e.g. fmi2LastSuccessfulTime (2).
    pub fn get_real_status(&mut self, kind: i32) -> (Status, f64) {
        let mut value = 0.0;
        // SAFETY: `value` is a valid fmi2Real to write to.
        let status = unsafe { fmi2GetRealStatus(self.c(), kind, &mut value) };
        (status, value)
    }

    pub fn get_integer_status(&mut self, kind: i32) -> (Status, i32) {
        let mut value = 0;
        // SAFETY: `value` is a valid fmi2Integer to write to.
        let status = unsafe { fmi2GetIntegerStatus(self.c(), kind, &mut value) };
        (status, value)
    }

    /// fmi2GetBooleanStatus(kind), e.g. fmi2Terminated (3).
    pub fn get_boolean_status(&mut self, kind: i32) -> (Status, bool) {
        let mut value = ffi::FALSE;
        // SAFETY: `value` is a valid fmi2Boolean to write to.
        let status = unsafe { fmi2GetBooleanStatus(self.c(), kind, &mut value) };
        (status, value != ffi::FALSE)
    }

    pub fn get_string_status(&mut self, kind: i32) -> Status {
        let mut value: ffi::FmiString = std::ptr::null();
        // SAFETY: `value` is a valid fmi2String to write to.
        unsafe { fmi2GetStringStatus(self.c(), kind, &mut value) }
    }

    /// fmi2GetFMUstate into a new state.
    pub fn get_fmu_state(&mut self) -> Result<State, Status> {
        let mut state = State::NULL;
        let status = self.update_fmu_state(&mut state);
        ok_then(status, Status::Ok, state)
    }

    /// fmi2GetFMUstate into `state`: a new one if it is NULL, else the FMU overwrites it (if it
    /// is one of this instance's) or refuses.
    pub fn update_fmu_state(&mut self, state: &mut State) -> Status {
        // SAFETY: `slot` is a valid fmi2FMUstate to write to; its value is validated by the FMU.
        state.through(|slot| unsafe { fmi2GetFMUstate(self.c(), slot) })
    }

    pub fn set_fmu_state(&mut self, state: State) -> Status {
        // SAFETY: the FMU only dereferences states in this instance's list.
        unsafe { fmi2SetFMUstate(self.c(), state.pointer()) }
    }

    /// fmi2FreeFMUstate; on success `state` becomes NULL.
    pub fn free_fmu_state(&mut self, state: &mut State) -> Status {
        // SAFETY: as for `update_fmu_state`.
        state.through(|slot| unsafe { fmi2FreeFMUstate(self.c(), slot) })
    }

    pub fn serialized_fmu_state_size(&mut self, state: State) -> (Status, usize) {
        let mut size = 0;
        // SAFETY: `size` is a valid size_t; the state is validated by the FMU.
        let status = unsafe { fmi2SerializedFMUstateSize(self.c(), state.pointer(), &mut size) };
        (status, size)
    }

    /// fmi2SerializeFMUstate into `buffer`, passing its length as the size.
    pub fn serialize_fmu_state_into(&mut self, state: State, buffer: &mut [u8]) -> Status {
        // SAFETY: `buffer` has room for the size passed.
        unsafe {
            fmi2SerializeFMUstate(
                self.c(),
                state.pointer(),
                buffer.as_mut_ptr() as *mut ffi::Byte,
                buffer.len(),
            )
        }
    }

    /// fmi2SerializedFMUstateSize, then fmi2SerializeFMUstate into a buffer of that size.
    pub fn serialize_fmu_state(&mut self, state: State) -> Result<Vec<u8>, Status> {
        let size = self.serialized_fmu_state_size(state);
        serialized(Status::Ok, size, |bytes| {
            self.serialize_fmu_state_into(state, bytes)
        })
    }

    /// fmi2DeSerializeFMUstate into a new state.
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<State, Status> {
        let mut state = State::NULL;
        let status = self.deserialize_fmu_state_into(bytes, &mut state);
        ok_then(status, Status::Ok, state)
    }

    /// fmi2DeSerializeFMUstate into `state` (overwritten if it is one of this instance's).
    pub fn deserialize_fmu_state_into(&mut self, bytes: &[u8], state: &mut State) -> Status {
        let bytes_pointer = bytes.as_ptr() as *const ffi::Byte;
        // SAFETY: `bytes` holds the size passed; `slot` as for `update_fmu_state`.
        state.through(|slot| unsafe {
            fmi2DeSerializeFMUstate(self.c(), bytes_pointer, bytes.len(), slot)
        })
    }

    /// fmi2GetDirectionalDerivative of `unknowns` with respect to `knowns` (seeded with `seed`).
    pub fn get_directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
    ) -> (Status, Vec<f64>) {
        assert_eq!(knowns.len(), seed.len(), "one seed per known");
        let mut values = vec![0.0; unknowns.len()];
        // SAFETY: every array holds the length passed with it.
        let status = unsafe {
            fmi2GetDirectionalDerivative(
                self.c(),
                unknowns.as_ptr(),
                unknowns.len(),
                knowns.as_ptr(),
                knowns.len(),
                seed.as_ptr(),
                values.as_mut_ptr(),
            )
        };
        (status, values)
    }

    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Status {
        assert!(orders.len() == vrs.len() && values.len() == vrs.len());
        // SAFETY: every array holds `vrs.len()` elements.
        unsafe {
            fmi2SetRealInputDerivatives(
                self.c(),
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_ptr(),
            )
        }
    }

    pub fn get_real_output_derivatives(&mut self, vrs: &[u32], orders: &[i32]) -> Status {
        assert_eq!(orders.len(), vrs.len(), "one order per value reference");
        let mut values = vec![0.0; vrs.len()];
        // SAFETY: every array holds `vrs.len()` elements.
        unsafe {
            fmi2GetRealOutputDerivatives(
                self.c(),
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_mut_ptr(),
            )
        }
    }

    /// Calls one function with one pointer argument NULL (see [`NullArgument`]).
    pub fn call_with_null(&mut self, which: NullArgument) -> Status {
        use NullArgument::*;
        let c = self.c();
        let vr = [0_u32];
        let null_state = std::ptr::null_mut();
        // SAFETY: every non-NULL pointer is valid for the length passed with it; the NULL one is
        // the FMU's to refuse (it must check it before any use).
        unsafe {
            match which {
                GetRealValues => fmi2GetReal(c, vr.as_ptr(), 1, std::ptr::null_mut()),
                SetRealValues => fmi2SetReal(c, vr.as_ptr(), 1, std::ptr::null()),
                GetRealReferences => {
                    let mut value = [0.0];
                    fmi2GetReal(c, std::ptr::null(), 1, value.as_mut_ptr())
                }
                DebugLoggingCategories => fmi2SetDebugLogging(c, ffi::TRUE, 1, std::ptr::null()),
                GetFmuStateSlot => fmi2GetFMUstate(c, null_state),
                FreeFmuStateSlot => fmi2FreeFMUstate(c, null_state),
                SerializedSizeOut(state) => {
                    fmi2SerializedFMUstateSize(c, state.pointer(), std::ptr::null_mut())
                }
                SerializeBuffer(state) => {
                    fmi2SerializeFMUstate(c, state.pointer(), std::ptr::null_mut(), 1000)
                }
                DeserializeBytes => {
                    let mut slot: FmuState = std::ptr::null_mut();
                    fmi2DeSerializeFMUstate(c, std::ptr::null(), 8, &mut slot)
                }
                DeserializeSlot => {
                    let bytes = [0_u8; 64];
                    fmi2DeSerializeFMUstate(
                        c,
                        bytes.as_ptr() as *const ffi::Byte,
                        bytes.len(),
                        null_state,
                    )
                }
                GetStatusValue => fmi2GetStatus(c, ffi::DO_STEP_STATUS, std::ptr::null_mut()),
                GetRealStatusValue => {
                    fmi2GetRealStatus(c, ffi::LAST_SUCCESSFUL_TIME, std::ptr::null_mut())
                }
                GetBooleanStatusValue => {
                    fmi2GetBooleanStatus(c, ffi::TERMINATED, std::ptr::null_mut())
                }
            }
        }
    }

    /// fmi2FreeInstance. Later calls through this driver instance (including `free` again) go
    /// to an address that is no instance, which the FMU must refuse.
    pub fn free(&mut self) {
        // SAFETY: a live instance of this driver, or (after a free) an address that never is one.
        unsafe { fmi2FreeInstance(self.c()) };
        self.retire();
    }

    /// fmi2FreeInstance, after which this driver instance goes on calling with the freed handle,
    /// as a buggy importer would.
    pub fn free_keeping_the_handle(&mut self) {
        // SAFETY: as for `free`; later calls with the handle must be refused by the FMU.
        unsafe { fmi2FreeInstance(self.c()) };
        self.freed = true;
    }

    /// fmi2FreeInstance twice on the same address, as a buggy importer would.
    pub fn free_twice(&mut self) {
        // Hold the allocation lock so no driver instance can be created at this address between
        // the two frees (the second would then end it).
        let _allocation = allocation();
        // SAFETY: as for `free`; the second call meets an address no longer listed as live.
        unsafe {
            fmi2FreeInstance(self.c());
            fmi2FreeInstance(self.c());
        }
        self.retire();
    }

    fn retire(&mut self) {
        self.freed = true;
        self.component = &*self.sink as *const Sink as usize;
    }
}

impl Drop for ImportedInstance {
    fn drop(&mut self) {
        if !self.freed {
            self.free();
        }
    }
}

/// fmi2GetVersion.
pub fn version() -> String {
    lossy(fmi2GetVersion())
}

/// fmi2GetTypesPlatform.
pub fn types_platform() -> String {
    lossy(fmi2GetTypesPlatform())
}

/// fmi2FreeInstance(NULL), which the FMU must ignore.
pub fn free_null_instance() {
    free_foreign_component(0);
}

/// fmi2FreeInstance on `component`, which is no live FMI 2.0 instance (NULL, made up, an FMI 3.0
/// instance's): the FMU must ignore it.
pub fn free_foreign_component(component: usize) {
    // SAFETY: the handle is looked up by the FMU, never dereferenced.
    unsafe { fmi2FreeInstance(component as ffi::Component) }
}

/// Calls every function that takes an instance with instance = NULL; returns each function's name
/// and status (nothing can be logged: without an instance there is no logger).
pub fn calls_on_null_component() -> Vec<(&'static str, Status)> {
    calls_on_component(0)
}

/// Calls every function that takes an instance, except fmi2FreeInstance, on `component`: each
/// function's name and status. Meant for handles that are no live FMI 2.0 instance (NULL, made
/// up, an FMI 3.0 instance's), which the FMU must refuse before touching anything else.
pub fn calls_on_component(component: usize) -> Vec<(&'static str, Status)> {
    let c = component as ffi::Component;
    let vr = [0_u32];
    let mut real = [0.0];
    let mut int = [0];
    let mut status = Status::Ok;
    let mut state: FmuState = std::ptr::null_mut();
    let mut size = 0;
    let mut bytes = [0_u8; 8];
    let mut string: ffi::FmiString = std::ptr::null();
    let mut strings = [std::ptr::null::<c_char>()];
    // SAFETY: every pointer is valid for the length passed; the FMU looks the handle up and must
    // refuse it before touching anything else.
    unsafe {
        vec![
            (
                "fmi2SetDebugLogging",
                fmi2SetDebugLogging(c, ffi::TRUE, 0, std::ptr::null()),
            ),
            (
                "fmi2SetupExperiment",
                fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0),
            ),
            (
                "fmi2EnterInitializationMode",
                fmi2EnterInitializationMode(c),
            ),
            ("fmi2ExitInitializationMode", fmi2ExitInitializationMode(c)),
            ("fmi2Terminate", fmi2Terminate(c)),
            ("fmi2Reset", fmi2Reset(c)),
            (
                "fmi2GetReal",
                fmi2GetReal(c, vr.as_ptr(), 1, real.as_mut_ptr()),
            ),
            (
                "fmi2GetInteger",
                fmi2GetInteger(c, vr.as_ptr(), 1, int.as_mut_ptr()),
            ),
            (
                "fmi2GetBoolean",
                fmi2GetBoolean(c, vr.as_ptr(), 1, int.as_mut_ptr()),
            ),
            (
                "fmi2GetString",
                fmi2GetString(c, vr.as_ptr(), 1, strings.as_mut_ptr()),
            ),
            ("fmi2SetReal", fmi2SetReal(c, vr.as_ptr(), 1, real.as_ptr())),
            (
                "fmi2SetInteger",
                fmi2SetInteger(c, vr.as_ptr(), 1, int.as_ptr()),
            ),
            (
                "fmi2SetBoolean",
                fmi2SetBoolean(c, vr.as_ptr(), 1, int.as_ptr()),
            ),
            (
                "fmi2SetString",
                fmi2SetString(c, vr.as_ptr(), 1, strings.as_ptr()),
            ),
            ("fmi2GetFMUstate", fmi2GetFMUstate(c, &mut state)),
            ("fmi2SetFMUstate", fmi2SetFMUstate(c, state)),
            ("fmi2FreeFMUstate", fmi2FreeFMUstate(c, &mut state)),
            (
                "fmi2SerializedFMUstateSize",
                fmi2SerializedFMUstateSize(c, state, &mut size),
            ),
            (
                "fmi2SerializeFMUstate",
                fmi2SerializeFMUstate(c, state, bytes.as_mut_ptr() as *mut ffi::Byte, 8),
            ),
            (
                "fmi2DeSerializeFMUstate",
                fmi2DeSerializeFMUstate(c, bytes.as_ptr() as *const ffi::Byte, 8, &mut state),
            ),
            (
                "fmi2GetDirectionalDerivative",
                fmi2GetDirectionalDerivative(
                    c,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    real.as_ptr(),
                    real.as_mut_ptr(),
                ),
            ),
            (
                "fmi2SetRealInputDerivatives",
                fmi2SetRealInputDerivatives(c, vr.as_ptr(), 1, int.as_ptr(), real.as_ptr()),
            ),
            (
                "fmi2GetRealOutputDerivatives",
                fmi2GetRealOutputDerivatives(c, vr.as_ptr(), 1, int.as_ptr(), real.as_mut_ptr()),
            ),
            ("fmi2DoStep", fmi2DoStep(c, 0.0, 1.0, ffi::FALSE)),
            ("fmi2CancelStep", fmi2CancelStep(c)),
            (
                "fmi2GetStatus",
                fmi2GetStatus(c, ffi::DO_STEP_STATUS, &mut status),
            ),
            (
                "fmi2GetRealStatus",
                fmi2GetRealStatus(c, ffi::LAST_SUCCESSFUL_TIME, real.as_mut_ptr()),
            ),
            (
                "fmi2GetIntegerStatus",
                fmi2GetIntegerStatus(c, 0, int.as_mut_ptr()),
            ),
            (
                "fmi2GetBooleanStatus",
                fmi2GetBooleanStatus(c, ffi::TERMINATED, int.as_mut_ptr()),
            ),
            (
                "fmi2GetStringStatus",
                fmi2GetStringStatus(c, ffi::PENDING_STATUS, &mut string),
            ),
        ]
    }
}
