//! The variable table: plain data describing every model variable once.
//!
//! This file is compiled twice: into the library (the FMI layer dispatches value references with
//! it) and into `build.rs` (which writes modelDescription.xml from it). So it depends on nothing
//! but `core` and the errors (src/error.rs, compiled into both), and the two can never disagree.

use crate::error::Error;

/// FMI 2.0 causality of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    Input,
    Output,
    Independent,
}

/// FMI 2.0 variability of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Tunable,
    Continuous,
}

/// The value type with its start value and the range a setter accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A Real; `min`/`max` are inclusive bounds checked on every set.
    Real {
        start: f64,
        unit: &'static str,
        min: f64,
        max: f64,
    },
    /// A switch: one of the numbered items of the model's enumeration type `type_name`. Declared
    /// to importers as an Integer (1 to the number of items) whose type's description lists the
    /// items, since co-simulation engines ignore FMI 2.0 Enumerations; set with fmi2SetInteger.
    Switch { type_name: &'static str, start: i32 },
    /// An Integer with inclusive bounds.
    Integer { start: i32, min: i32, max: i32 },
}

/// One model variable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variable {
    pub name: &'static str,
    pub value_reference: u32,
    pub description: &'static str,
    pub causality: Causality,
    pub variability: Variability,
    pub kind: Kind,
    /// For outputs: the inputs (value references) that reach this output within the same
    /// communication point (direct feedthrough). Empty for everything else.
    pub depends_on: &'static [u32],
}

/// An FMI enumeration type: items are numbered 1, 2, ... in the order given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnumType {
    pub name: &'static str,
    pub items: &'static [(&'static str, &'static str)],
}

impl EnumType {
    /// The integer value of an item, by name.
    pub fn value_of(&self, item: &str) -> Option<i32> {
        self.items
            .iter()
            .position(|(name, _)| *name == item)
            .map(|i| i as i32 + 1)
    }

    /// The items as importers read them: "1 split, 2 total".
    pub fn listing(&self) -> String {
        let items: Vec<String> = self
            .items
            .iter()
            .enumerate()
            .map(|(i, (name, _))| format!("{} {name}", i + 1))
            .collect();
        items.join(", ")
    }

    /// The item name of an integer value.
    pub fn item(&self, value: i32) -> Option<&'static str> {
        usize::try_from(value - 1)
            .ok()
            .and_then(|i| self.items.get(i))
            .map(|(name, _)| *name)
    }
}

/// A unit with its SI base-unit exponents (kg, m, s, A, rad as FMI names them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    pub name: &'static str,
    pub kg: i32,
    pub m: i32,
    pub s: i32,
    /// Ampere.
    pub a: i32,
    pub rad: i32,
}

/// The experiment a tool runs by default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: f64,
    pub stop_time: f64,
    pub tolerance: f64,
    pub step_size: f64,
}

/// An input that the model reads only when a switch has one item (`drive_source = input` reads
/// `vd_in`); with any other item, setting the input has no effect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InputSwitch {
    pub switch: &'static str,
    pub item: &'static str,
    pub input: &'static str,
}

/// Checks that an experiment's communication grid suits every importer: the step a whole number
/// of nanoseconds (libcosim's clock counts them), and `start + n step` equal to `stop` in double
/// precision for a whole n, so a master that computes its points as `start + i step` neither
/// stops short nor asks for a step past `stop`. Returns n.
pub fn communication_grid(start: f64, stop: f64, step: f64) -> Result<u64, Error> {
    let nanoseconds = step * 1e9;
    if (nanoseconds - nanoseconds.round()).abs() > 1e-6 || nanoseconds < 0.5 {
        return Err(Error::value_found(
            "step",
            format!("step = {step}"),
            "a whole number of nanoseconds (co-simulation engines such as libcosim count time in ns)",
        ));
    }
    let n = ((stop - start) / step).round();
    if !(n >= 1.0 && start + n * step == stop) {
        return Err(Error::value_found(
            "step",
            format!("step = {step}"),
            format!(
                "stop - start = {} to be a whole number of steps, start + n step = stop in double precision",
                stop - start
            ),
        ));
    }
    Ok(n as u64)
}

