//! Models: one module file and folder per model, declared below and listed in `list.rs`. A
//! model's simulation owns its state, its equations and its outputs; it reads parameters and
//! inputs from a [`ValueSet`] and knows nothing of FMI.
//!
//! Every model has the same parts under the same names. `<model>.rs`: the simulation, its `build`
//! (the [`Builder`]), its steps and what the FMI layer reads of it ([`Simulation`]). Its folder:
//! `start.rs` (the constructors `new` (the full model), `with_scope` (a trimmed one) and
//! `starting_from` (the state at the start time), and the periodic start), `table.rs` (the
//! variables), `switches.rs` (the switches' enums), `equations.rs`, `solver.rs` (the solver menu),
//! `stability.rs` (its cases in the stability matrix, feature `tools`), `tests.rs`,
//! `input_tests.rs` (inputs moving over a step), `documentation.html` (its page in the FMU) and,
//! where the model takes steps past the communication point (scenes T and O), `ahead.rs`. Other
//! files hold a model's own schemes (closed forms, the paper's algorithms). Different by nature:
//! DriveTrain is linear and steps by an exact propagator, so it has no solver menu (its `solver`
//! switch has one item) and no `solver.rs`, no periodic start, and its tests are all about its
//! inputs (no `input_tests.rs`); DryFrictionOscillator holds its input over each step, so it has no
//! `input_tests.rs` either.

// The models' modules are declared here, not by `models!` from list.rs: rustfmt does not
// follow modules a macro declares, and `cargo fmt` would leave their files unformatted and
// unchecked. A module list.rs names and this does not fails to compile.
pub mod drive;
pub mod input_scheme;
pub mod longitudinal;
pub mod oscillator;
pub mod period_mean;
#[cfg(test)]
mod pinned_runs;
pub mod ramp;
pub mod scope;
#[cfg(feature = "tools")]
pub mod stability;
pub mod switch;
pub mod transverse;

use crate::error::{Error, Failure};
use crate::variables::values::ValueSet;
use crate::variables::variable::ModelTable;
pub use scope::Scope;

/// A model running in one instance: its state, advanced in time. Errors say what was wrong and
/// what was expected ([`Error`]).
pub trait Simulation: Send {
    /// Advances from the simulation's current time by `h > 0`, reading inputs from `values`.
    fn do_step(&mut self, h: f64, values: &ValueSet) -> Result<(), Error>;

    /// Advances by `h > 0` where the step ends inside one already taken and read, which cannot
    /// fail (true); false, with nothing changed, where it does not. fmi2DoStep asks this first
    /// and saves no rollback for a step it answers. The default: never.
    fn read_inside(&mut self, _h: f64) -> bool {
        false
    }

    /// Writes every output variable into `values`, reading the inputs' current values there
    /// (outputs with direct feedthrough follow an input set after the last step).
    fn write_outputs(&self, values: &mut ValueSet);

    /// The simulation's current time.
    fn time(&self) -> f64;

    /// Writes the dynamic state as numbers into `out`, replacing what it held (parameters
    /// live in the [`ValueSet`]). Into a buffer the caller keeps: fmi2DoStep saves the state
    /// before every step that [`Simulation::read_inside`] does not answer, to roll a failed
    /// step back, and allocates nothing.
    fn save_into(&self, out: &mut Vec<f64>);

    /// The dynamic state as numbers, in a new vector.
    fn save(&self) -> Vec<f64> {
        let mut state = Vec::new();
        self.save_into(&mut state);
        state
    }

    /// Restores a state written by [`Simulation::save`] of a simulation built from the same
    /// values.
    fn restore(&mut self, state: &[f64]) -> Result<(), Error>;

    /// Takes the first time derivative of an input for the coming step only: the input then
    /// moves as `value + derivative (t - t_step)` over it. Models that hold their inputs over
    /// each step refuse (the default).
    fn set_input_derivative(&mut self, value_reference: u32, derivative: f64) -> Result<(), Error> {
        let _ = (value_reference, derivative);
        Err(held_inputs())
    }

    /// Drops the derivative set for an input, set again without one: over the coming step it
    /// moves as the model's input scheme says (held unless the model has one).
    fn drop_input_derivative(&mut self, value_reference: u32) {
        let _ = self.set_input_derivative(value_reference, 0.0);
    }

