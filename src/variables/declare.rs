//! Short constructors that keep the per-model tables readable.

use super::variable::{Causality, EnumType, Kind, Variability, Variable};

/// The `min` of a parameter that must be strictly positive: the smallest normal f64, so the
/// inclusive range check of every setter refuses 0 with "expected name > 0".
pub const POSITIVE: f64 = f64::MIN_POSITIVE;

/// A fixed Real parameter with an inclusive range; `f64::INFINITY` bounds are left open.
pub const fn real_parameter(
    name: &'static str,
    value_reference: u32,
    description: &'static str,
    start: f64,
    unit: &'static str,
    min: f64,
    max: f64,
) -> Variable {
    Variable {
        name,
        value_reference,
        description,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        kind: Kind::Real {
            start,
            unit,
            min,
            max,
        },
        depends_on: &[],
    }
}

/// A fixed Integer parameter with an inclusive range.
pub const fn integer_parameter(
    name: &'static str,
    value_reference: u32,
    description: &'static str,
    start: i32,
    min: i32,
    max: i32,
) -> Variable {
    Variable {
        name,
        value_reference,
        description,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        kind: Kind::Integer { start, min, max },
        depends_on: &[],
    }
}

/// A fixed Enumeration parameter; `start` is the item's integer value (items count from 1).
pub const fn enum_parameter(
    name: &'static str,
    value_reference: u32,
    description: &'static str,
    type_name: &'static str,
    start: i32,
) -> Variable {
    Variable {
        name,
        value_reference,
        description,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        kind: Kind::Switch { type_name, start },
        depends_on: &[],
    }
}

/// A continuous Real input with a start value and range.
pub const fn real_input(
    name: &'static str,
    value_reference: u32,
    description: &'static str,
    start: f64,
    unit: &'static str,
) -> Variable {
    Variable {
        name,
        value_reference,
        description,
        causality: Causality::Input,
        variability: Variability::Continuous,
        kind: Kind::Real {
            start,
            unit,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
        },
        depends_on: &[],
    }
}

/// A continuous Real output (initial="calculated", so it has no start value in the XML).
pub const fn real_output(
    name: &'static str,
    value_reference: u32,
    description: &'static str,
    unit: &'static str,
    depends_on: &'static [u32],
) -> Variable {
    Variable {
        name,
        value_reference,
        description,
        causality: Causality::Output,
        variability: Variability::Continuous,
        kind: Kind::Real {
            start: 0.0,
            unit,
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
        },
        depends_on,
    }
}

// Parameters more than one model declares: the same name, meaning, unit and range everywhere,
// each model choosing its default.

/// `tolerance`: the relative tolerance of the adaptive solvers.
pub const fn tolerance(value_reference: u32, start: f64) -> Variable {
    real_parameter(
        "tolerance",
        value_reference,
        "Relative tolerance of the adaptive solvers",
        start,
        "",
        1e-14,
        1e-2,
    )
}

/// `m`: the mass of the sliding body.
pub const fn body_mass(value_reference: u32, start: f64) -> Variable {
    real_parameter(
        "m",
        value_reference,
        "Mass of the sliding body (> 0)",
        start,
        "kg",
        POSITIVE,
        f64::INFINITY,
    )
}

/// `g`: the gravitational acceleration, 9.81 m/s2 unless set.
pub const fn gravity(value_reference: u32) -> Variable {
    real_parameter(
        "g",
        value_reference,
        "Gravitational acceleration (> 0)",
        9.81,
        "m/s2",
        POSITIVE,
        f64::INFINITY,
    )
}

/// `kt`: the tangential contact stiffness.
pub const fn contact_stiffness(value_reference: u32, start: f64) -> Variable {
    real_parameter(
        "kt",
        value_reference,
        "Tangential contact stiffness (> 0)",
        start,
        "N/m",
        POSITIVE,
        f64::INFINITY,
    )
}

/// The switch every model with inputs declares: how an input moves over a communication step
/// when the master gives no derivative (the runtime side: `models::input_scheme`). Held by
/// default, what the master's values mean unless it says otherwise; `DriveFriction.ssp` sets
/// `corrected`.
pub const fn input_scheme(value_reference: u32) -> Variable {
    enum_parameter(
        "input_scheme",
        value_reference,
        "How the inputs move over a communication step the master sets no derivative for",
        INPUT_SCHEME.name,
        1,
    )
}

/// The items of `input_scheme`.
pub const INPUT_SCHEME: EnumType = EnumType {
    name: "InputScheme",
    items: &[
        (
            "held",
            "Each input keeps the value set at the communication point over the step, as co-simulation engines mean it",
        ),
        (
            "extrapolated",
            "Each input moves along the line through its values at the last two communication points (second order in the step)",
        ),
        (
            "corrected",
            "As extrapolated, plus what the input's integral over time missed so far, spread over the step (the integral follows the master's values to third order)",
        ),
    ],
};
