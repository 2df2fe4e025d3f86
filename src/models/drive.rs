//! DriveTrain: a DC motor, a gear and a lead screw whose nut drives a load (the far end of
//! TransverseFriction's drive spring).
//!
//! ```text
//! L i'         = V - R i - ke omega
//! J_eff omega' = kt_m i - b omega - r F_load / efficiency,   r = lead / (2 pi n)
//! x_nut'       = r omega,   v_nut = r omega,   J_eff = J + m_nut r^2 / efficiency
//! ```
//!
//! Linear with inputs that move linearly over a step (held, or at the master's derivatives, or
//! as `input_scheme` moves them): so the state augmented with the inputs and their rates,
//! `[i, omega, x_nut, V, F_load, V', F_load']`, obeys `z' = A z` with a constant A, and each step
//! is exactly `z(t + h) = expm(A h) z(t)`: no step size to choose, no work limit to reach (one
//! 7 x 7 matrix exponential per distinct step size). The motor is a source, so there is no
//! passivity to check; the state is checked finite.

mod equations;
#[cfg(feature = "tools")]
pub mod stability;
mod start;
pub mod switches;
pub mod table;

pub use equations::Params;

use super::input_scheme::{self, Extrapolator, InputScheme};
use super::ramp::Ramp;
use super::{Scope, Simulation};
use crate::error::{Error, Failure};
use crate::models::drive::table::{vr, TABLE};
use crate::solve::expm::{expm, mul_vec, Matrix, Propagators};
use crate::variables::values::ValueSet;
use equations::{DIM, I, OMEGA, X};

#[derive(Clone, Debug, PartialEq)]
pub struct Drive {
    pub p: Params,
    t: f64,
    /// i, omega, x_nut.
    y: [f64; 3],
    /// How V_in and F_load move over a step: their past values and the master's derivatives.
    inputs: [Extrapolator; 2],
    input_scheme: InputScheme,
    /// expm(A h) of the last few step sizes h, reused while the master keeps its step.
    propagators: Propagators<DIM>,
}

pub fn build(
    values: &ValueSet,
    start_time: f64,
    scope: &Scope,
) -> Result<Box<dyn Simulation>, Error> {
    Ok(Box::new(Drive::with_scope(values, start_time, scope)?))
}

impl Drive {
    /// The armature voltage and the load now, from the inputs (or the voltage parameter).
    fn inputs(&self, values: &ValueSet) -> Result<(f64, f64), Error> {
        let voltage = self.p.voltage.unwrap_or_else(|| values.real(vr::V_IN));
        let force = values.real(vr::F_LOAD);
        if !voltage.is_finite() || !force.is_finite() {
            let name = if voltage.is_finite() {
                "F_load"
            } else {
                "V_in"
            };
            return Err(Error::value_found(
                name,
                format!("V_in = {voltage} and F_load = {force}"),
                "finite numbers",
            ));
        }
        Ok((voltage, force))
    }

    fn propagator(&mut self, h: f64) -> Result<Matrix<DIM>, Error> {
        let p = &self.p;
        let phi = self.propagators.get(h, |h| {
            let mut a = p.system();
            for row in a.iter_mut() {
                for x in row.iter_mut() {
                    *x *= h;
                }
            }
            expm(&a).map_err(|e| Error {
                expected: format!(
                    "{}: parameters that keep every coefficient of the drive's equations within f64",
                    e.expected
                ),
                ..e
            })
        })?;
        Ok(*phi)
    }
}

impl Simulation for Drive {
    fn do_step(&mut self, h: f64, values: &ValueSet) -> Result<(), Error> {
        super::require_step(h)?;
        let (voltage, force) = self.inputs(values)?;
        let phi = self.propagator(h)?;
        // The master's derivatives apply to this step only (fmi2DoStep restores them with the
        // rest of the state when the step fails).
        let [voltage_input, force_input] = &mut self.inputs;
        let voltage = if self.p.voltage.is_some() {
            voltage_input.lapse();
            Ramp {
                value: voltage,
                rate: 0.0,
            }
        } else {
            voltage_input.ramp(self.input_scheme, self.t, voltage, h)
        };
        let force = force_input.ramp(self.input_scheme, self.t, force, h);
        let z = [
            self.y[I],
            self.y[OMEGA],
            self.y[X],
            voltage.value,
            force.value,
            voltage.rate,
            force.rate,
        ];
        let z = mul_vec(&phi, &z);
        if !z[..3].iter().all(|v| v.is_finite()) {
            return Err(Error::step(
                "exponential",
                Failure::NotFinite,
                format!("the state became non-finite at t = {}", self.t + h),
                format!("smaller inputs or derivatives, or R, L, kt_m, ke and J that keep the motor resolvable in f64 over a step of {h} s"),
            ));
        }
        self.y.copy_from_slice(&z[..3]);
        self.t += h;
        Ok(())
    }

    fn write_outputs(&self, values: &mut ValueSet) {
        values.set(vr::V_NUT, self.p.r * self.y[OMEGA]);
        values.set(vr::X_NUT, self.y[X]);
        values.set(vr::CURRENT, self.y[I]);
        values.set(vr::OMEGA, self.y[OMEGA]);
    }

    fn time(&self) -> f64 {
        self.t
    }

    fn save_into(&self, out: &mut Vec<f64>) {
        // The input rates pending for the next step are state too: a master that rolls back
        // and retakes the step need not set them again (FMI 2.0, 2.1.8). So are the inputs'
        // past values the input scheme reads.
        out.clear();
        out.extend_from_slice(&[self.t, self.y[I], self.y[OMEGA], self.y[X]]);
        for input in &self.inputs {
            input.save(out);
        }
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), Error> {
        super::check_saved(TABLE.model_identifier, state, 4 + 2 * input_scheme::SAVED)?;
        let mut inputs = self.inputs;
        for (input, saved) in inputs
            .iter_mut()
            .zip(state[4..].chunks_exact(input_scheme::SAVED))
        {
            input.restore(saved)?;
        }
        self.inputs = inputs;
        self.t = state[0];
        self.y.copy_from_slice(&state[1..4]);
        Ok(())
    }

    fn set_input_derivative(&mut self, value_reference: u32, derivative: f64) -> Result<(), Error> {
        match value_reference {
            vr::V_IN => self.inputs[0].set_derivative(derivative),
            vr::F_LOAD => self.inputs[1].set_derivative(derivative),
            _ => return Err(super::not_an_input(value_reference)),
        }
        Ok(())
    }

    fn take_warning(&mut self) -> Option<String> {
        let [voltage, force] = &mut self.inputs;
        let unstable = force.instability("F_load", self.input_scheme);
        unstable.or_else(|| voltage.instability("V_in", self.input_scheme))
    }

    fn drop_input_derivative(&mut self, value_reference: u32) {
        match value_reference {
            vr::V_IN => self.inputs[0].lapse(),
            vr::F_LOAD => self.inputs[1].lapse(),
            _ => {}
        }
    }

    fn output_derivative(&self, value_reference: u32, values: &ValueSet) -> Result<f64, Error> {
        let (voltage, force) = self.inputs(values)?;
        let (di, domega) = self.p.rates(self.y[I], self.y[OMEGA], voltage, force);
        match value_reference {
            vr::V_NUT => Ok(self.p.r * domega),
            vr::X_NUT => Ok(self.p.r * self.y[OMEGA]),
            vr::CURRENT => Ok(di),
            vr::OMEGA => Ok(domega),
            _ => Err(super::no_output_derivative(value_reference)),
        }
    }
}

#[cfg(test)]
mod tests;
