//! How FMI 3.0 names the instance's calls and phases, for its messages.

use crate::instance::calls::{Call, Dialect, ValueType};
use crate::instance::phase::Phase;
use crate::model_description::{TIME_NAME, TIME_VALUE_REFERENCE};
use crate::variables::variable::{Causality, Kind, Variability, Variable};

pub static FMI3: Dialect = Dialect {
    function,
    phase: |phase| match phase {
        Phase::Instantiated => "Instantiated",
        Phase::InitializationMode => "InitializationMode",
        Phase::StepComplete => "StepMode",
        Phase::StepFailed => "StepDiscarded",
        Phase::Terminated => "Terminated",
        Phase::Error => "Error",
        Phase::IntermediateUpdate => "IntermediateUpdateMode",
    },
    independent: Some(&TIME),
};

/// `time`, the independent variable of every FMI 3.0 description.
static TIME: Variable = Variable {
    name: TIME_NAME,
    value_reference: TIME_VALUE_REFERENCE,
    description: "Simulation time",
    causality: Causality::Independent,
    variability: Variability::Continuous,
    kind: Kind::Real {
        start: 0.0,
        unit: "s",
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
    },
    depends_on: &[],
};

fn function(call: Call) -> &'static str {
    macro_rules! typed {
        ($prefix:literal, $t:expr) => {
            match $t {
                ValueType::Float32 => concat!($prefix, "Float32"),
                ValueType::Float64 => concat!($prefix, "Float64"),
                ValueType::Int8 => concat!($prefix, "Int8"),
                ValueType::UInt8 => concat!($prefix, "UInt8"),
                ValueType::Int16 => concat!($prefix, "Int16"),
                ValueType::UInt16 => concat!($prefix, "UInt16"),
                ValueType::Int32 => concat!($prefix, "Int32"),
                ValueType::UInt32 => concat!($prefix, "UInt32"),
                ValueType::Int64 => concat!($prefix, "Int64"),
                ValueType::UInt64 => concat!($prefix, "UInt64"),
                ValueType::Boolean => concat!($prefix, "Boolean"),
                ValueType::String => concat!($prefix, "String"),
                ValueType::Binary => concat!($prefix, "Binary"),
                ValueType::Clock => concat!($prefix, "Clock"),
            }
        };
    }
    match call {
        Call::SetDebugLogging => "fmi3SetDebugLogging",
        // FMI 3.0 sets up the experiment as it enters initialization.
        Call::SetupExperiment | Call::EnterInitializationMode => "fmi3EnterInitializationMode",
        Call::ExitInitializationMode => "fmi3ExitInitializationMode",
        Call::Terminate => "fmi3Terminate",
        Call::Reset => "fmi3Reset",
        Call::Get(t) => typed!("fmi3Get", t),
        Call::Set(t) => typed!("fmi3Set", t),
        Call::GetFMUstate => "fmi3GetFMUState",
        Call::SetFMUstate => "fmi3SetFMUState",
        Call::FreeFMUstate => "fmi3FreeFMUState",
        Call::SerializedFMUstateSize => "fmi3SerializedFMUStateSize",
        Call::SerializeFMUstate => "fmi3SerializeFMUState",
        Call::DeSerializeFMUstate => "fmi3DeserializeFMUState",
        Call::GetDirectionalDerivative => "fmi3GetDirectionalDerivative",
        // FMI 3.0 co-simulation has no input derivatives; nothing calls these here.
        Call::SetRealInputDerivatives => "fmi3SetInputDerivatives",
        Call::GetRealOutputDerivatives => "fmi3GetOutputDerivatives",
        Call::DoStep => "fmi3DoStep",
        Call::CancelStep
        | Call::GetStatus
        | Call::GetRealStatus
        | Call::GetIntegerStatus
        | Call::GetBooleanStatus
        | Call::GetStringStatus
        | Call::Unsupported => "fmi3",
    }
}
