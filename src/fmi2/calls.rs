//! Which function may be called in which phase of an instance: the co-simulation state machine
//! of FMI 2.0 (section 4.2.4) as one table. Every export that the phase governs names its
//! [`Call`], and `Instance::check_phase` refuses it outside the phases listed here, naming them.

use super::instance::Phase::{self, *};

/// The exported functions whose legality depends on the instance's phase. fmi2Instantiate and
/// fmi2FreeInstance do not: there is no instance before the one, and the other ends any phase.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Call {
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    GetReal,
    GetInteger,
    GetBoolean,
    GetString,
    SetReal,
    SetInteger,
    SetBoolean,
    SetString,
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
}

/// Every phase: the instance's own housekeeping and its FMU states are allowed in any.
const ANY: &[Phase] = &Phase::ALL;
/// Where values can be read (the standard also allows it after an error, for debugging).
const READABLE: &[Phase] = &[
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
];
/// Where inputs and parameters can be set (which of them, the variability decides).
const WRITABLE: &[Phase] = &[Instantiated, InitializationMode, StepComplete];
/// Where a step's outcome can be asked for.
const AFTER_A_STEP: &[Phase] = &[StepComplete, StepFailed, Terminated];

impl Call {
    /// The function's name and the phases it may be called in: the table itself.
    const fn entry(self) -> (&'static str, &'static [Phase]) {
        match self {
            Call::SetDebugLogging => ("fmi2SetDebugLogging", ANY),
            Call::SetupExperiment => ("fmi2SetupExperiment", &[Instantiated]),
            Call::EnterInitializationMode => ("fmi2EnterInitializationMode", &[Instantiated]),
            Call::ExitInitializationMode => ("fmi2ExitInitializationMode", &[InitializationMode]),
            Call::Terminate => ("fmi2Terminate", &[StepComplete, StepFailed, Error]),
            Call::Reset => ("fmi2Reset", ANY),
            Call::GetReal => ("fmi2GetReal", READABLE),
            Call::GetInteger => ("fmi2GetInteger", READABLE),
            Call::GetBoolean => ("fmi2GetBoolean", READABLE),
            Call::GetString => ("fmi2GetString", READABLE),
            Call::SetReal => ("fmi2SetReal", WRITABLE),
            Call::SetInteger => ("fmi2SetInteger", WRITABLE),
            Call::SetBoolean => ("fmi2SetBoolean", WRITABLE),
            Call::SetString => ("fmi2SetString", WRITABLE),
            Call::GetFMUstate => ("fmi2GetFMUstate", ANY),
            Call::SetFMUstate => ("fmi2SetFMUstate", ANY),
            Call::FreeFMUstate => ("fmi2FreeFMUstate", ANY),
            Call::SerializedFMUstateSize => ("fmi2SerializedFMUstateSize", ANY),
            Call::SerializeFMUstate => ("fmi2SerializeFMUstate", ANY),
            Call::DeSerializeFMUstate => ("fmi2DeSerializeFMUstate", ANY),
            Call::GetDirectionalDerivative => ("fmi2GetDirectionalDerivative", READABLE),
            Call::SetRealInputDerivatives => ("fmi2SetRealInputDerivatives", WRITABLE),
            Call::GetRealOutputDerivatives => (
                "fmi2GetRealOutputDerivatives",
                &[StepComplete, StepFailed, Terminated, Error],
            ),
            Call::DoStep => ("fmi2DoStep", &[StepComplete]),
            // Only in StepPending, which never occurs: fmi2DoStep never returns fmi2Pending.
            Call::CancelStep => ("fmi2CancelStep", &[]),
            Call::GetStatus => ("fmi2GetStatus", AFTER_A_STEP),
            Call::GetRealStatus => ("fmi2GetRealStatus", AFTER_A_STEP),
            Call::GetIntegerStatus => ("fmi2GetIntegerStatus", AFTER_A_STEP),
            Call::GetBooleanStatus => ("fmi2GetBooleanStatus", AFTER_A_STEP),
            Call::GetStringStatus => ("fmi2GetStringStatus", AFTER_A_STEP),
        }
    }

    pub const fn name(self) -> &'static str {
        self.entry().0
    }

    pub const fn phases(self) -> &'static [Phase] {
        self.entry().1
    }

    /// Whether the call is legal in `phase`.
    pub fn allowed_in(self, phase: Phase) -> bool {
        self.phases().contains(&phase)
    }

    /// What a refusal says the call needs.
    pub fn expected(self) -> String {
        let phases = self.phases();
        if phases.is_empty() {
            return "StepPending, which never occurs here (fmi2DoStep never returns fmi2Pending)"
                .to_string();
        }
        let names: Vec<&str> = phases.iter().map(|p| p.name()).collect();
        names.join(" or ")
    }
}
