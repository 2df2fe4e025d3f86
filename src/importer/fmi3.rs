//! The FMI 3.0 half of the in-process importer: calls this crate's exported `fmi3*` functions
//! directly, as a co-simulation master calls them through `dlsym`, without loading a library.
//!
//! [`ImportedInstance`] owns one FMU instance made by fmi3InstantiateCoSimulation and the log of
//! the messages its logMessage callback received. Besides the well-behaved calls it makes the
//! ill-behaved ones an FMI 3.0 importer can make: any getter or setter with an nValues that does
//! not match ([`ImportedInstance::get`], [`ImportedInstance::set`]), FMU states as bare addresses,
//! NULL arguments ([`ImportedInstance::call_with_null`]), the functions of the interfaces and modes
//! these FMUs leave out ([`ImportedInstance::call_unsupported`]), calls after fmi3FreeInstance,
//! a second fmi3FreeInstance, and every function on a handle that is no live FMI 3.0 instance
//! ([`calls_on_handle`]: NULL, freed, made up, or an FMI 2.0 instance's).
//!
//! A freed instance's handle is kept and used on purpose: the FMU hands out ids that are never
//! reused (src/instance/handles.rs), never addresses, so a freed handle must be refused, also
//! after later instances were made. Every array passed holds the length passed with it, so the
//! calls stay memory-safe as long as the FMU keeps to the C signatures; whether it refuses the
//! rest is what is being tested.

use super::{
    c_pointer, c_strings, c_text, lossy, no_model, ok_then, serialized, Message, Sink, State,
};
use crate::fmi3::exports::*;
use crate::fmi3::ffi::{
    self, BinaryValue, Boolean, FmiInstance, FmiString, FmuState, InstanceEnvironment, Status,
    ValueReference,
};
use crate::instance::calls::ValueType;
use crate::instance::library::Binary;
use std::ffi::{c_char, c_void};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::Mutex;

/// What the intermediateUpdate callback does besides counting: it is handed a driver instance
/// on the handle of the instance being stepped (to call the FMU back from inside fmi3DoStep, as
/// FMI 3.0's intermediate update mode allows for some calls) and the intermediateUpdateTime.
/// That driver instance never frees the FMU instance; what the FMU logs goes to the stepped
/// instance's log.
pub type OnIntermediateUpdate = Box<dyn FnMut(&mut ImportedInstance, f64) + Send>;

/// Where an instance's callbacks write: boxed so that its address, the instanceEnvironment the
/// FMU passes back, stays put while the instance lives.
#[derive(Default)]
struct Environment {
    sink: Sink,
    intermediate_updates: AtomicU64,
    /// The handle of the instance, once instantiated, for `on_update`.
    handle: AtomicUsize,
    on_update: Mutex<Option<OnIntermediateUpdate>>,
}

/// The logMessage callback: FMI 3.0 passes the message as it is, no format string.
unsafe extern "C" fn record(
    environment: InstanceEnvironment,
    status: Status,
    category: FmiString,
    message: FmiString,
) {
    if environment.is_null() {
        return;
    }
    // SAFETY: the environment is the `Environment` of the `ImportedInstance` that owns this FMU
    // instance, which outlives the FMU instance (freed in `Drop` before it).
    let environment = unsafe { &*(environment as *const Environment) };
    environment.sink.lock().push(Message {
        status: status as i32,
        category: lossy(category),
        text: lossy(message),
    });
}

/// The intermediateUpdate callback: counts the calls, runs the instance's
/// [`OnIntermediateUpdate`] if it has one, and never asks for an early return.
#[allow(clippy::too_many_arguments)]
unsafe extern "C" fn intermediate_update(
    environment: InstanceEnvironment,
    time: f64,
    _variable_set_requested: Boolean,
    _variable_get_allowed: Boolean,
    _step_finished: Boolean,
    _can_return_early: Boolean,
    early_return_requested: *mut Boolean,
    _early_return_time: *mut f64,
) {
    if let Some(requested) = early_return_requested.as_mut() {
        *requested = ffi::FALSE;
    }
    let Some(environment) = (environment as *const Environment).as_ref() else {
        return;
    };
    environment
        .intermediate_updates
        .fetch_add(1, Ordering::Relaxed);
    // try_lock: a call made from inside `on_update` that steps again (refused or not) finds the
    // hook busy and only counts.
    let Ok(mut on_update) = environment.on_update.try_lock() else {
        return;
    };
    if let Some(on_update) = on_update.as_mut() {
        let mut borrowed = ImportedInstance::borrowing(environment.handle.load(Ordering::SeqCst));
        // No panic may unwind into the FMU: a panicking hook is a failed test, counted by the
        // test's panic hook.
        let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            on_update(&mut borrowed, time)
        }));
    }
}

/// The three ways FMI 3.0 instantiates; these FMUs implement co-simulation only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interface {
    CoSimulation,
    ModelExchange,
    ScheduledExecution,
}

impl Interface {
    pub fn function(self) -> &'static str {
        match self {
            Interface::CoSimulation => "fmi3InstantiateCoSimulation",
            Interface::ModelExchange => "fmi3InstantiateModelExchange",
            Interface::ScheduledExecution => "fmi3InstantiateScheduledExecution",
        }
    }
}

