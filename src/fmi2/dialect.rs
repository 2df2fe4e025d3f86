//! How FMI 2.0 names the instance's calls and phases, for its messages.

use crate::instance::calls::{Call, Dialect, ValueType};
use crate::instance::phase::Phase;

pub static FMI2: Dialect = Dialect {
    function,
    phase: |phase| match phase {
        Phase::Instantiated => "Instantiated",
        Phase::InitializationMode => "InitializationMode",
        Phase::StepComplete => "StepComplete",
        Phase::StepFailed => "StepFailed",
        Phase::Terminated => "Terminated",
        Phase::Error => "Error",
        Phase::IntermediateUpdate => "IntermediateUpdateMode",
    },
    independent: None,
};

fn function(call: Call) -> &'static str {
    match call {
        Call::SetDebugLogging => "fmi2SetDebugLogging",
        Call::SetupExperiment => "fmi2SetupExperiment",
        Call::EnterInitializationMode => "fmi2EnterInitializationMode",
        Call::ExitInitializationMode => "fmi2ExitInitializationMode",
        Call::Terminate => "fmi2Terminate",
        Call::Reset => "fmi2Reset",
        Call::Get(ValueType::Float64) => "fmi2GetReal",
        Call::Get(ValueType::Boolean) => "fmi2GetBoolean",
        Call::Get(ValueType::String) => "fmi2GetString",
        Call::Get(_) => "fmi2GetInteger",
        Call::Set(ValueType::Float64) => "fmi2SetReal",
        Call::Set(ValueType::Boolean) => "fmi2SetBoolean",
        Call::Set(ValueType::String) => "fmi2SetString",
        Call::Set(_) => "fmi2SetInteger",
        Call::GetFMUstate => "fmi2GetFMUstate",
        Call::SetFMUstate => "fmi2SetFMUstate",
        Call::FreeFMUstate => "fmi2FreeFMUstate",
        Call::SerializedFMUstateSize => "fmi2SerializedFMUstateSize",
        Call::SerializeFMUstate => "fmi2SerializeFMUstate",
        Call::DeSerializeFMUstate => "fmi2DeSerializeFMUstate",
        Call::GetDirectionalDerivative | Call::Unsupported => "fmi2GetDirectionalDerivative",
        Call::SetRealInputDerivatives => "fmi2SetRealInputDerivatives",
        Call::GetRealOutputDerivatives => "fmi2GetRealOutputDerivatives",
        Call::DoStep => "fmi2DoStep",
        Call::CancelStep => "fmi2CancelStep",
        Call::GetStatus => "fmi2GetStatus",
        Call::GetRealStatus => "fmi2GetRealStatus",
        Call::GetIntegerStatus => "fmi2GetIntegerStatus",
        Call::GetBooleanStatus => "fmi2GetBooleanStatus",
        Call::GetStringStatus => "fmi2GetStringStatus",
    }
}
