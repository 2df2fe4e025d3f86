//! One FMU instance, whichever standard calls it: phases, values, FMU states, logging, and the
//! table of which call is legal when ([`calls`]). Each standard's boundary (`src/fmi2`,
//! `src/fmi3`) turns C arguments into Rust ones, calls a method here and turns the [`Status`]
//! back; the instance never asks which standard that is, and names calls and phases in its
//! messages as the [`Dialect`] it was made with says.
//!
//! Every public method checks that the call is legal in the current phase, does its work and
//! returns the status; every refusal is logged naming the function, what was wrong and what was
//! expected. The physics is the simulation's; this module only moves values and time.

pub mod calls;
pub mod handles;
pub mod library;
pub mod log;
pub mod phase;
pub mod snapshot;
mod states;
mod step;
pub use step::Stepped;
mod values;

use crate::models::{Model, Scope, Simulation};
use crate::variables::unread_inputs::UnreadInputs;
use crate::variables::values::ValueSet;
use crate::variables::variable::{Causality, ModelTable, LOG_CATEGORIES};
use crate::variant::registry::Loaded;
use calls::{Call, Dialect};
pub use log::Status;
use log::{LogSink, CATEGORY_CALLS, CATEGORY_ERROR, CATEGORY_WARNING};
use phase::Phase::{self, *};
use snapshot::Snapshot;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// The next instance's id: ids are never reused, so a freed handle names no later instance.
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// The most numbers a simulation's saved state holds (TransverseFriction reading a dopri5 step
/// taken ahead), with room to spare; `rollback_buffer_fits_every_model` checks it.
const ROLLBACK_CAPACITY: usize = 256;

pub struct Instance {
    id: u64,
    model: &'static Model,
    /// How the standard that made the instance names its calls and phases.
    dialect: &'static Dialect,
    /// The full model's GUID; a variant's instance takes its own from `variant`.
    model_guid: &'static str,
    /// The variant a variant FMU's instance was made from; it lives as long as its instances.
    variant: Option<Arc<Loaded>>,
    logger: Box<dyn LogSink>,
    log_calls: bool,
    phase: Phase,
    values: ValueSet,
    /// The values instantiation set and a reset restores: the model's start values, or a
    /// variant's.
    defaults: ValueSet,
    /// What the interface hides (nothing for a full model).
    scope: Scope,
    sim: Option<Box<dyn Simulation>>,
    start_time: f64,
    stop_time: Option<f64>,
    time: f64,
    last_successful_time: f64,
    /// The FMU states this instance handed out and has not freed; the importer holds their
    /// addresses, so each state is boxed: its address must not move as the list grows.
    #[allow(clippy::vec_box)]
    snapshots: Vec<Box<Snapshot>>,
    /// The simulation's state at the start of the step under way, to roll a failed step back to
    /// lastSuccessfulTime. Room for every model's state from the start, so that a step
    /// never allocates (also after an FMU state with another solver is restored).
    rollback: Vec<f64>,
    /// Input derivatives set before the simulation exists (handed to it when it is built); once it
    /// exists they go straight to it. Capacity for every input, so setting never allocates.
    pending_derivatives: Vec<(u32, f64)>,
    /// Inputs set while their switch says they are not read.
    unread_inputs: UnreadInputs,
    /// The communication step under way: while its internal steps are taken one at a time, and
    /// until a step has ended.
    step: Option<step::StepUnderWay>,
    /// Whether this run has said that the clock bounds the readings' accuracy.
    clock_warned: bool,
    /// Whether the outputs in `values` are those of the current state and inputs. Outputs are
    /// computed when a getter asks for one, not by every step (a master that steps many
    /// times a reading would pay for them on every step), and then kept until the state, an
    /// input or a parameter changes.
    outputs_current: bool,
    /// Each value reference's position in the model's table, and so in `values`
    /// ([`NO_VARIABLE`] for a number that names none): getters and setters run every
    /// communication step, and this spares them a search of the table for each reference
    /// (docs/performance.md, Cost per call).
    positions: Vec<u16>,
}

/// A value reference that names no variable, in [`Instance::positions`].
const NO_VARIABLE: u16 = u16::MAX;

/// Each value reference's position in `table` (see [`Instance::positions`]).
fn positions(table: &ModelTable) -> Vec<u16> {
    let largest = table.variables.iter().map(|v| v.value_reference).max();
    let mut positions = vec![NO_VARIABLE; largest.map_or(0, |vr| vr as usize + 1)];
    for (position, var) in table.variables.iter().enumerate() {
        positions[var.value_reference as usize] =
            u16::try_from(position).expect("a model has fewer than 65535 variables");
    }
    positions
}