/// Arguments of the fmi3Instantiate functions, each of which may be made wrong on purpose.
#[derive(Clone, Debug)]
pub struct Instantiation {
    pub interface: Interface,
    /// None passes NULL.
    pub instance_name: Option<String>,
    /// None passes NULL.
    pub instantiation_token: Option<String>,
    /// None passes NULL.
    pub resource_path: Option<String>,
    pub visible: bool,
    pub logging_on: bool,
    pub event_mode_used: bool,
    pub early_return_allowed: bool,
    pub required_intermediate_variables: Vec<ValueReference>,
    /// Whether to pass the logMessage callback (FMI 3.0 allows NULL: the FMU then logs nothing).
    pub log_message: bool,
    /// Whether to pass the intermediateUpdate callback.
    pub intermediate_update: bool,
}

impl Instantiation {
    /// The right co-simulation arguments for `model_identifier` (its instantiation token, the
    /// FMI 2.0 GUID), named `instance_name`; None for a model this binary does not contain.
    pub fn new(model_identifier: &str, instance_name: &str) -> Option<Instantiation> {
        Some(Instantiation {
            interface: Interface::CoSimulation,
            instance_name: Some(instance_name.to_string()),
            instantiation_token: Some(crate::fmi2::guid(model_identifier)?.to_string()),
            resource_path: None,
            visible: false,
            logging_on: false,
            event_mode_used: false,
            early_return_allowed: false,
            required_intermediate_variables: Vec::new(),
            log_message: true,
            intermediate_update: false,
        })
    }
}

/// What fmi3DoStep returned besides its status.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepOutcome {
    pub event_handling_needed: bool,
    pub terminate_simulation: bool,
    pub early_return: bool,
    pub last_successful_time: f64,
}

/// Which argument [`ImportedInstance::call_with_null`] passes as NULL, and to which function.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NullArgument {
    /// fmi3GetFloat64 with one value reference and a NULL value array.
    GetFloat64Values,
    /// fmi3SetFloat64 with one value reference and a NULL value array.
    SetFloat64Values,
    /// fmi3GetFloat64 with a NULL value-reference array of length 1.
    GetFloat64References,
    /// fmi3GetInt64 with one value reference and a NULL value array.
    GetInt64Values,
    /// fmi3SetInt64 with one value reference and a NULL value array.
    SetInt64Values,
    /// fmi3SetString with one value reference and a NULL string in the value array.
    SetStringElement,
    /// fmi3GetBinary with one value reference and NULL valueSizes.
    GetBinarySizes,
    /// fmi3SetDebugLogging with one category and a NULL category array.
    DebugLoggingCategories,
    /// fmi3GetFMUState with a NULL `FMUState*`.
    GetFmuStateSlot,
    /// fmi3FreeFMUState with a NULL `FMUState*`.
    FreeFmuStateSlot,
    /// fmi3SerializedFMUStateSize of `state` with a NULL `size*`.
    SerializedSizeOut(State),
    /// fmi3SerializeFMUState of `state` with a NULL buffer of size 1000.
    SerializeBuffer(State),
    /// fmi3DeserializeFMUState with NULL bytes of size 8.
    DeserializeBytes,
    /// fmi3DeserializeFMUState of 64 bytes into a NULL `FMUState*`.
    DeserializeSlot,
    /// fmi3DoStep with one of its four output pointers (0..=3, in the signature's order) NULL.
    DoStepOutput(u8),
    /// fmi3GetOutputDerivatives with one value reference and NULL orders.
    OutputDerivativeOrders,
    /// fmi3GetOutputDerivatives with one value reference and a NULL value array.
    OutputDerivativeValues,
}

impl NullArgument {
    /// The C function the call goes to.
    pub fn function(self) -> &'static str {
        use NullArgument::*;
        match self {
            GetFloat64Values | GetFloat64References => "fmi3GetFloat64",
            SetFloat64Values => "fmi3SetFloat64",
            GetInt64Values => "fmi3GetInt64",
            SetInt64Values => "fmi3SetInt64",
            SetStringElement => "fmi3SetString",
            GetBinarySizes => "fmi3GetBinary",
            DebugLoggingCategories => "fmi3SetDebugLogging",
            GetFmuStateSlot => "fmi3GetFMUState",
            FreeFmuStateSlot => "fmi3FreeFMUState",
            SerializedSizeOut(_) => "fmi3SerializedFMUStateSize",
            SerializeBuffer(_) => "fmi3SerializeFMUState",
            DeserializeBytes | DeserializeSlot => "fmi3DeserializeFMUState",
            DoStepOutput(_) => "fmi3DoStep",
            OutputDerivativeOrders | OutputDerivativeValues => "fmi3GetOutputDerivatives",
        }
    }
}

/// Declares [`Unsupported`] and its `ALL`, so that the functions are listed once.
macro_rules! unsupported {
    ($($function:ident,)*) => {
        /// The fmi3 functions of the interfaces, modes and features FMI 3.0 declares and these
        /// FMUs leave out (model exchange, scheduled execution, event and configuration modes,
        /// clocks, dependencies, derivatives): each called with valid arrays of one element.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum Unsupported {
            $($function,)*
        }

        impl Unsupported {
            pub const ALL: [Unsupported; [$(stringify!($function)),*].len()] =
                [$(Unsupported::$function),*];
        }
    };
}

unsupported! {
    EnterEventMode,
    GetNumberOfVariableDependencies,
    GetVariableDependencies,
    GetDirectionalDerivative,
    GetAdjointDerivative,
    EnterConfigurationMode,
    ExitConfigurationMode,
    GetIntervalDecimal,
    GetIntervalFraction,
    GetShiftDecimal,
    GetShiftFraction,
    SetIntervalDecimal,
    SetIntervalFraction,
    SetShiftDecimal,
    SetShiftFraction,
    EvaluateDiscreteStates,
    UpdateDiscreteStates,
    EnterContinuousTimeMode,
    CompletedIntegratorStep,
    SetTime,
    SetContinuousStates,
    GetContinuousStateDerivatives,
    GetEventIndicators,
    GetContinuousStates,
    GetNominalsOfContinuousStates,
    GetNumberOfEventIndicators,
    GetNumberOfContinuousStates,
    EnterStepMode,
    ActivateModelPartition,
}