    /// The step the simulation's solver takes next, for an importer that takes intermediate
    /// updates at the internal steps; None where the simulation has no internal steps of its
    /// own to offer (a step is then one internal step). The default: none.
    fn next_internal_step(&self) -> Option<f64> {
        None
    }

    /// A warning the build or the last step left for the user (logged, the call itself having
    /// succeeded): once, then None. The default: none.
    fn take_warning(&mut self) -> Option<String> {
        None
    }

    /// The period the simulation's readings (means, amplitudes) are taken over and the relative
    /// accuracy asked of them, for [`clock_warning`]; None for one without such readings.
    fn reading_period(&self) -> Option<(f64, f64)> {
        None
    }

    /// The first time derivative of an output now, where it is exact and cheap (the inputs'
    /// current values are in `values`); refuses the others (the default: all).
    fn output_derivative(&self, value_reference: u32, values: &ValueSet) -> Result<f64, Error> {
        let _ = (value_reference, values);
        Err(Error::refused(
            format!("value reference {value_reference} has no derivative here"),
            "none: this model gives no output derivatives (maxOutputDerivativeOrder = 0)",
        ))
    }
}

/// The warning of a simulation whose explicit `solver` found the problem stiff from `t` on
/// ([`crate::solve::stiffness`]); `instead` names the solvers to use.
fn stiff_warning(t: f64, solver: &str, instead: &str) -> String {
    format!(
        "solver {solver} found the problem stiff from t = {t:e} s on: its steps are held by its stability, not by the tolerance, so the run is slow (though accurate); {instead} takes far fewer steps here"
    )
}

/// Far from t = 0 a double resolves time only to about ulp(t), and a master's communication
/// points, and with them where a period's reading starts and ends, round by that much. Once that
/// is more than `tolerance` of the `period`, the clock, not the solver, bounds the readings'
/// accuracy: said once a run (None while it is not so).
pub fn clock_warning(t: f64, (period, tolerance): (f64, f64)) -> Option<String> {
    let resolution = f64::EPSILON * t.abs();
    (resolution > tolerance * period).then(|| {
        format!(
            "at t = {t:e} s a double resolves time to {resolution:.1e} s, {:.1e} of the {period:e} s period the readings are taken over and more than the tolerance {tolerance:e}: means and amplitudes are now accurate to about that fraction only; start the experiment nearer t = 0",
            resolution / period
        )
    })
}

/// Whether `[start, end]` is a few ulps of the absolute time long: sub-step ends (a period's
/// boundary, a kink) that met in the clock's round-off. Nothing happens over it that the clock
/// resolves, and a solver counting time from the step's start would take it for a real interval.
pub fn within_round_off(start: f64, end: f64) -> bool {
    end - start <= 16.0 * f64::EPSILON * start.abs().max(end.abs())
}

/// The accuracy a fixed-step solver's period readings are held to for [`clock_warning`] (it has
/// no tolerance; its error is set by steps_per_period).
pub const FIXED_STEP_ACCURACY: f64 = 1e-9;

/// Why a simulation without input derivatives refuses one.
pub fn held_inputs() -> Error {
    Error::refused(
        "an input's derivative",
        "none: this model holds its inputs over each step (canInterpolateInputs = false)",
    )
}

/// Why a simulation refuses a derivative for `value_reference`, which is not one of its inputs.
pub fn not_an_input(value_reference: u32) -> Error {
    Error::refused(
        format!("value reference {value_reference}"),
        "an input's value reference",
    )
}

/// Why a simulation refuses the derivative of `value_reference`, which it does not give.
pub fn no_output_derivative(value_reference: u32) -> Error {
    Error::refused(
        format!("value reference {value_reference} has no derivative here"),
        "an output",
    )
}

