//! One FMU instance: the FMI 2.0 co-simulation state machine, shared by every model.
//!
//! Every public method checks that the call is legal in the current phase, does its work and
//! returns the status; every refusal is logged naming the function, what was wrong and what was
//! expected. The physics is the simulation's; this file only moves values and time.

use super::ffi::Status;
use super::logger::{Logger, CATEGORY_CALLS, CATEGORY_ERROR, CATEGORY_WARNING};
use crate::models::{clock_warning, Model, Scope, Simulation, HELD_INPUTS};
use crate::variables::unread_inputs::UnreadInputs;
use crate::variables::values::{check_value, ValueSet};
use crate::variables::variable::{
    Causality, Kind, ModelTable, Variability, Variable, LOG_CATEGORIES,
};
use crate::variant::registry::Loaded;
use std::sync::Arc;

/// Where an instance is in its life (FMI 2.0 co-simulation state machine).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    Instantiated,
    InitializationMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
}

impl Phase {
    /// Every phase, in the order of their codes.
    pub const ALL: [Phase; 6] = [
        Phase::Instantiated,
        Phase::InitializationMode,
        Phase::StepComplete,
        Phase::StepFailed,
        Phase::Terminated,
        Phase::Error,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Phase::Instantiated => "Instantiated",
            Phase::InitializationMode => "InitializationMode",
            Phase::StepComplete => "StepComplete",
            Phase::StepFailed => "StepFailed",
            Phase::Terminated => "Terminated",
            Phase::Error => "Error",
        }
    }

    pub fn code(self) -> f64 {
        self as u8 as f64
    }

    pub fn from_code(code: f64) -> Option<Phase> {
        Phase::ALL.into_iter().find(|p| p.code() == code)
    }
}

use super::calls::Call;
use Phase::*;

/// The most numbers a simulation's saved state holds (TransverseFriction reading a dopri5 step
/// taken ahead), with room to spare; `rollback_buffer_fits_every_model` checks it.
const ROLLBACK_CAPACITY: usize = 256;