impl Unsupported {
    /// The C function, e.g. "fmi3EnterEventMode".
    pub fn function(self) -> String {
        format!("fmi3{self:?}")
    }

    /// Calls the function on handle `c` with valid one-element arrays.
    ///
    /// # Safety
    /// None beyond the FMU's own: every pointer is valid; `c` is looked up by the FMU.
    unsafe fn call(self, c: FmiInstance) -> Status {
        use Unsupported::*;
        let vr = [0 as ValueReference];
        let mut real = [0.0];
        let mut size = [0_usize];
        let mut word = [0_u64];
        let mut word2 = [0_u64];
        let mut int = [0 as std::ffi::c_int];
        let mut flags = [ffi::FALSE; 6];
        let [a, b, c2, d, e, _] = &mut flags;
        match self {
            EnterEventMode => fmi3EnterEventMode(c),
            GetNumberOfVariableDependencies => {
                fmi3GetNumberOfVariableDependencies(c, 0, size.as_mut_ptr())
            }
            GetVariableDependencies => {
                let mut independents = [0 as ValueReference];
                let mut indices = [0_usize];
                fmi3GetVariableDependencies(
                    c,
                    0,
                    size.as_mut_ptr(),
                    independents.as_mut_ptr(),
                    indices.as_mut_ptr(),
                    int.as_mut_ptr(),
                    1,
                )
            }
            GetDirectionalDerivative | GetAdjointDerivative => {
                let seed = [1.0];
                let function = if self == GetDirectionalDerivative {
                    fmi3GetDirectionalDerivative
                } else {
                    fmi3GetAdjointDerivative
                };
                function(
                    c,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    seed.as_ptr(),
                    1,
                    real.as_mut_ptr(),
                    1,
                )
            }
            EnterConfigurationMode => fmi3EnterConfigurationMode(c),
            ExitConfigurationMode => fmi3ExitConfigurationMode(c),
            GetIntervalDecimal => {
                fmi3GetIntervalDecimal(c, vr.as_ptr(), 1, real.as_mut_ptr(), int.as_mut_ptr())
            }
            GetIntervalFraction => fmi3GetIntervalFraction(
                c,
                vr.as_ptr(),
                1,
                word.as_mut_ptr(),
                word2.as_mut_ptr(),
                int.as_mut_ptr(),
            ),
            GetShiftDecimal => fmi3GetShiftDecimal(c, vr.as_ptr(), 1, real.as_mut_ptr()),
            GetShiftFraction => {
                fmi3GetShiftFraction(c, vr.as_ptr(), 1, word.as_mut_ptr(), word2.as_mut_ptr())
            }
            SetIntervalDecimal => fmi3SetIntervalDecimal(c, vr.as_ptr(), 1, real.as_ptr()),
            SetIntervalFraction => {
                fmi3SetIntervalFraction(c, vr.as_ptr(), 1, word.as_ptr(), word2.as_ptr())
            }
            SetShiftDecimal => fmi3SetShiftDecimal(c, vr.as_ptr(), 1, real.as_ptr()),
            SetShiftFraction => {
                fmi3SetShiftFraction(c, vr.as_ptr(), 1, word.as_ptr(), word2.as_ptr())
            }
            EvaluateDiscreteStates => fmi3EvaluateDiscreteStates(c),
            UpdateDiscreteStates => fmi3UpdateDiscreteStates(c, a, b, c2, d, e, real.as_mut_ptr()),
            EnterContinuousTimeMode => fmi3EnterContinuousTimeMode(c),
            CompletedIntegratorStep => fmi3CompletedIntegratorStep(c, ffi::TRUE, a, b),
            SetTime => fmi3SetTime(c, 0.0),
            SetContinuousStates => fmi3SetContinuousStates(c, real.as_ptr(), 1),
            GetContinuousStateDerivatives => {
                fmi3GetContinuousStateDerivatives(c, real.as_mut_ptr(), 1)
            }
            GetEventIndicators => fmi3GetEventIndicators(c, real.as_mut_ptr(), 1),
            GetContinuousStates => fmi3GetContinuousStates(c, real.as_mut_ptr(), 1),
            GetNominalsOfContinuousStates => {
                fmi3GetNominalsOfContinuousStates(c, real.as_mut_ptr(), 1)
            }
            GetNumberOfEventIndicators => fmi3GetNumberOfEventIndicators(c, size.as_mut_ptr()),
            GetNumberOfContinuousStates => fmi3GetNumberOfContinuousStates(c, size.as_mut_ptr()),
            EnterStepMode => fmi3EnterStepMode(c),
            ActivateModelPartition => fmi3ActivateModelPartition(c, 0, 0.0),
        }
    }
}

fn boolean(value: bool) -> Boolean {
    if value {
        ffi::TRUE
    } else {
        ffi::FALSE
    }
}

/// A typed getter's and setter's C signature (every fmi3Get/Set of a scalar type).
type Getter<T> =
    unsafe extern "C" fn(FmiInstance, *const ValueReference, usize, *mut T, usize) -> Status;
type Setter<T> =
    unsafe extern "C" fn(FmiInstance, *const ValueReference, usize, *const T, usize) -> Status;

/// One FMI 3.0 instance of this crate, called in-process, with its log.
///
/// Dropping it frees the FMU instance (and, through the FMU, every state it still holds).
pub struct ImportedInstance {
    /// The handle fmi3InstantiateCoSimulation returned, kept after a free (see the module's
    /// documentation).
    handle: usize,
    freed: bool,
    environment: Box<Environment>,
}

