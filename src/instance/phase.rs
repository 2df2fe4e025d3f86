//! Where an instance is in its life: the co-simulation phases both standards share (FMI 3.0
//! without event mode has no others; FMI 2.0's StepComplete is its StepMode), and FMI 3.0's
//! IntermediateUpdateMode, between the internal steps of a step, which FMI 2.0 never enters.

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    IntermediateUpdate,
}

impl Phase {
    /// Every phase, in the order of their codes.
    pub const ALL: [Phase; 7] = [
        Phase::Instantiated,
        Phase::InitializationMode,
        Phase::StepComplete,
        Phase::StepFailed,
        Phase::Terminated,
        Phase::Error,
        Phase::IntermediateUpdate,
    ];

    /// The code an FMU state's bytes carry.
    pub fn code(self) -> f64 {
        self as u8 as f64
    }

    pub fn from_code(code: f64) -> Option<Phase> {
        Phase::ALL.into_iter().find(|p| p.code() == code)
    }
}
