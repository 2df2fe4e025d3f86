//! How an input moves over a communication step when the master gives no derivative.
//!
//! Co-simulation engines (libcosim, ecos) set each input to the partner's output at the
//! communication point and hold it over the step: the coupled run is then first order in the
//! step. An FMU that remembers the values its inputs had at the last communication points can do
//! better by itself:
//!
//! - `held`: the value set, over the whole step (what the engine means);
//! - `extrapolated`: the line through the last two communication points' values, continued over
//!   the step (second order);
//! - `corrected`: `extrapolated`, plus what the input's integral over time (a velocity's
//!   displacement, a force's impulse) missed over the steps so far, spread over the coming step.
//!   What an input did over the last step is read from the quadratic through its last three
//!   values, so the integral the model sees stays within the third order of what the master's
//!   samples say, and the coupled error falls as about the 2.5th power of the step.
//!
//! A derivative the master sets (fmi2SetRealInputDerivatives) takes precedence, for that step.
//! The values at past communication points, the integral missed and the derivative pending for
//! the coming step are state: saved, restored, rolled back with the rest of the model.
//!
//! A coupling through an input is stable only below some communication step, which depends on
//! the partner as much as on this model (docs/coupling.md measures it against the drive spring's
//! stiffness), and is the lower the more a scheme extrapolates. Past it the exchanged values
//! oscillate with the step and grow. Each input watches for that under every scheme
//! and says it once ([`Extrapolator::instability`]), with the largest stable step estimated from
//! the growth ([`stability`]).

use super::ramp::Ramp;
use super::switch::{switch, Switch};
use crate::error::Error;
use crate::variables::declare;

switch!(
    /// How an input moves over a step the master gives no derivative for (every model with
    /// inputs).
    InputScheme = declare::INPUT_SCHEME {
        Held = "held",
        Extrapolated = "extrapolated",
        Corrected = "corrected",
    }
);

/// The numbers [`Extrapolator::save`] writes.
pub const SAVED: usize = 12 + Watch::SAVED;

/// One input's past values at communication points, oldest first, and what its last step used.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Extrapolator {
    /// (time, value) at the last three communication points; `count` of them are known.
    samples: [(f64, f64); 3],
    count: usize,
    /// The integral over time of the input the model was given over the last step.
    used: f64,
    /// What the integral of the given input is short of the master's values' so far.
    debt: f64,
    /// The derivative the master set for the coming step.
    derivative: Option<f64>,
    /// The last step's length.
    step: f64,
    watch: Watch,
}

impl Extrapolator {
    /// The master's derivative for the coming step only.
    pub fn set_derivative(&mut self, derivative: f64) {
        self.derivative = Some(derivative);
    }

    /// The derivative the master set for the coming step, 0 if none (the outputs' derivatives
    /// read it).
    pub fn pending_rate(&self) -> f64 {
        self.derivative.unwrap_or(0.0)
    }

    /// A step the input does not enter (its source is not the input, or the step only reads
    /// one taken ahead): the master's derivative for it lapses.
    pub fn lapse(&mut self) {
        self.derivative = None;
    }

    /// The input over the step `[t, t + h]` (on the step's own time, 0 at its start), `value`
    /// being its value at `t`: the master's derivative if one was set for the step, else
    /// `scheme`'s. Records `(t, value)` and takes the derivative, so call it once per step.
    pub fn ramp(&mut self, scheme: InputScheme, t: f64, value: f64, h: f64) -> Ramp {
        self.ramp_where(scheme, t, value, h, |_| true)
    }