/// Builds a simulation at `start_time` from parameter values, refusing inconsistent ones; `scope`
/// says what the interface hides, so the simulation may skip what nobody can see or change.
pub type Builder =
    fn(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Box<dyn Simulation>, Error>;

/// A model this crate exports, everything about it in one place: its interface (the variable
/// table, with which switches select which inputs and its law and tolerance parameters), how to
/// build it, and, for packing and the report, its documentation page and stability cases.
pub struct Model {
    pub table: &'static ModelTable,
    pub build: Builder,
    /// The model's page in the FMU's documentation/index.html, before its variables.
    #[cfg(feature = "tools")]
    pub documentation: &'static str,
    #[cfg(feature = "tools")]
    pub stability: stability::Cases,
}

// One constant per model, so that an FMU's library that names one links none of the others,
// and the registry of them all, from the list in src/models/list.rs.
macro_rules! models {
    ($($module:ident => $constant:ident),* $(,)?) => {
        $(
            pub const $constant: Model = Model {
                table: &$module::table::TABLE,
                build: $module::build,
                #[cfg(feature = "tools")]
                documentation: include_str!(concat!(stringify!($module), "/documentation.html")),
                #[cfg(feature = "tools")]
                stability: $module::stability::CASES,
            };
        )*

        /// Every model this crate exports, in the order the CLI builds them.
        pub const MODELS: &[Model] = &[$($constant),*];

        /// Every model's switch enums (its folder's switches.rs), and the input scheme's.
        #[cfg(test)]
        fn switch_enums() -> Vec<(&'static str, Vec<&'static str>)> {
            let mut enums = vec![switch::items::<input_scheme::InputScheme>()];
            $(enums.extend($module::switches::enums());)*
            enums
        }
    };
}
include!("list.rs");

pub fn model(model_identifier: &str) -> Option<&'static Model> {
    MODELS
        .iter()
        .find(|m| m.table.model_identifier == model_identifier)
}

/// A parameter value checked on its way into a simulation: `ok` says whether `x` is acceptable,
/// `expected` is how the message says what would be (the setters check the tables' ranges already;
/// these also guard values restored from FMU states and the models' own unit tests).
fn require(
    values: &ValueSet,
    value_reference: u32,
    ok: fn(f64) -> bool,
    expected: &str,
) -> Result<f64, Error> {
    let x = values.real(value_reference);
    if ok(x) {
        Ok(x)
    } else {
        let name = name_of(values, value_reference);
        Err(Error::value(name, x, expected.replace("{name}", name)))
    }
}

/// The name of the variable `value_reference` in `values`' table.
fn name_of(values: &ValueSet, value_reference: u32) -> &'static str {
    values
        .table
        .variable(value_reference)
        .map_or("?", |v| v.name)
}

/// An adaptive solver's relative tolerance, within what the solvers can meet.
pub fn require_tolerance(values: &ValueSet, value_reference: u32) -> Result<f64, Error> {
    require(
        values,
        value_reference,
        |x| (1e-14..=1e-2).contains(&x),
        "1e-14 <= {name} <= 0.01",
    )
}

/// A fixed-step solver's steps per period: at least 1.
pub fn require_steps(values: &ValueSet, value_reference: u32) -> Result<u32, Error> {
    let steps = values.integer(value_reference);
    u32::try_from(steps)
        .ok()
        .filter(|&s| s >= 1)
        .ok_or_else(|| {
            let name = name_of(values, value_reference);
            Error::value(name, steps, format!("{name} >= 1"))
        })
}

/// A strictly positive, finite parameter.
pub fn require_positive(values: &ValueSet, value_reference: u32) -> Result<f64, Error> {
    require(
        values,
        value_reference,
        |x| x > 0.0 && x.is_finite(),
        "{name} > 0",
    )
}

/// A finite parameter >= 0.
pub fn require_non_negative(values: &ValueSet, value_reference: u32) -> Result<f64, Error> {
    require(
        values,
        value_reference,
        |x| x >= 0.0 && x.is_finite(),
        "{name} >= 0",
    )
}

/// Errs unless the start time a simulation is built at is a finite number (the FMI layer checks it
/// too; simulations are also built in-process).
pub fn require_finite_start(start_time: f64) -> Result<(), Error> {
    if start_time.is_finite() {
        Ok(())
    } else {
        Err(Error::value("start time", start_time, "a finite number"))
    }
}

/// A communication step a simulation can take: finite and > 0 (the FMI layer checks it too;
/// simulations are also stepped in-process).
pub fn require_step(h: f64) -> Result<(), Error> {
    if h > 0.0 && h.is_finite() {
        Ok(())
    } else {
        Err(Error::value("communication step", h, "a finite step > 0"))
    }
}