// SAFETY: FMI 3.0 lets an instance be called from any thread as long as calls on it do not
// overlap; `&mut self` on every call guarantees that, and the FMU instance holds no thread-bound
// data (the callbacks' environment is this instance's own).
unsafe impl Send for ImportedInstance {}

impl ImportedInstance {
    /// Instantiates `model_identifier` for co-simulation, named `instance_name`. The error is
    /// the log of the refusal.
    pub fn new(
        model_identifier: &str,
        instance_name: &str,
    ) -> Result<ImportedInstance, Vec<Message>> {
        match Instantiation::new(model_identifier, instance_name) {
            Some(arguments) => ImportedInstance::instantiate(&arguments),
            None => Err(no_model(model_identifier, Status::Error as i32)),
        }
    }

    /// Calls the fmi3Instantiate function of `arguments.interface` with those arguments.
    pub fn instantiate(arguments: &Instantiation) -> Result<ImportedInstance, Vec<Message>> {
        let environment = Box::<Environment>::default();
        let pointer = &*environment as *const Environment as *mut c_void;
        let name = c_text(&arguments.instance_name);
        let token = c_text(&arguments.instantiation_token);
        let path = c_text(&arguments.resource_path);
        let log_message = arguments
            .log_message
            .then_some(record as ffi::LogMessageCallback);
        let update = arguments
            .intermediate_update
            .then_some(intermediate_update as ffi::IntermediateUpdateCallback);
        let required = &arguments.required_intermediate_variables;
        // SAFETY: every pointer is NULL or a live C string or array for the whole call; the FMU
        // keeps the callbacks and the environment, which outlive the instance (see `record`).
        let handle = unsafe {
            match arguments.interface {
                Interface::CoSimulation => instantiate_co_simulation(
                    &Binary::ALL,
                    c_pointer(&name),
                    c_pointer(&token),
                    c_pointer(&path),
                    boolean(arguments.visible),
                    boolean(arguments.logging_on),
                    boolean(arguments.event_mode_used),
                    boolean(arguments.early_return_allowed),
                    required.as_ptr(),
                    required.len(),
                    pointer,
                    log_message,
                    update,
                ),
                Interface::ModelExchange => fmi3InstantiateModelExchange(
                    c_pointer(&name),
                    c_pointer(&token),
                    c_pointer(&path),
                    boolean(arguments.visible),
                    boolean(arguments.logging_on),
                    pointer,
                    log_message,
                ),
                Interface::ScheduledExecution => fmi3InstantiateScheduledExecution(
                    c_pointer(&name),
                    c_pointer(&token),
                    c_pointer(&path),
                    boolean(arguments.visible),
                    boolean(arguments.logging_on),
                    pointer,
                    log_message,
                    None,
                    None,
                    None,
                ),
            }
        };
        if handle.is_null() {
            return Err(environment.sink.take());
        }
        environment.handle.store(handle as usize, Ordering::SeqCst);
        Ok(ImportedInstance {
            handle: handle as usize,
            freed: false,
            environment,
        })
    }

    /// A driver instance that calls on `handle` and never frees it (marked freed, so `Drop`
    /// leaves it), with a log of its own that the FMU never writes to.
    fn borrowing(handle: usize) -> ImportedInstance {
        ImportedInstance {
            handle,
            freed: true,
            environment: Box::default(),
        }
    }

    fn c(&self) -> FmiInstance {
        self.handle as FmiInstance
    }

    /// Sets what the intermediateUpdate callback does (see [`OnIntermediateUpdate`]); it is only
    /// called if the instance was given the callback ([`Instantiation::intermediate_update`]).
    pub fn on_intermediate_update(&mut self, hook: Option<OnIntermediateUpdate>) {
        *self
            .environment
            .on_update
            .lock()
            .unwrap_or_else(|e| e.into_inner()) = hook;
    }

    /// The handle the FMU handed out (kept after a free).
    pub fn handle(&self) -> usize {
        self.handle
    }

    /// The messages logged so far, oldest first.
    pub fn messages(&self) -> Vec<Message> {
        self.environment.sink.messages()
    }

    /// The text of the last message logged, or "" if none.
    pub fn last_message(&self) -> String {
        self.environment.sink.last_text()
    }

    /// Removes and returns the messages logged so far.
    pub fn take_messages(&mut self) -> Vec<Message> {
        self.environment.sink.take()
    }

    /// How often the FMU called the intermediateUpdate callback.
    pub fn intermediate_updates(&self) -> u64 {
        self.environment
            .intermediate_updates
            .load(Ordering::Relaxed)
    }