impl Instance {
    /// A new instance of `model` whose FMU has `guid`, speaking `dialect`, logging to `logger`.
    pub fn new(
        model: &'static Model,
        guid: &'static str,
        dialect: &'static Dialect,
        logger: Box<dyn LogSink>,
        log_calls: bool,
    ) -> Self {
        Instance {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            model,
            dialect,
            model_guid: guid,
            variant: None,
            logger,
            log_calls,
            phase: Instantiated,
            values: ValueSet::start(model.table),
            defaults: ValueSet::start(model.table),
            scope: Scope::full(),
            sim: None,
            start_time: 0.0,
            stop_time: None,
            time: 0.0,
            last_successful_time: 0.0,
            snapshots: Vec::new(),
            rollback: Vec::with_capacity(ROLLBACK_CAPACITY),
            unread_inputs: UnreadInputs::default(),
            step: None,
            clock_warned: false,
            outputs_current: false,
            positions: positions(model.table),
            pending_derivatives: Vec::with_capacity(
                model
                    .table
                    .variables
                    .iter()
                    .filter(|v| v.causality == Causality::Input)
                    .count(),
            ),
        }
    }

    /// The instance of a variant's FMU: the file's name is its modelIdentifier, its values
    /// replace the model's start values (also for a reset), its scope hides what its interface
    /// leaves out.
    pub fn for_variant(mut self, loaded: Arc<Loaded>) -> Self {
        self.values.clone_from(&loaded.variant.values);
        self.defaults.clone_from(&loaded.variant.values);
        self.scope.clone_from(&loaded.scope);
        self.variant = Some(loaded);
        self
    }

    /// The FMU's modelIdentifier: the model's, or a variant's name.
    pub fn name(&self) -> &str {
        self.variant
            .as_ref()
            .map_or(self.model.table.model_identifier, |f| &f.variant.name)
    }

    pub fn guid(&self) -> &str {
        self.variant.as_ref().map_or(self.model_guid, |f| &f.guid)
    }