/// Everything modelDescription.xml says about one model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelTable {
    pub model_identifier: &'static str,
    pub description: &'static str,
    pub variables: &'static [Variable],
    pub enum_types: &'static [EnumType],
    /// The inputs each switch governs.
    pub input_switches: &'static [InputSwitch],
    /// Whether inputs may move linearly over a communication step (fmi2SetRealInputDerivatives,
    /// first order) and some outputs give first derivatives: modelDescription.xml declares
    /// canInterpolateInputs and maxOutputDerivativeOrder = 1. The simulation's own
    /// `set_input_derivative` is the runtime side of the same promise.
    pub interpolates_inputs: bool,
    /// The switch a variant's top-level `law` key sets; None for a model with no friction
    /// law, which a variant cannot trim.
    pub law_parameter: Option<&'static str>,
    /// The parameter the adaptive solvers integrate to, which the experiment's tolerance states.
    pub tolerance_parameter: Option<&'static str>,
    pub default_experiment: DefaultExperiment,
}

impl ModelTable {
    pub fn variable(&self, value_reference: u32) -> Option<&'static Variable> {
        self.variables
            .iter()
            .find(|v| v.value_reference == value_reference)
    }

    pub fn by_name(&self, name: &str) -> Option<&'static Variable> {
        self.variables.iter().find(|v| v.name == name)
    }

    pub fn enum_type(&self, name: &str) -> Option<&'static EnumType> {
        self.enum_types.iter().find(|e| e.name == name)
    }
}

/// The units every model may use; the XML lists only those a model refers to.
pub const UNITS: &[Unit] = &[
    Unit {
        name: "s",
        kg: 0,
        m: 0,
        s: 1,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "m",
        kg: 0,
        m: 1,
        s: 0,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "m/s",
        kg: 0,
        m: 1,
        s: -1,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "m/s2",
        kg: 0,
        m: 1,
        s: -2,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "kg",
        kg: 1,
        m: 0,
        s: 0,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "N",
        kg: 1,
        m: 1,
        s: -2,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "N/m",
        kg: 1,
        m: 0,
        s: -2,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "J",
        kg: 1,
        m: 2,
        s: -2,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "N.s/m",
        kg: 1,
        m: 0,
        s: -1,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "Hz",
        kg: 0,
        m: 0,
        s: -1,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "rad",
        kg: 0,
        m: 0,
        s: 0,
        a: 0,
        rad: 1,
    },
    Unit {
        name: "rad/s",
        kg: 0,
        m: 0,
        s: -1,
        a: 0,
        rad: 1,
    },
    Unit {
        name: "kg.m2",
        kg: 1,
        m: 2,
        s: 0,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "N.m.s/rad",
        kg: 1,
        m: 2,
        s: -1,
        a: 0,
        rad: -1,
    },
    Unit {
        name: "%",
        kg: 0,
        m: 0,
        s: 0,
        a: 0,
        rad: 0,
    },
    Unit {
        name: "V",
        kg: 1,
        m: 2,
        s: -3,
        a: -1,
        rad: 0,
    },
    Unit {
        name: "Ohm",
        kg: 1,
        m: 2,
        s: -3,
        a: -2,
        rad: 0,
    },
    Unit {
        name: "H",
        kg: 1,
        m: 2,
        s: -2,
        a: -2,
        rad: 0,
    },
    Unit {
        name: "A",
        kg: 0,
        m: 0,
        s: 0,
        a: 1,
        rad: 0,
    },
    Unit {
        name: "N.m/A",
        kg: 1,
        m: 2,
        s: -2,
        a: -1,
        rad: 0,
    },
    Unit {
        name: "V.s/rad",
        kg: 1,
        m: 2,
        s: -2,
        a: -1,
        rad: -1,
    },
];

/// Log categories declared in every modelDescription and accepted by fmi2SetDebugLogging.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    (
        "logStatusError",
        "Calls that fail: wrong state, bad value, step not completed",
    ),
    ("logStatusWarning", "Calls that succeed with a caveat"),
    ("logCalls", "The calls that change the instance, with their arguments: fmi2SetupExperiment, fmi2Enter/ExitInitializationMode, fmi2SetXXX, fmi2SetRealInputDerivatives, fmi2DoStep, fmi2Get/Set/DeSerializeFMUstate, fmi2Terminate, fmi2Reset"),
];

/// Unit-less "1" is written without a unit attribute.
pub const NO_UNIT: &str = "";