    /// Whether fmi3FreeInstance has been called through this driver instance.
    pub fn is_freed(&self) -> bool {
        self.freed
    }

    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        let names = c_strings(categories);
        let pointers: Vec<FmiString> = names.iter().map(|c| c.as_ptr()).collect();
        // SAFETY: `pointers` holds `len` live C strings.
        unsafe {
            fmi3SetDebugLogging(
                self.c(),
                boolean(logging_on),
                pointers.len(),
                pointers.as_ptr(),
            )
        }
    }

    pub fn enter_initialization_mode(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Status {
        // SAFETY: plain values; the handle is looked up by the FMU.
        unsafe {
            fmi3EnterInitializationMode(
                self.c(),
                boolean(tolerance.is_some()),
                tolerance.unwrap_or(0.0),
                start_time,
                boolean(stop_time.is_some()),
                stop_time.unwrap_or(0.0),
            )
        }
    }

    pub fn exit_initialization_mode(&mut self) -> Status {
        // SAFETY: the handle is looked up by the FMU.
        unsafe { fmi3ExitInitializationMode(self.c()) }
    }

    /// Enters initialization (start 0, no tolerance, no stop time) and exits it: the worse
    /// status.
    pub fn initialize(&mut self) -> Status {
        let enter = self.enter_initialization_mode(None, 0.0, None);
        let exit = self.exit_initialization_mode();
        enter.max(exit)
    }

    pub fn terminate(&mut self) -> Status {
        // SAFETY: as above.
        unsafe { fmi3Terminate(self.c()) }
    }

    pub fn reset(&mut self) -> Status {
        // SAFETY: as above.
        unsafe { fmi3Reset(self.c()) }
    }

    fn get_with<T>(&mut self, getter: Getter<T>, vrs: &[u32], values: &mut [T]) -> Status {
        // SAFETY: `vrs` holds nValueReferences and `values` nValues elements.
        unsafe {
            getter(
                self.c(),
                vrs.as_ptr(),
                vrs.len(),
                values.as_mut_ptr(),
                values.len(),
            )
        }
    }

    fn set_with<T>(&mut self, setter: Setter<T>, vrs: &[u32], values: &[T]) -> Status {
        // SAFETY: `vrs` holds nValueReferences and `values` nValues elements.
        unsafe {
            setter(
                self.c(),
                vrs.as_ptr(),
                vrs.len(),
                values.as_ptr(),
                values.len(),
            )
        }
    }

    /// fmi3GetFloat64 into `values`, passing its length as nValues (so a length other than
    /// `vrs`'s is a call the FMU must refuse). Allocates nothing.
    pub fn get_float64_into(&mut self, vrs: &[u32], values: &mut [f64]) -> Status {
        self.get_with(fmi3GetFloat64, vrs, values)
    }

    /// fmi3GetFloat64; the values are only meaningful when the status is OK.
    pub fn get_float64(&mut self, vrs: &[u32]) -> (Status, Vec<f64>) {
        let mut values = vec![0.0; vrs.len()];
        let status = self.get_float64_into(vrs, &mut values);
        (status, values)
    }

    /// fmi3SetFloat64, with nValues the length of `values`.
    pub fn set_float64(&mut self, vrs: &[u32], values: &[f64]) -> Status {
        self.set_with(fmi3SetFloat64, vrs, values)
    }

    /// fmi3GetInt32 (Integer variables).
    pub fn get_int32(&mut self, vrs: &[u32]) -> (Status, Vec<i32>) {
        let mut values = vec![0; vrs.len()];
        let status = self.get_with(fmi3GetInt32, vrs, &mut values);
        (status, values)
    }

    /// fmi3SetInt32 (Integer variables), with nValues the length of `values`.
    pub fn set_int32(&mut self, vrs: &[u32], values: &[i32]) -> Status {
        self.set_with(fmi3SetInt32, vrs, values)
    }

    /// fmi3GetInt64 (the switches, Enumerations in FMI 3.0).
    pub fn get_int64(&mut self, vrs: &[u32]) -> (Status, Vec<i64>) {
        let mut values = vec![0; vrs.len()];
        let status = self.get_with(fmi3GetInt64, vrs, &mut values);
        (status, values)
    }

    /// fmi3SetInt64 (the switches), with nValues the length of `values`.
    pub fn set_int64(&mut self, vrs: &[u32], values: &[i64]) -> Status {
        self.set_with(fmi3SetInt64, vrs, values)
    }

    /// The getter of type `t` with nValues = `n_values`, the values read converted to f64
    /// (a String's or Binary's to 0 or 1 for NULL or not, a Boolean's to 0 or 1).
    pub fn get(&mut self, t: ValueType, vrs: &[u32], n_values: usize) -> (Status, Vec<f64>) {
        macro_rules! read {
            ($getter:ident, $zero:expr) => {{
                let mut values = vec![$zero; n_values];
                let status = self.get_with($getter, vrs, &mut values);
                (status, values.iter().map(|&x| x as f64).collect())
            }};
        }
        match t {
            ValueType::Float32 => read!(fmi3GetFloat32, 0.0_f32),
            ValueType::Float64 => read!(fmi3GetFloat64, 0.0_f64),
            ValueType::Int8 => read!(fmi3GetInt8, 0_i8),
            ValueType::UInt8 => read!(fmi3GetUInt8, 0_u8),
            ValueType::Int16 => read!(fmi3GetInt16, 0_i16),
            ValueType::UInt16 => read!(fmi3GetUInt16, 0_u16),
            ValueType::Int32 => read!(fmi3GetInt32, 0_i32),
            ValueType::UInt32 => read!(fmi3GetUInt32, 0_u32),
            ValueType::Int64 => read!(fmi3GetInt64, 0_i64),
            ValueType::UInt64 => read!(fmi3GetUInt64, 0_u64),
            ValueType::Boolean => read!(fmi3GetBoolean, ffi::FALSE),
            ValueType::String => {
                let mut values: Vec<FmiString> = vec![std::ptr::null(); n_values];
                let status = self.get_with(fmi3GetString, vrs, &mut values);
                (
                    status,
                    values
                        .iter()
                        .map(|p| f64::from(u8::from(!p.is_null())))
                        .collect(),
                )
            }
            ValueType::Binary => {
                let mut sizes = vec![0_usize; n_values];
                let mut values: Vec<BinaryValue> = vec![std::ptr::null(); n_values];
                // SAFETY: `vrs` holds nValueReferences, `sizes` and `values` nValues elements.
                let status = unsafe {
                    fmi3GetBinary(
                        self.c(),
                        vrs.as_ptr(),
                        vrs.len(),
                        sizes.as_mut_ptr(),
                        values.as_mut_ptr(),
                        n_values,
                    )
                };
                (status, sizes.iter().map(|&s| s as f64).collect())
            }
            ValueType::Clock => {
                // fmi3GetClock has no nValues: one value per value reference.
                let mut values = vec![ffi::FALSE; vrs.len()];
                // SAFETY: both arrays hold `vrs.len()` elements.
                let status =
                    unsafe { fmi3GetClock(self.c(), vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
                (status, values.iter().map(|&x| f64::from(x)).collect())
            }
        }
    }

    /// The setter of type `t`, with nValues the length of `values`, each converted from f64
    /// with `as` (a String's is "x", a Binary's one byte).
    pub fn set(&mut self, t: ValueType, vrs: &[u32], values: &[f64]) -> Status {
        macro_rules! write {
            ($setter:ident, $t:ty) => {{
                let values: Vec<$t> = values.iter().map(|&x| x as $t).collect();
                self.set_with($setter, vrs, &values)
            }};
        }
        match t {
            ValueType::Float32 => write!(fmi3SetFloat32, f32),
            ValueType::Float64 => self.set_with(fmi3SetFloat64, vrs, values),
            ValueType::Int8 => write!(fmi3SetInt8, i8),
            ValueType::UInt8 => write!(fmi3SetUInt8, u8),
            ValueType::Int16 => write!(fmi3SetInt16, i16),
            ValueType::UInt16 => write!(fmi3SetUInt16, u16),
            ValueType::Int32 => write!(fmi3SetInt32, i32),
            ValueType::UInt32 => write!(fmi3SetUInt32, u32),
            ValueType::Int64 => write!(fmi3SetInt64, i64),
            ValueType::UInt64 => write!(fmi3SetUInt64, u64),
            ValueType::Boolean => write!(fmi3SetBoolean, u8),
            ValueType::String => {
                let pointers: Vec<FmiString> = values.iter().map(|_| c"x".as_ptr()).collect();
                self.set_with(fmi3SetString, vrs, &pointers)
            }
            ValueType::Binary => {
                let byte = [0x5a_u8];
                let sizes = vec![1_usize; values.len()];
                let pointers: Vec<BinaryValue> = values.iter().map(|_| byte.as_ptr()).collect();
                // SAFETY: `vrs` holds nValueReferences, `sizes` and `pointers` nValues elements,
                // each pointer one byte.
                unsafe {
                    fmi3SetBinary(
                        self.c(),
                        vrs.as_ptr(),
                        vrs.len(),
                        sizes.as_ptr(),
                        pointers.as_ptr(),
                        pointers.len(),
                    )
                }
            }
            ValueType::Clock => {
                // fmi3SetClock has no nValues: one value per value reference.
                let clocks: Vec<Boolean> = vrs
                    .iter()
                    .enumerate()
                    .map(|(i, _)| boolean(values.get(i).is_some_and(|&x| x != 0.0)))
                    .collect();
                // SAFETY: both arrays hold `vrs.len()` elements.
                unsafe { fmi3SetClock(self.c(), vrs.as_ptr(), vrs.len(), clocks.as_ptr()) }
            }
        }
    }

    /// fmi3DoStep.
    pub fn do_step(
        &mut self,
        current_communication_point: f64,
        communication_step_size: f64,
        no_set_fmu_state_prior: bool,
    ) -> (Status, StepOutcome) {
        let (mut event, mut terminate, mut early) = (ffi::TRUE, ffi::TRUE, ffi::TRUE);
        let mut last = f64::NAN;
        // SAFETY: the four outputs point to live values of their types.
        let status = unsafe {
            fmi3DoStep(
                self.c(),
                current_communication_point,
                communication_step_size,
                boolean(no_set_fmu_state_prior),
                &mut event,
                &mut terminate,
                &mut early,
                &mut last,
            )
        };
        let outcome = StepOutcome {
            event_handling_needed: event != ffi::FALSE,
            terminate_simulation: terminate != ffi::FALSE,
            early_return: early != ffi::FALSE,
            last_successful_time: last,
        };
        (status, outcome)
    }

    /// fmi3GetOutputDerivatives of `vrs` at `orders`, with nValues = `n_values`.
    pub fn get_output_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        n_values: usize,
    ) -> (Status, Vec<f64>) {
        assert_eq!(orders.len(), vrs.len(), "one order per value reference");
        let mut values = vec![0.0; n_values];
        // SAFETY: `vrs` and `orders` hold nValueReferences, `values` nValues elements.
        let status = unsafe {
            fmi3GetOutputDerivatives(
                self.c(),
                vrs.as_ptr(),
                vrs.len(),
                orders.as_ptr(),
                values.as_mut_ptr(),
                n_values,
            )
        };
        (status, values)
    }

    /// fmi3GetFMUState into a new state.
    pub fn get_fmu_state(&mut self) -> Result<State, Status> {
        let mut state = State::NULL;
        let status = self.update_fmu_state(&mut state);
        ok_then(status, Status::Ok, state)
    }

    /// fmi3GetFMUState into `state`: a new one if it is NULL, else the FMU overwrites it (if it
    /// is one of this instance's) or refuses.
    pub fn update_fmu_state(&mut self, state: &mut State) -> Status {
        // SAFETY: `slot` is a valid fmi3FMUState to write to; its value is checked by the FMU.
        state.through(|slot| unsafe { fmi3GetFMUState(self.c(), slot) })
    }

    pub fn set_fmu_state(&mut self, state: State) -> Status {
        // SAFETY: the FMU only dereferences states in this instance's list.
        unsafe { fmi3SetFMUState(self.c(), state.pointer()) }
    }

    /// fmi3FreeFMUState; on success `state` becomes NULL.
    pub fn free_fmu_state(&mut self, state: &mut State) -> Status {
        // SAFETY: as for `update_fmu_state`.
        state.through(|slot| unsafe { fmi3FreeFMUState(self.c(), slot) })
    }

    pub fn serialized_fmu_state_size(&mut self, state: State) -> (Status, usize) {
        let mut size = 0;
        // SAFETY: `size` is a valid size_t; the state is checked by the FMU.
        let status = unsafe { fmi3SerializedFMUStateSize(self.c(), state.pointer(), &mut size) };
        (status, size)
    }

    /// fmi3SerializeFMUState into `buffer`, passing its length as the size.
    pub fn serialize_fmu_state_into(&mut self, state: State, buffer: &mut [u8]) -> Status {
        // SAFETY: `buffer` has room for the size passed.
        unsafe {
            fmi3SerializeFMUState(self.c(), state.pointer(), buffer.as_mut_ptr(), buffer.len())
        }
    }

    /// fmi3SerializedFMUStateSize, then fmi3SerializeFMUState into a buffer of that size.
    pub fn serialize_fmu_state(&mut self, state: State) -> Result<Vec<u8>, Status> {
        let size = self.serialized_fmu_state_size(state);
        serialized(Status::Ok, size, |bytes| {
            self.serialize_fmu_state_into(state, bytes)
        })
    }

    /// fmi3DeserializeFMUState into a new state.
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8]) -> Result<State, Status> {
        let mut state = State::NULL;
        let status = self.deserialize_fmu_state_into(bytes, &mut state);
        ok_then(status, Status::Ok, state)
    }

    /// fmi3DeserializeFMUState into `state` (overwritten if it is one of this instance's).
    pub fn deserialize_fmu_state_into(&mut self, bytes: &[u8], state: &mut State) -> Status {
        // SAFETY: `bytes` holds the size passed; `slot` as for `update_fmu_state`.
        state.through(|slot| unsafe {
            fmi3DeserializeFMUState(self.c(), bytes.as_ptr(), bytes.len(), slot)
        })
    }

    /// One of the functions these FMUs leave out (see [`Unsupported`]).
    pub fn call_unsupported(&mut self, which: Unsupported) -> Status {
        // SAFETY: see `Unsupported::call`.
        unsafe { which.call(self.c()) }
    }

    /// Calls one function with one pointer argument NULL (see [`NullArgument`]).
    pub fn call_with_null(&mut self, which: NullArgument) -> Status {
        use NullArgument::*;
        let c = self.c();
        let vr = [0 as ValueReference];
        let order = [1_i32];
        let mut real = [0.0];
        let mut slot: FmuState = std::ptr::null_mut();
        let (mut event, mut terminate, mut early, mut last) =
            (ffi::FALSE, ffi::FALSE, ffi::FALSE, 0.0);
        let null_state: *mut FmuState = std::ptr::null_mut();
        // SAFETY: every non-NULL pointer is valid for the length passed with it; the NULL one is
        // the FMU's to refuse (it must check it before any use).
        unsafe {
            match which {
                GetFloat64Values => fmi3GetFloat64(c, vr.as_ptr(), 1, std::ptr::null_mut(), 1),
                SetFloat64Values => fmi3SetFloat64(c, vr.as_ptr(), 1, std::ptr::null(), 1),
                GetFloat64References => {
                    fmi3GetFloat64(c, std::ptr::null(), 1, real.as_mut_ptr(), 1)
                }
                GetInt64Values => fmi3GetInt64(c, vr.as_ptr(), 1, std::ptr::null_mut(), 1),
                SetInt64Values => fmi3SetInt64(c, vr.as_ptr(), 1, std::ptr::null(), 1),
                SetStringElement => {
                    let strings = [std::ptr::null::<c_char>()];
                    fmi3SetString(c, vr.as_ptr(), 1, strings.as_ptr(), 1)
                }
                GetBinarySizes => {
                    let mut values = [std::ptr::null::<u8>()];
                    fmi3GetBinary(
                        c,
                        vr.as_ptr(),
                        1,
                        std::ptr::null_mut(),
                        values.as_mut_ptr(),
                        1,
                    )
                }
                DebugLoggingCategories => fmi3SetDebugLogging(c, ffi::TRUE, 1, std::ptr::null()),
                GetFmuStateSlot => fmi3GetFMUState(c, null_state),
                FreeFmuStateSlot => fmi3FreeFMUState(c, null_state),
                SerializedSizeOut(state) => {
                    fmi3SerializedFMUStateSize(c, state.pointer(), std::ptr::null_mut())
                }
                SerializeBuffer(state) => {
                    fmi3SerializeFMUState(c, state.pointer(), std::ptr::null_mut(), 1000)
                }
                DeserializeBytes => fmi3DeserializeFMUState(c, std::ptr::null(), 8, &mut slot),
                DeserializeSlot => {
                    let bytes = [0_u8; 64];
                    fmi3DeserializeFMUState(c, bytes.as_ptr(), bytes.len(), null_state)
                }
                DoStepOutput(which) => {
                    let nothing = std::ptr::null_mut();
                    let pick = |k: u8, p: *mut Boolean| if k == which { nothing } else { p };
                    let last = if which == 3 {
                        std::ptr::null_mut()
                    } else {
                        &mut last as *mut f64
                    };
                    fmi3DoStep(
                        c,
                        0.0,
                        1e-3,
                        ffi::FALSE,
                        pick(0, &mut event),
                        pick(1, &mut terminate),
                        pick(2, &mut early),
                        last,
                    )
                }
                OutputDerivativeOrders => fmi3GetOutputDerivatives(
                    c,
                    vr.as_ptr(),
                    1,
                    std::ptr::null(),
                    real.as_mut_ptr(),
                    1,
                ),
                OutputDerivativeValues => fmi3GetOutputDerivatives(
                    c,
                    vr.as_ptr(),
                    1,
                    order.as_ptr(),
                    std::ptr::null_mut(),
                    1,
                ),
            }
        }
    }

    /// fmi3FreeInstance. The handle stays, so later calls through this driver instance
    /// (including `free` again) test that the FMU refuses a freed handle.
    pub fn free(&mut self) {
        // SAFETY: the handle is looked up by the FMU; a freed one is ignored.
        unsafe { fmi3FreeInstance(self.c()) };
        self.freed = true;
    }

    /// fmi3FreeInstance twice in a row, as a buggy importer would.
    pub fn free_twice(&mut self) {
        self.free();
        self.free();
    }
}

