//! Reading and writing variables, and the inputs' and outputs' derivatives.

use super::calls::Call;
use super::phase::Phase::*;
use super::{Instance, Status, NO_VARIABLE};
use crate::models::held_inputs;
use crate::variables::values::check_value;
use crate::variables::variable::{Causality, Kind, Variability, Variable};

impl Instance {
    /// The variable a value reference names in this FMU's interface; a variable a variant
    /// hides is refused exactly as one that does not exist.
    pub fn variable(
        &self,
        function: &str,
        value_reference: u32,
        accepts: fn(&Kind) -> bool,
        type_name: &str,
    ) -> Result<&'static Variable, Status> {
        let independent = self
            .dialect
            .independent
            .filter(|v| v.value_reference == value_reference);
        let visible = independent.or_else(|| {
            self.position(value_reference)
                .map(|position| &self.model.table.variables[position])
                .filter(|v| self.scope.exposes(v.value_reference))
        });
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
    /// from a simulation built from the values set so far, which exiting initialization then
    /// takes if nothing changed since. Computed once until either changes.
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
                self.draft = Some(sim);
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
        let function = self.function(call);
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
        let time = self
            .dialect
            .independent
            .map(|v| (v.value_reference, self.time));
        let value = |vr: u32| match time {
            Some((independent, t)) if vr == independent => t,
            _ => self
                .position(vr)
                .map_or(f64::NAN, |position| values[position]),
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
        let function = self.function(call);
        for (i, &vr) in value_references.iter().enumerate() {
            let value = value_at(i);
            let var = match self.variable(function, vr, accepts, type_name) {
                Ok(var) => var,
                Err(status) => return status,
            };
            if self.phase == IntermediateUpdate && var.causality != Causality::Input {
                return self.error(&format!(
                    "{function}: {} is not an input: between a step's internal steps only inputs can be set",
                    var.name
                ));
            }
            let writable = match var.causality {
                Causality::Input => true,
                Causality::Parameter => {
                    self.phase != StepComplete || var.variability == Variability::Tunable
                }
                Causality::Output | Causality::Independent => {
                    let what = if var.causality == Causality::Output {
                        "an output"
                    } else {
                        "the independent variable"
                    };
                    return self.error(&format!(
                        "{function}: {} is {what}: it can be read, not set",
                        var.name
                    ));
                }
            };
            if !writable {
                return self.error(&format!(
                    "{function}: {} is a fixed parameter: it can be set only before {} (current state {})",
                    var.name,
                    self.function(Call::ExitInitializationMode),
                    self.phase_name(self.phase)
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
            // Every reference was found above, through the instance's index.
            if let Some(position) = self.position(vr) {
                self.values.set_at(position, value_at(i));
            }
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
                && self
                    .position(vr)
                    .map(|position| self.model.table.variables[position].causality)
                    == Some(Causality::Input)
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

    /// First derivatives of inputs for the next step only.
    /// All are checked before any is stored.
    pub fn set_input_derivatives(
        &mut self,
        value_references: &[u32],
        orders: &[i32],
        derivatives: &[f64],
    ) -> Status {
        if let Err(status) = self.check_phase(Call::SetRealInputDerivatives) {
            return status;
        }
        let function = self.function(Call::SetRealInputDerivatives);
        if !self.model.table.interpolates_inputs {
            return self.error(&format!("{function}: {}", held_inputs()));
        }
        for ((&vr, &order), &derivative) in value_references.iter().zip(orders).zip(derivatives) {
            let var = match self.derivative_variable(function, vr, order, Causality::Input) {
                Ok(var) => var,
                Err(status) => return status,
            };
            if !derivative.is_finite() {
                return self.error(&format!(
                    "{function}: the derivative of {} is {derivative}: expected a finite number",
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
                        return self.error(&format!("{function}: {message}"));
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

    /// First derivatives of outputs at the current time, where
    /// the simulation has them exactly.
    pub fn get_output_derivatives(
        &mut self,
        value_references: &[u32],
        orders: &[i32],
        out: &mut [f64],
    ) -> Status {
        if let Err(status) = self.check_phase(Call::GetRealOutputDerivatives) {
            return status;
        }
        let function = self.function(Call::GetRealOutputDerivatives);
        if !self.model.table.interpolates_inputs {
            return self.error(&format!(
                "{function}: this model gives no output derivatives (maxOutputDerivativeOrder = 0)"
            ));
        }
        for (i, (&vr, &order)) in value_references.iter().zip(orders).enumerate() {
            let var = match self.derivative_variable(function, vr, order, Causality::Output) {
                Ok(var) => var,
                Err(status) => return status,
            };
            let Some(sim) = self.sim.as_ref() else {
                return self.error(&format!(
                    "{function}: no simulation: {} has not succeeded",
                    self.function(Call::ExitInitializationMode)
                ));
            };
            match sim.output_derivative(vr, &self.values) {
                Ok(x) if x.is_finite() => out[i] = x,
                Ok(x) => {
                    return self.error(&format!(
                    "{function}: the derivative of {} is {x} at t = {}: expected a finite value",
                    var.name, self.time
                ))
                }
                Err(message) => return self.error(&format!("{function}: {}: {message}", var.name)),
            }
        }
        Status::Ok
    }
}
