//! An input over the step under way, on the equations' time (0 at the step's start): its value
//! there, and the rate the master set for the step with fmi2SetRealInputDerivatives (0: held).

use crate::error::Error;
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Ramp {
    pub value: f64,
    pub rate: f64,
}

impl Ramp {
    pub fn at(self, t: f64) -> f64 {
        self.value + self.rate * t
    }

    /// The integral over `[t0, t1]`.
    pub fn integral(self, t0: f64, t1: f64) -> f64 {
        (t1 - t0) * self.at(0.5 * (t0 + t1))
    }

    /// Where the input crosses zero, if it moves.
    pub fn zero(self) -> Option<f64> {
        (self.rate != 0.0).then(|| -self.value / self.rate)
    }

    /// The value and rate as read from `name`, the rate taken for one step.
    pub fn checked(name: &'static str, value: f64, rate: f64) -> Result<Ramp, Error> {
        if value.is_finite() && rate.is_finite() {
            Ok(Ramp { value, rate })
        } else {
            Err(Error::value_found(
                name,
                format!("{name} = {value} with derivative {rate}"),
                "finite numbers",
            ))
        }
    }
}