    /// As [`Extrapolator::ramp`], holding the value over the step where the scheme's line is
    /// not `admissible` for the model, or not finite (a master's derivative is taken as it
    /// is).
    pub fn ramp_where(
        &mut self,
        scheme: InputScheme,
        t: f64,
        value: f64,
        h: f64,
        admissible: impl Fn(Ramp) -> bool,
    ) -> Ramp {
        self.record(t, value);
        self.step = h;
        if scheme != InputScheme::Corrected {
            // Nothing is made up: the integral's shortfall is the scheme's error, not a debt.
            self.debt = 0.0;
        }
        let ramp = match self.derivative.take() {
            Some(rate) => {
                // The master drives the input: nothing of ours to make up later.
                self.debt = 0.0;
                Ramp { value, rate }
            }
            None if scheme == InputScheme::Held => Ramp { value, rate: 0.0 },
            None => {
                let rate = self.slope();
                let offset = if scheme == InputScheme::Corrected {
                    self.debt / h
                } else {
                    0.0
                };
                let ramp = Ramp {
                    value: value + offset,
                    rate,
                };
                // A step far shorter than the last ones can make the line or the debt's share
                // overflow: such a step holds.
                if admissible(ramp) && ramp.value.is_finite() && ramp.rate.is_finite() {
                    ramp
                } else {
                    Ramp { value, rate: 0.0 }
                }
            }
        };
        self.used = ramp.integral(0.0, h);
        ramp
    }

    /// Takes the value at a new communication point `t` and settles what the last step's input
    /// missed of the master's values (a point at or before the last one restarts the history:
    /// the master went back without restoring a state).
    fn record(&mut self, t: f64, value: f64) {
        if self.count > 0 && t <= self.samples[2].0 {
            self.count = 0;
            self.debt = 0.0;
        }
        if self.count > 0 {
            self.watch.add(value - self.samples[2].1);
        }
        self.samples.rotate_left(1);
        self.samples[2] = (t, value);
        self.count = (self.count + 1).min(3);
        if self.count >= 2 {
            self.debt += self.last_integral() - self.used;
        }
    }

    /// The slope of the line through the last two values (0 with one).
    fn slope(&self) -> f64 {
        if self.count < 2 {
            return 0.0;
        }
        let [_, (t1, u1), (t2, u2)] = self.samples;
        (u2 - u1) / (t2 - t1)
    }

    /// The integral over the last step of the quadratic through the last three values (the
    /// trapezoid with two), by two-point Gauss, exact for it.
    fn last_integral(&self) -> f64 {
        let [(t0, u0), (t1, u1), (t2, u2)] = self.samples;
        let h = t2 - t1;
        if self.count < 3 {
            return 0.5 * h * (u1 + u2);
        }
        let quadratic = |t: f64| {
            u0 * (t - t1) * (t - t2) / ((t0 - t1) * (t0 - t2))
                + u1 * (t - t0) * (t - t2) / ((t1 - t0) * (t1 - t2))
                + u2 * (t - t0) * (t - t1) / ((t2 - t0) * (t2 - t1))
        };
        let (middle, half_width) = (0.5 * (t1 + t2), 0.5 * h / 3f64.sqrt());
        0.5 * h * (quadratic(middle - half_width) + quadratic(middle + half_width))
    }

    /// Appends [`SAVED`] numbers that [`Extrapolator::restore`] takes back to the same bits.
    pub fn save(&self, out: &mut Vec<f64>) {
        for (t, u) in self.samples {
            out.extend_from_slice(&[t, u]);
        }
        out.extend_from_slice(&[
            self.count as f64,
            self.used,
            self.debt,
            f64::from(u8::from(self.derivative.is_some())),
            self.derivative.unwrap_or(0.0),
            self.step,
        ]);
        self.watch.save(out);
    }

    /// Takes back what [`Extrapolator::save`] wrote (`saved` holds exactly [`SAVED`] numbers).
    pub fn restore(&mut self, saved: &[f64]) -> Result<(), Error> {
        let count = saved[6];
        if !matches!(count, 0.0..=3.0) || count.fract() != 0.0 {
            return Err(Error::state(
                format!("a saved input history of {count} values"),
                "0, 1, 2 or 3",
            ));
        }
        for (k, sample) in self.samples.iter_mut().enumerate() {
            *sample = (saved[2 * k], saved[2 * k + 1]);
        }
        self.count = count as usize;
        self.used = saved[7];
        self.debt = saved[8];
        let watch = Watch::restore(&saved[12..])?;
        self.derivative = match saved[9] {
            0.0 => None,
            1.0 => Some(saved[10]),
            flag => {
                return Err(Error::state(
                    format!("a saved input's derivative flag of {flag}"),
                    "0 or 1",
                ))
            }
        };
        self.step = saved[11];
        self.watch = watch;
        Ok(())
    }

