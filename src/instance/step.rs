//! One communication step, taken whole or one internal step at a time, and the rollback of one
//! that fails.

use super::calls::Call;
use super::log::CATEGORY_ERROR;
use super::phase::Phase::*;
use super::{Instance, Status};
use crate::models::clock_warning;

/// Where a step taken one internal step at a time is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stepped {
    /// An internal step ended at this time, inside the communication step.
    At(f64),
    /// The communication step ended (or failed) with this status.
    Done(Status),
}

/// The communication step under way.
#[derive(Clone, Copy, Debug)]
pub(super) struct StepUnderWay {
    start: f64,
    size: f64,
    target: f64,
    /// The worst status of its internal steps so far.
    status: Status,
}

impl Instance {
    /// Advances from `current_communication_point` (the instance's time, give or take the
    /// master's round-off) by `step`.
    pub fn do_step(&mut self, current_communication_point: f64, step: f64) -> Status {
        match self.begin_step(current_communication_point, step) {
            Ok(()) => self.advance(false),
            Err(status) => status,
        }
    }

    /// Starts a communication step that stops at each of the simulation's internal steps (for
    /// an importer that takes intermediate updates): [`Instance::next_internal_step`] then
    /// advances it, and between its internal steps the instance is in IntermediateUpdate,
    /// where outputs can be read and inputs set.
    pub fn begin_step_with_updates(
        &mut self,
        current_communication_point: f64,
        step: f64,
    ) -> Status {
        match self.begin_step(current_communication_point, step) {
            Ok(()) => {
                self.phase = IntermediateUpdate;
                Status::Ok
            }
            Err(status) => status,
        }
    }

    /// Takes the next internal step of the communication step under way: [`Stepped::At`] its end
    /// where the communication step goes on (the instance stays in IntermediateUpdate), or
    /// [`Stepped::Done`] with the step's status where it has ended or failed.
    pub fn next_internal_step(&mut self) -> Stepped {
        if self.phase != IntermediateUpdate {
            return Stepped::Done(self.error(&format!(
                "{}: no step under way: expected a step begun with intermediate updates",
                self.function(Call::DoStep)
            )));
        }
        self.phase = StepComplete;
        let status = self.advance(true);
        // An end within round-off of the target is the target.
        let going_on = self.step.is_some_and(|step| {
            self.time < step.target - 4.0 * f64::EPSILON * step.target.abs().max(step.size)
        });
        if self.phase == StepComplete && going_on {
            self.phase = IntermediateUpdate;
            Stepped::At(self.time)
        } else {
            Stepped::Done(status)
        }
    }

    /// Checks a step (its phase, size and start) and records it as the step under way.
    fn begin_step(&mut self, current_communication_point: f64, step: f64) -> Result<(), Status> {
        self.check_phase(Call::DoStep)?;
        let function = self.function(Call::DoStep);
        if !step.is_finite() || step <= 0.0 {
            return Err(self.error(&format!(
                "{function}: communicationStepSize = {step}: expected a finite step > 0"
            )));
        }
        let tolerance = 1e-12 * (1.0 + self.time.abs()) + 4.0 * f64::EPSILON * step;
        if !current_communication_point.is_finite()
            || (current_communication_point - self.time).abs() > tolerance
        {
            return Err(self.error(&format!(
                "{function}: expected currentCommunicationPoint = {} (within {tolerance:.1e} s: 1e-12 (1 + |t|) and 4 ulps of the step) but was {current_communication_point}",
                self.time
            )));
        }
        if let Some(stop) = self.stop_time {
            if current_communication_point + step > stop * (1.0 + 1e-12) + 1e-12 {
                return Err(self.error(&format!(
                    "{function}: the step to t = {} passes stopTime = {stop} set in {}",
                    current_communication_point + step,
                    self.function(Call::SetupExperiment)
                )));
            }
        }
        // The step ends where the master's clock says, currentCommunicationPoint + step, not at
        // our time + step: a master that computes its points as t0 + i h would otherwise drift
        // away from our sum of steps by round-off until the check above refuses it.
        let target = current_communication_point + step;
        if target <= self.time {
            return Err(self.error(&format!(
                "{function}: t = {current_communication_point} + communicationStepSize = {step} does not move past t in double precision: expected a step above {:e}",
                self.time.abs() * f64::EPSILON
            )));
        }
        if self.sim.is_none() {
            let exit = self.function(Call::ExitInitializationMode);
            return Err(self.error(&format!(
                "{function}: no simulation: {exit} has not succeeded"
            )));
        }
        self.step = Some(StepUnderWay {
            start: current_communication_point,
            size: step,
            target,
            status: Status::Ok,
        });
        Ok(())
    }

    /// Advances the step under way to its end, or (`one_internal_step`) by at most the
    /// simulation's next internal step; the step is over when it reaches its end or fails.
    fn advance(&mut self, one_internal_step: bool) -> Status {
        let function = self.function(Call::DoStep);
        let (Some(sim), Some(under_way)) = (self.sim.as_mut(), self.step) else {
            return self.error(&format!("{function}: no step under way"));
        };
        let StepUnderWay {
            start: current_communication_point,
            size: step,
            target,
            ..
        } = under_way;
        self.outputs_current = false;
        let rest = target - self.time;
        let h = match sim.next_internal_step() {
            // Not an internal step that would leave a sliver of the step for another.
            Some(internal) if one_internal_step && internal < 0.999 * rest => internal,
            _ => rest,
        };
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
                // a warning, with the message logged (FMI 2.0, 2.1.3).
                let clock = match sim.reading_period() {
                    Some(reading) if !self.clock_warned => clock_warning(self.time, reading),
                    _ => None,
                };
                self.clock_warned |= clock.is_some();
                let warnings = [sim.take_warning(), clock];
                let status = self.warn_all(function, &warnings).max(under_way.status);
                self.step = (self.time < target).then_some(StepUnderWay {
                    status,
                    ..under_way
                });
                status
            }
            Err(message) => {
                // Back to where the step (or its last internal step) started, so that outputs,
                // their derivatives and FMU states read now are those of lastSuccessfulTime,
                // not of a model stopped half-way (or of one that broke down: a non-finite
                // state).
                self.step = None;
                if let Err(why) = sim.restore(&self.rollback) {
                    self.phase = Error;
                    return self.error(&format!(
                        "{function}: the step from t = {current_communication_point} by {step} could not be completed ({message}), nor rolled back: {why}"
                    ));
                }
                self.phase = StepFailed;
                self.last_successful_time = self.time;
                self.logger.log(
                    Status::Discard,
                    CATEGORY_ERROR,
                    &format!(
                        "{function}: the step from t = {current_communication_point} by {step} could not be completed: {message}; the model is back at lastSuccessfulTime = {}",
                        self.last_successful_time
                    ),
                );
                Status::Discard
            }
        }
    }
}