    /// The C function of `call` in the standard that made this instance.
    pub fn function(&self, call: Call) -> &'static str {
        (self.dialect.function)(call)
    }

    /// The standard's name of `phase`.
    fn phase_name(&self, phase: Phase) -> &'static str {
        (self.dialect.phase)(phase)
    }

    pub fn error(&self, message: &str) -> Status {
        self.logger.log(Status::Error, CATEGORY_ERROR, message);
        Status::Error
    }

    pub fn warning(&self, message: &str) {
        self.logger.log(Status::Warning, CATEGORY_WARNING, message);
    }

    /// Logs each of `warnings` that is there, after the function's name: a warning status
    /// where there is one, OK where there is none.
    fn warn_all(&self, function: &str, warnings: &[Option<String>]) -> Status {
        let mut status = Status::Ok;
        for message in warnings.iter().flatten() {
            self.warning(&format!("{function}: {message}"));
            status = Status::Warning;
        }
        status
    }

    pub fn trace(&self, message: impl FnOnce() -> String) {
        if self.log_calls {
            self.logger.log(Status::Ok, CATEGORY_CALLS, &message());
        }
    }

    /// Refuses a call outside the phases [`Call`]'s table allows it in, naming them.
    pub fn check_phase(&self, call: Call) -> Result<(), Status> {
        if call.allowed_in(self.phase) {
            return Ok(());
        }
        Err(self.error(&format!(
            "{} is not allowed in state {}: expected {}",
            self.function(call),
            self.phase_name(self.phase),
            self.dialect.expected(call)
        )))
    }

    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[String]) -> Status {
        if let Err(status) = self.check_phase(Call::SetDebugLogging) {
            return status;
        }
        let function = self.function(Call::SetDebugLogging);
        for category in categories {
            if !LOG_CATEGORIES.iter().any(|(name, _)| name == category) {
                let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(name, _)| *name).collect();
                return self.error(&format!(
                    "{function}: unknown log category \"{category}\": expected one of {}",
                    known.join(", ")
                ));
            }
        }
        // Errors and warnings are always reported; the switch governs the call trace.
        if categories.is_empty() || categories.iter().any(|c| c == CATEGORY_CALLS) {
            self.log_calls = logging_on;
        }
        Status::Ok
    }

    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Status {
        if let Err(status) = self.check_phase(Call::SetupExperiment) {
            return status;
        }
        let function = self.function(Call::SetupExperiment);
        if !start_time.is_finite() {
            return self.error(&format!(
                "{function}: startTime = {start_time}: expected a finite time"
            ));
        }
        if let Some(stop) = stop_time {
            if stop.is_nan() || stop < start_time {
                return self.error(&format!(
                    "{function}: stopTime = {stop}: expected a time >= startTime = {start_time}"
                ));
            }
        }
        if let Some(tolerance) = tolerance {
            if tolerance.is_nan() || tolerance <= 0.0 {
                return self.error(&format!(
                    "{function}: tolerance = {tolerance}: expected > 0"
                ));
            }
        }
        self.start_time = start_time;
        self.stop_time = stop_time;
        self.time = start_time;
        self.last_successful_time = start_time;
        self.outputs_current = false;
        Status::Ok
    }

    pub fn enter_initialization_mode(&mut self) -> Status {
        if let Err(status) = self.check_phase(Call::EnterInitializationMode) {
            return status;
        }
        self.phase = InitializationMode;
        Status::Ok
    }

    pub fn exit_initialization_mode(&mut self) -> Status {
        if let Err(status) = self.check_phase(Call::ExitInitializationMode) {
            return status;
        }
        let function = self.function(Call::ExitInitializationMode);
        self.outputs_current = false;
        match (self.model.build)(&self.values, self.start_time, &self.scope) {
            Ok(mut sim) => {
                // What the build could not mend (a periodic start that fell back to the
                // transient, a law the solvers cannot resolve): said by the call that built it.
                let found = sim.take_warning();
                let handed = self
                    .pending_derivatives
                    .iter()
                    .try_for_each(|&(vr, derivative)| sim.set_input_derivative(vr, derivative));
                self.pending_derivatives.clear();
                if let Err(message) = handed {
                    return self.error(&format!("{function}: {message}"));
                }
                self.sim = Some(sim);
                self.time = self.start_time;
                self.last_successful_time = self.start_time;
                self.phase = StepComplete;
                let warnings = [
                    found,
                    self.unread_inputs.start(self.model.table, &self.values),
                ];
                self.warn_all(function, &warnings)
            }
            Err(message) => self.error(&format!("{function}: {message}")),
        }
    }

    pub fn terminate(&mut self) -> Status {
        if let Err(status) = self.check_phase(Call::Terminate) {
            return status;
        }
        self.phase = Terminated;
        Status::Ok
    }

    /// Back to the state right after instantiation: start values, no simulation, time 0.
    pub fn reset(&mut self) -> Status {
        if let Err(status) = self.check_phase(Call::Reset) {
            return status;
        }
        self.phase = Instantiated;
        self.values.clone_from(&self.defaults);
        self.sim = None;
        self.start_time = 0.0;
        self.stop_time = None;
        self.time = 0.0;
        self.last_successful_time = 0.0;
        self.pending_derivatives.clear();
        self.unread_inputs.clear();
        self.step = None;
        self.clock_warned = false;
        self.outputs_current = false;
        Status::Ok
    }

    /// A refusal of a NULL argument of `call`.
    pub fn null_argument(&self, call: Call, what: &str) -> Status {
        self.error(&format!(
            "{}: {what} is NULL: expected a valid pointer",
            self.function(call)
        ))
    }

    /// Whether the last step could not be completed (the instance is back at
    /// lastSuccessfulTime).
    pub fn step_discarded(&self) -> bool {
        self.phase == StepFailed
    }

    /// The time the last step reached, or the time it was rolled back to.
    pub fn last_successful_time(&self) -> f64 {
        self.last_successful_time
    }

    /// Whether the instance asks the master to end: it reached the stop time, or has ended.
    pub fn asks_to_end(&self) -> bool {
        let at_stop = self.stop_time.is_some_and(|stop| self.time >= stop);
        at_stop || self.phase == Terminated
    }

    /// Logs a refusal of what this FMU does not offer, after the phase check, and returns
    /// the error.
    pub fn unsupported(&self, call: Call, why: &str) -> Status {
        if let Err(status) = self.check_phase(call) {
            return status;
        }
        self.error(why)
    }
}

#[cfg(test)]
mod tests {
    use super::ROLLBACK_CAPACITY;
    use crate::models::{Scope, MODELS};
    use crate::report::stability::solvers;
    use crate::variables::values::ValueSet;

    /// fmi2DoStep saves the simulation into a buffer of this capacity before every step that
    /// integrates; a state that did not fit would allocate there.
    #[test]
    fn rollback_buffer_fits_every_model() {
        for model in MODELS {
            let table = model.table;
            let id = table.model_identifier;
            // Each solver item by its code (items count from 1), and the model's defaults.
            let codes = (1..=solvers(id).len()).map(Some).chain([None]);
            for code in codes {
                let mut values = ValueSet::start(table);
                if let Some(code) = code {
                    let var = table.by_name("solver").expect("a solver parameter");
                    values.set(var.value_reference, code as f64);
                }
                let mut sim = (model.build)(&values, 0.0, &Scope::full())
                    .unwrap_or_else(|e| panic!("{id} solver {code:?}: {e}"));
                // Calls far shorter than the solvers' steps: those that take steps ahead then
                // hold one.
                for _ in 0..=20 {
                    let saved = sim.save().len();
                    assert!(
                        saved <= ROLLBACK_CAPACITY,
                        "{id} solver {code:?}: {saved} numbers"
                    );
                    sim.do_step(1e-7, &values)
                        .unwrap_or_else(|e| panic!("{id} solver {code:?}: {e}"));
                }
            }
        }
    }
}