pub struct Instance {
    pub id: u64,
    pub model: &'static Model,
    /// The full model's GUID; a variant's instance takes its own from `variant`.
    model_guid: &'static str,
    /// The variant a variant FMU's instance was made from; it lives as long as its instances.
    variant: Option<Arc<Loaded>>,
    logger: Logger,
    log_calls: bool,
    pub phase: Phase,
    pub values: ValueSet,
    /// The values fmi2Instantiate set and fmi2Reset restores: the model's start values, or a
    /// variant's.
    defaults: ValueSet,
    /// What the interface hides (nothing for a full model).
    pub scope: Scope,
    pub sim: Option<Box<dyn Simulation>>,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    pub time: f64,
    pub last_successful_time: f64,
    /// Addresses of the FMU states this instance handed out and has not freed.
    pub snapshots: Vec<usize>,
    /// The simulation's state at the start of the step under way, to roll a failed step back to
    /// lastSuccessfulTime. Room for every model's state from the start, so that fmi2DoStep
    /// never allocates (also after an FMU state with another solver is restored).
    rollback: Vec<f64>,
    /// Input derivatives set before the simulation exists (handed to it when it is built); once it
    /// exists they go straight to it. Capacity for every input, so setting never allocates.
    pending_derivatives: Vec<(u32, f64)>,
    /// Inputs set while their switch says they are not read.
    unread_inputs: UnreadInputs,
    /// Whether this run has said that the clock bounds the readings' accuracy.
    clock_warned: bool,
    /// Whether the outputs in `values` are those of the current state and inputs. Outputs are
    /// computed when a getter asks for one, not by every fmi2DoStep (a master that steps many
    /// times a reading would pay for them on every step), and then kept until the state, an
    /// input or a parameter changes.
    pub(super) outputs_current: bool,
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
    pub fn new(
        id: u64,
        model: &'static Model,
        guid: &'static str,
        logger: Logger,
        log_calls: bool,
    ) -> Self {
        Instance {
            id,
            model,
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
    /// replace the model's start values (also for fmi2Reset), its scope hides what its interface
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

    pub fn error(&self, message: &str) -> Status {
        self.logger.log(Status::Error, CATEGORY_ERROR, message);
        Status::Error
    }

    pub fn warning(&self, message: &str) {
        self.logger.log(Status::Warning, CATEGORY_WARNING, message);
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
            call.name(),
            self.phase.name(),
            call.expected()
        )))
    }

    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[String]) -> Status {
        if let Err(status) = self.check_phase(Call::SetDebugLogging) {
            return status;
        }
        for category in categories {
            if !LOG_CATEGORIES.iter().any(|(name, _)| name == category) {
                let known: Vec<&str> = LOG_CATEGORIES.iter().map(|(name, _)| *name).collect();
                return self.error(&format!(
                    "fmi2SetDebugLogging: unknown log category \"{category}\": expected one of {}",
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
        if !start_time.is_finite() {
            return self.error(&format!(
                "fmi2SetupExperiment: startTime = {start_time}: expected a finite time"
            ));
        }
        if let Some(stop) = stop_time {
            if stop.is_nan() || stop < start_time {
                return self.error(&format!(
                    "fmi2SetupExperiment: stopTime = {stop}: expected a time >= startTime = {start_time}"
                ));
            }
        }
        if let Some(tolerance) = tolerance {
            if tolerance.is_nan() || tolerance <= 0.0 {
                return self.error(&format!(
                    "fmi2SetupExperiment: tolerance = {tolerance}: expected > 0"
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
                    return self.error(&format!("fmi2ExitInitializationMode: {message}"));
                }
                self.sim = Some(sim);
                self.time = self.start_time;
                self.last_successful_time = self.start_time;
                self.phase = StepComplete;
                let warnings = [
                    found,
                    self.unread_inputs.start(self.model.table, &self.values),
                ];
                for message in warnings.iter().flatten() {
                    self.warning(&format!("fmi2ExitInitializationMode: {message}"));
                }
                if warnings.iter().any(Option::is_some) {
                    Status::Warning
                } else {
                    Status::Ok
                }
            }
            Err(message) => self.error(&format!("fmi2ExitInitializationMode: {message}")),
        }
    }

    pub fn terminate(&mut self) -> Status {
        if let Err(status) = self.check_phase(Call::Terminate) {
            return status;
        }
        self.phase = Terminated;
        Status::Ok
    }

    /// Back to the state right after fmi2Instantiate: start values, no simulation, time 0.
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
        self.clock_warned = false;
        self.outputs_current = false;
        Status::Ok
    }

    /// The variable a value reference names in this FMU's interface; a variable a variant
    /// hides is refused exactly as one that does not exist.
    pub fn variable(
        &self,
        function: &str,
        value_reference: u32,
        accepts: fn(&Kind) -> bool,
        type_name: &str,
    ) -> Result<&'static Variable, Status> {
        let visible = self
            .position(value_reference)
            .map(|position| &self.model.table.variables[position])
            .filter(|v| self.scope.exposes(v.value_reference));
        match visible {
            Some(var) if accepts(&var.kind) => Ok(var),
            Some(var) => Err(self.error(&format!(
                "{function}: value reference {value_reference} is {}, not a {type_name} variable",
                var.name
            ))),
            None => Err(self.error(&format!(
                "{function}: unknown value reference {value_reference}: {} has no variable with it",
                self.name()
            ))),
        }
    }

    /// Where a value reference's variable is in the model's table and in `values`.
    fn position(&self, value_reference: u32) -> Option<usize> {
        let position = *self.positions.get(value_reference as usize)?;
        (position != NO_VARIABLE).then_some(usize::from(position))
    }

    /// Outputs follow the current state and inputs; in initialisation mode they are computed
    /// from a simulation built from the values set so far. Computed once until either changes.
    fn refresh_outputs(&mut self, function: &str) -> Result<(), Status> {
        if self.outputs_current {
            return Ok(());
        }
        if let Some(sim) = &self.sim {
            sim.write_outputs(&mut self.values);
            self.outputs_current = true;
            return Ok(());
        }
        match (self.model.build)(&self.values, self.start_time, &self.scope) {
            Ok(sim) => {
                sim.write_outputs(&mut self.values);
                self.outputs_current = true;
                Ok(())
            }
            Err(message) => Err(self.error(&format!(
                "{function}: outputs cannot be computed: {message}"
            ))),
        }
    }

    /// Reads values of one FMI type, handing each to `out(index, value)`; `accepts` says which
    /// variable kinds that type covers.
    pub fn get(
        &mut self,
        call: Call,
        value_references: &[u32],
        out: &mut dyn FnMut(usize, f64),
        accepts: fn(&Kind) -> bool,
        type_name: &str,
    ) -> Status {
        if let Err(status) = self.check_phase(call) {
            return status;
        }
        let function = call.name();
        // Two passes over the references instead of a list of variables: getters run every
        // communication step, and allocate nothing.
        let mut any_output = false;
        for &vr in value_references {
            match self.variable(function, vr, accepts, type_name) {
                Ok(var) => any_output |= var.causality == Causality::Output,
                Err(status) => return status,
            }
        }
        if any_output {
            if let Err(status) = self.refresh_outputs(function) {
                return status;
            }
        }
        // No NaN reaches the master silently (a simulation can produce one where it cannot be
        // evaluated, e.g. at an absurd start time, or a step can leave one in an output). Every
        // reference was found above.
        let values = self.values.as_slice();
        let value = |vr: u32| {
            self.position(vr)
                .map_or(f64::NAN, |position| values[position])
        };
        if let Some(&vr) = value_references.iter().find(|&&vr| !value(vr).is_finite()) {
            let name = self.model.table.variable(vr).map_or("?", |v| v.name);
            return self.error(&format!(
                "{function}: {name} is {} at t = {}: the model cannot be evaluated there; expected a finite value",
                value(vr),
                self.time
            ));
        }
        for (i, &vr) in value_references.iter().enumerate() {
            out(i, value(vr));
        }
        Status::Ok
    }

    /// Writes values of one FMI type after checking them all: either every value is stored or
    /// none is.
    pub fn set(
        &mut self,
        call: Call,
        value_references: &[u32],
        value_at: &dyn Fn(usize) -> f64,
        accepts: fn(&Kind) -> bool,
        type_name: &str,
    ) -> Status {
        if let Err(status) = self.check_phase(call) {
            return status;
        }
        let function = call.name();
        for (i, &vr) in value_references.iter().enumerate() {
            let value = value_at(i);
            let var = match self.variable(function, vr, accepts, type_name) {
                Ok(var) => var,
                Err(status) => return status,
            };
            let writable = match var.causality {
                Causality::Input => true,
                Causality::Parameter => {
                    self.phase != StepComplete || var.variability == Variability::Tunable
                }
                Causality::Output | Causality::Independent => {
                    return self.error(&format!(
                        "{function}: {} is an output: it can be read, not set",
                        var.name
                    ))
                }
            };
            if !writable {
                return self.error(&format!(
                    "{function}: {} is a fixed parameter: it can be set only before fmi2ExitInitializationMode (current state {})",
                    var.name,
                    self.phase.name()
                ));
            }
            if let Err(message) = check_value(self.model.table, var, value) {
                return self.error(&format!("{function}: {message}"));
            }
        }
        let mut status = Status::Ok;
        if !value_references.is_empty() {
            self.outputs_current = false;
        }
        for (i, &vr) in value_references.iter().enumerate() {
            self.values.set(vr, value_at(i));
            let running = self.phase == StepComplete;
            if let Some(message) =
                self.unread_inputs
                    .set(self.model.table, &self.values, vr, running)
            {
                self.warning(&format!("{function}: {message}"));
                status = Status::Warning;
            }
            // An input set again without a derivative moves as the model's input scheme says:
            // held unless told otherwise (FMI 2.0, 4.2.1, leaves this open; holding is what a
            // master that sets no derivative means).
            if self.model.table.interpolates_inputs
                && self.model.table.variable(vr).map(|v| v.causality) == Some(Causality::Input)
            {
                self.pending_derivatives.retain(|&(r, _)| r != vr);
                if let Some(sim) = self.sim.as_mut() {
                    sim.drop_input_derivative(vr);
                }
            }
        }
        status
    }

    /// The variable a derivative call names: a Real input (to set) or output (to get), at
    /// order 1, the only one these FMUs declare (maxOutputDerivativeOrder = 1, first-order input
    /// interpolation).
    fn derivative_variable(
        &self,
        function: &str,
        value_reference: u32,
        order: i32,
        causality: Causality,
    ) -> Result<&'static Variable, Status> {
        let var = self.variable(
            function,
            value_reference,
            |k| matches!(k, Kind::Real { .. }),
            "Real",
        )?;
        let (role, rule) = if causality == Causality::Input {
            ("an input", "only inputs take derivatives")
        } else {
            ("an output", "only outputs have derivatives to get")
        };
        if var.causality != causality {
            return Err(self.error(&format!("{function}: {} is not {role}: {rule}", var.name)));
        }
        if order != 1 {
            return Err(self.error(&format!(
                "{function}: order {order} for {}: expected order 1, the only one here (maxOutputDerivativeOrder = 1; inputs move linearly over a step)",
                var.name
            )));
        }
        Ok(var)
    }

    /// fmi2SetRealInputDerivatives: first derivatives of inputs for the next fmi2DoStep only.
    /// All are checked before any is stored.
    pub fn set_input_derivatives(
        &mut self,
        value_references: &[u32],
        orders: &[i32],
        derivatives: &[f64],
    ) -> Status {
        const FUNCTION: &str = "fmi2SetRealInputDerivatives";
        if let Err(status) = self.check_phase(Call::SetRealInputDerivatives) {
            return status;
        }
        if !self.model.table.interpolates_inputs {
            return self.error(&format!("{FUNCTION}: {HELD_INPUTS}"));
        }
        for ((&vr, &order), &derivative) in value_references.iter().zip(orders).zip(derivatives) {
            let var = match self.derivative_variable(FUNCTION, vr, order, Causality::Input) {
                Ok(var) => var,
                Err(status) => return status,
            };
            if !derivative.is_finite() {
                return self.error(&format!(
                    "{FUNCTION}: the derivative of {} is {derivative}: expected a finite number",
                    var.name
                ));
            }
        }
        if !value_references.is_empty() {
            self.outputs_current = false;
        }
        for (&vr, &derivative) in value_references.iter().zip(derivatives) {
            match self.sim.as_mut() {
                Some(sim) => {
                    if let Err(message) = sim.set_input_derivative(vr, derivative) {
                        return self.error(&format!("{FUNCTION}: {message}"));
                    }
                }
                None => {
                    self.pending_derivatives.retain(|&(r, _)| r != vr);
                    self.pending_derivatives.push((vr, derivative));
                }
            }
        }
        Status::Ok
    }

    /// fmi2GetRealOutputDerivatives: first derivatives of outputs at the current time, where
    /// the simulation has them exactly.
    pub fn get_output_derivatives(
        &mut self,
        value_references: &[u32],
        orders: &[i32],
        out: &mut [f64],
    ) -> Status {
        const FUNCTION: &str = "fmi2GetRealOutputDerivatives";
        if let Err(status) = self.check_phase(Call::GetRealOutputDerivatives) {
            return status;
        }
        if !self.model.table.interpolates_inputs {
            return self.error(&format!(
                "{FUNCTION}: this model gives no output derivatives (maxOutputDerivativeOrder = 0)"
            ));
        }
        for (i, (&vr, &order)) in value_references.iter().zip(orders).enumerate() {
            let var = match self.derivative_variable(FUNCTION, vr, order, Causality::Output) {
                Ok(var) => var,
                Err(status) => return status,
            };
            let Some(sim) = self.sim.as_ref() else {
                return self.error(&format!(
                    "{FUNCTION}: no simulation: fmi2ExitInitializationMode has not succeeded"
                ));
            };
            match sim.output_derivative(vr, &self.values) {
                Ok(x) if x.is_finite() => out[i] = x,
                Ok(x) => {
                    return self.error(&format!(
                    "{FUNCTION}: the derivative of {} is {x} at t = {}: expected a finite value",
                    var.name, self.time
                ))
                }
                Err(message) => return self.error(&format!("{FUNCTION}: {}: {message}", var.name)),
            }
        }
        Status::Ok
    }

    pub fn do_step(&mut self, current_communication_point: f64, step: f64) -> Status {
        if let Err(status) = self.check_phase(Call::DoStep) {
            return status;
        }
        if !step.is_finite() || step <= 0.0 {
            return self.error(&format!(
                "fmi2DoStep: communicationStepSize = {step}: expected a finite step > 0"
            ));
        }
        let tolerance = 1e-12 * (1.0 + self.time.abs()) + 4.0 * f64::EPSILON * step;
        if !current_communication_point.is_finite()
            || (current_communication_point - self.time).abs() > tolerance
        {
            return self.error(&format!(
                "fmi2DoStep: expected currentCommunicationPoint = {} (within {tolerance:.1e} s: 1e-12 (1 + |t|) and 4 ulps of the step) but was {current_communication_point}",
                self.time
            ));
        }
        if let Some(stop) = self.stop_time {
            if current_communication_point + step > stop * (1.0 + 1e-12) + 1e-12 {
                return self.error(&format!(
                    "fmi2DoStep: the step to t = {} passes stopTime = {stop} set in fmi2SetupExperiment",
                    current_communication_point + step
                ));
            }
        }
        // The step ends where the master's clock says, currentCommunicationPoint + step, not at
        // our time + step: a master that computes its points as t0 + i h would otherwise drift
        // away from our sum of steps by round-off until the check above refuses it.
        let target = current_communication_point + step;
        if target <= self.time {
            return self.error(&format!(
                "fmi2DoStep: t = {current_communication_point} + communicationStepSize = {step} does not move past t in double precision: expected a step above {:e}",
                self.time.abs() * f64::EPSILON
            ));
        }
        let Some(sim) = self.sim.as_mut() else {
            return self
                .error("fmi2DoStep: no simulation: fmi2ExitInitializationMode has not succeeded");
        };
        self.outputs_current = false;
        let h = target - self.time;
        // A step read inside one taken before cannot fail: it needs no rollback.
        let result = if sim.read_inside(h) {
            Ok(())
        } else {
            sim.save_into(&mut self.rollback);
            sim.do_step(h, &self.values)
        };
        match result {
            Ok(()) => {
                // The simulations check their states; the outputs are computed when they are read,
                // and the getters refuse a non-finite one, so no NaN reaches the master silently.
                self.time = sim.time();
                self.last_successful_time = self.time;
                // A step that succeeded but left a warning (a solver that is a poor fit):
                // fmi2Warning, with the message logged (FMI 2.0, 2.1.3).
                let clock = match sim.reading_period() {
                    Some(reading) if !self.clock_warned => clock_warning(self.time, reading),
                    _ => None,
                };
                self.clock_warned |= clock.is_some();
                let warnings = [sim.take_warning(), clock];
                for message in warnings.iter().flatten() {
                    self.warning(&format!("fmi2DoStep: {message}"));
                }
                if warnings.iter().any(Option::is_some) {
                    Status::Warning
                } else {
                    Status::Ok
                }
            }
            Err(message) => {
                // Back to where the step started, so that outputs, their derivatives and FMU
                // states read now are those of lastSuccessfulTime, not of a model stopped
                // half-way (or of one that broke down: a non-finite state).
                if let Err(why) = sim.restore(&self.rollback) {
                    self.phase = Error;
                    return self.error(&format!(
                        "fmi2DoStep: the step from t = {current_communication_point} by {step} could not be completed ({message}), nor rolled back: {why}"
                    ));
                }
                self.phase = StepFailed;
                self.last_successful_time = self.time;
                self.logger.log(
                    Status::Discard,
                    CATEGORY_ERROR,
                    &format!(
                        "fmi2DoStep: the step from t = {current_communication_point} by {step} could not be completed: {message}; the model is back at lastSuccessfulTime = {}",
                        self.last_successful_time
                    ),
                );
                Status::Discard
            }
        }
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
