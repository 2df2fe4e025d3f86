//! One communication step, and the rollback of one that fails.

use super::calls::Call;
use super::log::CATEGORY_ERROR;
use super::phase::Phase::*;
use super::{Instance, Status};
use crate::models::clock_warning;

impl Instance {
    /// Advances from `current_communication_point` (the instance's time, give or take the
    /// master's round-off) by `step`.
    pub fn do_step(&mut self, current_communication_point: f64, step: f64) -> Status {
        if let Err(status) = self.check_phase(Call::DoStep) {
            return status;
        }
        let function = self.function(Call::DoStep);
        if !step.is_finite() || step <= 0.0 {
            return self.error(&format!(
                "{function}: communicationStepSize = {step}: expected a finite step > 0"
            ));
        }
        let tolerance = 1e-12 * (1.0 + self.time.abs()) + 4.0 * f64::EPSILON * step;
        if !current_communication_point.is_finite()
            || (current_communication_point - self.time).abs() > tolerance
        {
            return self.error(&format!(
                "{function}: expected currentCommunicationPoint = {} (within {tolerance:.1e} s: 1e-12 (1 + |t|) and 4 ulps of the step) but was {current_communication_point}",
                self.time
            ));
        }
        if let Some(stop) = self.stop_time {
            if current_communication_point + step > stop * (1.0 + 1e-12) + 1e-12 {
                return self.error(&format!(
                    "{function}: the step to t = {} passes stopTime = {stop} set in {}",
                    current_communication_point + step,
                    self.function(Call::SetupExperiment)
                ));
            }
        }
        // The step ends where the master's clock says, currentCommunicationPoint + step, not at
        // our time + step: a master that computes its points as t0 + i h would otherwise drift
        // away from our sum of steps by round-off until the check above refuses it.
        let target = current_communication_point + step;
        if target <= self.time {
            return self.error(&format!(
                "{function}: t = {current_communication_point} + communicationStepSize = {step} does not move past t in double precision: expected a step above {:e}",
                self.time.abs() * f64::EPSILON
            ));
        }
        let Some(sim) = self.sim.as_mut() else {
            let exit = self.function(Call::ExitInitializationMode);
            return self.error(&format!(
                "{function}: no simulation: {exit} has not succeeded"
            ));
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
                // a warning, with the message logged (FMI 2.0, 2.1.3).
                let clock = match sim.reading_period() {
                    Some(reading) if !self.clock_warned => clock_warning(self.time, reading),
                    _ => None,
                };
                self.clock_warned |= clock.is_some();
                let warnings = [sim.take_warning(), clock];
                self.warn_all(function, &warnings)
            }
            Err(message) => {
                // Back to where the step started, so that outputs, their derivatives and FMU
                // states read now are those of lastSuccessfulTime, not of a model stopped
                // half-way (or of one that broke down: a non-finite state).
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
