//! Which call is legal in which phase of an instance: the co-simulation state machine of FMI 2.0
//! (section 4.2.4) and FMI 3.0 (section 4.2.1, without event mode) as one table. The calls are
//! the operations, not their C names: each standard's boundary names them ([`Dialect`]), and
//! [`super::Instance::check_phase`] refuses a call outside the phases listed here, naming them.

use super::phase::Phase::{self, *};
use crate::variables::variable::Variable;

/// A variable type as the getters and setters of a standard name it (FMI 2.0's Real is
/// [`ValueType::Float64`], its Integer [`ValueType::Int32`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ValueType {
    Float32,
    Float64,
    Int8,
    UInt8,
    Int16,
    UInt16,
    Int32,
    UInt32,
    Int64,
    UInt64,
    Boolean,
    String,
    Binary,
    Clock,
}

/// The operations whose legality depends on the instance's phase. Instantiation and freeing do
/// not: there is no instance before the one, and the other ends any phase.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Call {
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    Get(ValueType),
    Set(ValueType),
    GetFMUstate,
    SetFMUstate,
    FreeFMUstate,
    SerializedFMUstateSize,
    SerializeFMUstate,
    DeSerializeFMUstate,
    GetDirectionalDerivative,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
    DoStep,
    CancelStep,
    GetStatus,
    GetRealStatus,
    GetIntegerStatus,
    GetBooleanStatus,
    GetStringStatus,
    /// What a standard declares and these FMUs do not offer (FMI 3.0's configuration and event
    /// modes, clocks, adjoint derivatives): refused in any phase, after the phase is checked.
    Unsupported,
}

/// How a standard names the calls and phases, for messages: the instance never asks which
/// standard calls it, only how to say what it refuses.
pub struct Dialect {
    /// The C function of a call (`fmi2DoStep`, `fmi3DoStep`).
    pub function: fn(Call) -> &'static str,
    /// The standard's name of a phase (FMI 2.0's StepComplete is FMI 3.0's StepMode).
    pub phase: fn(Phase) -> &'static str,
    /// The independent variable the standard's descriptions declare (FMI 3.0 requires one,
    /// `time`; FMI 2.0's leave it out), read as the instance's time.
    pub independent: Option<&'static Variable>,
}

/// Every phase but a step's intermediate update: the instance's own housekeeping and its FMU
/// states are allowed in any.
const ANY: &[Phase] = &[
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
];
/// Where values can be read (the standards also allow it after an error, for debugging, and
/// between a step's internal steps).
const READABLE: &[Phase] = &[
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    IntermediateUpdate,
];
/// Where inputs and parameters can be set (which of them, the variability and the phase
/// decide: between a step's internal steps, inputs alone).
const WRITABLE: &[Phase] = &[
    Instantiated,
    InitializationMode,
    StepComplete,
    IntermediateUpdate,
];
/// Where a step's outcome can be asked for.
const AFTER_A_STEP: &[Phase] = &[StepComplete, StepFailed, Terminated];

impl Call {
    /// The phases the call may be made in: the table itself.
    pub const fn phases(self) -> &'static [Phase] {
        match self {
            Call::SetDebugLogging | Call::Reset | Call::Unsupported => ANY,
            Call::SetupExperiment | Call::EnterInitializationMode => &[Instantiated],
            Call::ExitInitializationMode => &[InitializationMode],
            Call::Terminate => &[StepComplete, StepFailed, Error],
            Call::Get(_) | Call::GetDirectionalDerivative => READABLE,
            Call::Set(_) => WRITABLE,
            Call::SetRealInputDerivatives => &[Instantiated, InitializationMode, StepComplete],
            Call::GetFMUstate
            | Call::SetFMUstate
            | Call::FreeFMUstate
            | Call::SerializedFMUstateSize
            | Call::SerializeFMUstate
            | Call::DeSerializeFMUstate => ANY,
            Call::GetRealOutputDerivatives => &[StepComplete, StepFailed, Terminated, Error],
            Call::DoStep => &[StepComplete],
            // Only while a step is pending, which never happens: steps are synchronous.
            Call::CancelStep => &[],
            Call::GetStatus
            | Call::GetRealStatus
            | Call::GetIntegerStatus
            | Call::GetBooleanStatus
            | Call::GetStringStatus => AFTER_A_STEP,
        }
    }

    /// Whether the call is legal in `phase`.
    pub fn allowed_in(self, phase: Phase) -> bool {
        self.phases().contains(&phase)
    }
}

impl Dialect {
    /// What a refusal says the call needs.
    pub fn expected(&self, call: Call) -> String {
        let phases = call.phases();
        if phases.is_empty() {
            let do_step = (self.function)(Call::DoStep);
            let prefix = do_step.get(..4).unwrap_or("fmi");
            return format!(
                "StepPending, which never occurs here ({do_step} never returns {prefix}Pending)"
            );
        }
        let names: Vec<&str> = phases.iter().map(|&p| (self.phase)(p)).collect();
        names.join(" or ")
    }
}