/// Any finite value.
pub fn require_finite(values: &ValueSet, value_reference: u32) -> Result<f64, Error> {
    require(values, value_reference, f64::is_finite, "a finite number")
}

/// Errs unless a saved state (`Simulation::restore`'s input) has `expected` numbers, all finite.
pub fn check_saved(model: &str, state: &[f64], expected: usize) -> Result<(), Error> {
    let bad = state.iter().filter(|x| !x.is_finite()).count();
    if state.len() != expected {
        Err(Error::state(
            format!("a {model} state of {} numbers", state.len()),
            format!("{expected}"),
        ))
    } else if bad > 0 {
        Err(Error::state(
            format!("a {model} state with {bad} numbers that are not finite"),
            format!("{expected} finite numbers"),
        ))
    } else {
        Ok(())
    }
}

/// Errs when a contact has created energy: `dissipated` (the friction work minus `stored`, the
/// energy in the deflection) is below zero by more than `tolerance` times the energies it is the
/// difference of, plus `resolved`, the least energy the solver resolves (0 for a fixed step). A
/// fixed step beyond the solver's stability bound shows here first, while the state is still
/// finite but meaningless. The tolerance is far above the solvers' truncation error and far
/// below what an unstable step produces.
pub fn require_passive(
    solver: &'static str,
    (dissipated, stored): (f64, f64),
    tolerance: f64,
    resolved: f64,
    (t, advice): (f64, &str),
) -> Result<(), Error> {
    let scale = dissipated.abs() + stored.abs();
    if dissipated.is_finite() && stored.is_finite() && dissipated >= -(tolerance * scale + resolved)
    {
        Ok(())
    } else {
        Err(Error::step(
            solver,
            Failure::CreatedEnergy,
            format!("the contact created energy by t = {t} (dissipated {dissipated:e} J, stored {stored:e} J): the integration is unstable"),
            format!("a passive contact: {advice}"),
        ))
    }
}

/// The least energy an adaptive solver at `rtol` resolves in a contact of stiffness `kt` that
/// saturates at `fc`: its absolute tolerance on the deflection, rtol FC/kt, times the force at
/// saturation. Below it the energies are round-off of the tolerance, not a sign of instability
/// (scene L, Dahl at va 0.13 um/s: a contact at 1e-5 of FC/kt was read as creating energy).
pub fn resolved_energy(rtol: f64, fc: f64, kt: f64) -> f64 {
    rtol * fc * fc / kt
}

#[cfg(test)]
mod tests {
    use super::{switch_enums, Scope, MODELS};
    use crate::variables::values::ValueSet;
    use crate::variables::variable::{Causality, EnumType};

    /// Every switch type of every table has its enum, with the table's items in its order.
    #[test]
    fn every_switch_type_has_an_enum_with_its_items() {
        let enums = switch_enums();
        // A type several tables share (InputScheme) is the same const in each.
        let mut types: Vec<&EnumType> = MODELS.iter().flat_map(|m| m.table.enum_types).collect();
        types.sort_by_key(|t| t.name);
        types.dedup_by_key(|t| t.name);
        assert_eq!(enums.len(), types.len());
        for enum_type in types {
            let items: Vec<&str> = enum_type.items.iter().map(|(name, _)| *name).collect();
            let found = enums.iter().find(|(name, _)| *name == enum_type.name);
            assert_eq!(
                found.map(|(_, variants)| variants),
                Some(&items),
                "{}",
                enum_type.name
            );
        }
    }

    /// What modelDescription.xml declares (canInterpolateInputs) is what the models do: every
    /// input of an interpolating model takes a derivative, no input of another model does.
    #[test]
    fn models_take_input_derivatives_exactly_where_the_xml_says() {
        for model in MODELS {
            let values = ValueSet::start(model.table);
            let mut sim = (model.build)(&values, 0.0, &Scope::full()).unwrap();
            for input in model
                .table
                .variables
                .iter()
                .filter(|v| v.causality == Causality::Input)
            {
                assert_eq!(
                    sim.set_input_derivative(input.value_reference, 1.0).is_ok(),
                    model.table.interpolates_inputs,
                    "{} {}",
                    model.table.model_identifier,
                    input.name
                );
            }
        }
    }
}