impl Drop for ImportedInstance {
    fn drop(&mut self) {
        if !self.freed {
            self.free();
        }
    }
}

/// fmi3GetVersion.
pub fn version() -> String {
    lossy(fmi3GetVersion())
}

/// fmi3FreeInstance on `handle`, which is no live FMI 3.0 instance of the caller's (NULL, made
/// up, freed, or an FMI 2.0 instance's): the FMU must ignore it.
pub fn free_foreign_handle(handle: usize) {
    // SAFETY: the handle is looked up by the FMU, never dereferenced.
    unsafe { fmi3FreeInstance(handle as FmiInstance) }
}

/// Calls every fmi3 function that takes an instance, except fmi3FreeInstance, on `handle`:
/// each function's name and status. Meant for handles that are no live FMI 3.0 instance (NULL,
/// made up, freed, an FMI 2.0 instance's), which the FMU must refuse without touching anything;
/// nothing can be logged, as there is no instance whose logger to call.
pub fn calls_on_handle(handle: usize) -> Vec<(String, Status)> {
    let c = handle as FmiInstance;
    let vr = [0 as ValueReference];
    let order = [1_i32];
    let mut real = [0.0];
    let mut state: FmuState = std::ptr::null_mut();
    let mut size = 0;
    let mut bytes = [0_u8; 8];
    let (mut event, mut terminate, mut early) = (ffi::FALSE, ffi::FALSE, ffi::FALSE);
    // SAFETY: every pointer is valid for the length passed; the FMU must refuse the handle
    // before touching anything else.
    let mut calls: Vec<(String, Status)> = unsafe {
        vec![
            (
                "fmi3SetDebugLogging".into(),
                fmi3SetDebugLogging(c, ffi::TRUE, 0, std::ptr::null()),
            ),
            (
                "fmi3EnterInitializationMode".into(),
                fmi3EnterInitializationMode(c, ffi::FALSE, 0.0, 0.0, ffi::FALSE, 0.0),
            ),
            (
                "fmi3ExitInitializationMode".into(),
                fmi3ExitInitializationMode(c),
            ),
            ("fmi3Terminate".into(), fmi3Terminate(c)),
            ("fmi3Reset".into(), fmi3Reset(c)),
            ("fmi3GetFMUState".into(), fmi3GetFMUState(c, &mut state)),
            ("fmi3SetFMUState".into(), fmi3SetFMUState(c, state)),
            ("fmi3FreeFMUState".into(), fmi3FreeFMUState(c, &mut state)),
            (
                "fmi3SerializedFMUStateSize".into(),
                fmi3SerializedFMUStateSize(c, state, &mut size),
            ),
            (
                "fmi3SerializeFMUState".into(),
                fmi3SerializeFMUState(c, state, bytes.as_mut_ptr(), bytes.len()),
            ),
            (
                "fmi3DeserializeFMUState".into(),
                fmi3DeserializeFMUState(c, bytes.as_ptr(), bytes.len(), &mut state),
            ),
            (
                "fmi3GetOutputDerivatives".into(),
                fmi3GetOutputDerivatives(c, vr.as_ptr(), 1, order.as_ptr(), real.as_mut_ptr(), 1),
            ),
            (
                "fmi3DoStep".into(),
                fmi3DoStep(
                    c,
                    0.0,
                    1e-3,
                    ffi::FALSE,
                    &mut event,
                    &mut terminate,
                    &mut early,
                    real.as_mut_ptr(),
                ),
            ),
        ]
    };
    // The getters and setters of every type, and the functions these FMUs leave out, through
    // a driver instance that borrows the handle.
    let mut borrowed = ImportedInstance::borrowing(handle);
    for t in VALUE_TYPES {
        let (status, _) = borrowed.get(t, &vr, 1);
        calls.push((format!("fmi3Get{t:?}"), status));
        calls.push((format!("fmi3Set{t:?}"), borrowed.set(t, &vr, &[1.0])));
    }
    for which in Unsupported::ALL {
        calls.push((which.function(), borrowed.call_unsupported(which)));
    }
    calls
}

/// Every type FMI 3.0 has a getter and a setter of.
pub const VALUE_TYPES: [ValueType; 14] = [
    ValueType::Float32,
    ValueType::Float64,
    ValueType::Int8,
    ValueType::UInt8,
    ValueType::Int16,
    ValueType::UInt16,
    ValueType::Int32,
    ValueType::UInt32,
    ValueType::Int64,
    ValueType::UInt64,
    ValueType::Boolean,
    ValueType::String,
    ValueType::Binary,
    ValueType::Clock,
];