    /// The warning that the coupling through this input (`name`, moved by `scheme`) has gone
    /// unstable: once an instance, None until then.
    pub fn instability(&mut self, name: &str, scheme: InputScheme) -> Option<String> {
        let growth = self.watch.take()?;
        let h = self.step;
        let largest = stability::largest_stable_steps(scheme, h, growth)(scheme);
        let scheme_name = scheme.name();
        Some(format!(
            "input_scheme = {scheme_name}: {name} oscillates with the communication step of {h:.4e} s and grows {growth:.2}-fold a step: the coupling through it is unstable at this step. Estimated from that growth, the largest stable step with {scheme_name} is {largest:.2e} s (docs/coupling.md, \"Stability\"); take a shorter one"
        ))
    }
}

/// Watches an input's changes from one communication point to the next for the coupling
/// instability: in blocks of [`Watch::BLOCK`] steps, each with at least one change of sign (an
/// oscillation of a few steps' period, which no step resolves), the largest change growing from
/// block to block and at least doubling over two.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Watch {
    /// The largest change of the two blocks before and of the current one.
    largest: [f64; 3],
    /// Whether each of those blocks changed sign.
    turned: [bool; 3],
    /// Changes so far in the current block.
    count: u32,
    last_change: f64,
    /// The growth a step once found (taken by [`Watch::take`]), and whether it was.
    found: Option<f64>,
    reported: bool,
}

impl Watch {
    const BLOCK: u32 = 5;
    const SAVED: usize = 11;

    fn add(&mut self, change: f64) {
        if self.count == Self::BLOCK {
            self.largest.rotate_left(1);
            self.turned.rotate_left(1);
            (self.largest[2], self.turned[2], self.count) = (0.0, false, 0);
        }
        self.largest[2] = self.largest[2].max(change.abs());
        self.turned[2] |= change * self.last_change < 0.0;
        self.last_change = change;
        self.count += 1;
        let [a, b, c] = self.largest;
        if self.count == Self::BLOCK
            && !self.reported
            && self.found.is_none()
            && self.turned.iter().all(|&turned| turned)
            && a > 0.0
            && a < b
            && b < c
            && c >= 2.0 * a
        {
            self.found = Some((c / a).powf(1.0 / f64::from(2 * Self::BLOCK)));
        }
    }

    fn take(&mut self) -> Option<f64> {
        let growth = self.found.take()?;
        self.reported = true;
        Some(growth)
    }

    fn save(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&self.largest);
        out.extend(self.turned.map(|turned| f64::from(u8::from(turned))));
        out.extend_from_slice(&[
            f64::from(self.count),
            self.last_change,
            f64::from(u8::from(self.found.is_some())),
            self.found.unwrap_or(0.0),
            f64::from(u8::from(self.reported)),
        ]);
    }

    fn restore(saved: &[f64]) -> Result<Self, Error> {
        let flag = |x: f64| match x {
            0.0 => Ok(false),
            1.0 => Ok(true),
            _ => Err(Error::state(
                format!("a saved input's stability watch with the flag {x}"),
                "0 or 1",
            )),
        };
        let count = saved[6];
        if !(0.0..=f64::from(Self::BLOCK)).contains(&count) || count.fract() != 0.0 {
            return Err(Error::state(
                format!("a saved input's stability watch counting {count} changes"),
                format!("0 to {}", Self::BLOCK),
            ));
        }
        Ok(Watch {
            largest: [saved[0], saved[1], saved[2]],
            turned: [flag(saved[3])?, flag(saved[4])?, flag(saved[5])?],
            count: count as u32,
            last_change: saved[7],
            found: flag(saved[8])?.then_some(saved[9]),
            reported: flag(saved[10])?,
        })
    }
}

pub mod stability;

#[cfg(test)]
mod tests;
