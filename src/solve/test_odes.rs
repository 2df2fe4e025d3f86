//! Test problems the solvers' tests share, each with its solution in closed form.

use super::switching::{Switching, MAX_SWITCHES};
use super::{Integrator, Ode, Work};

/// A scalar equation y' = f(t, y).
pub struct Scalar(pub fn(f64, f64) -> f64);

/// y' = -2 t y, y(0) = 1: y = exp(-t^2).
pub const GAUSS: Scalar = Scalar(|t, y| -2.0 * t * y);

/// The error of `integrator` on [`GAUSS`] over [0, 3], against the closed form.
pub fn gauss_error(integrator: &mut dyn Integrator) -> f64 {
    let mut y = [1.0];
    integrator
        .integrate(&GAUSS, 0.0, 3.0, &mut y, &mut Work::default())
        .unwrap();
    (y[0] - (-9.0f64).exp()).abs()
}

impl Ode for Scalar {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = (self.0)(t, y[0]);
    }
}

/// y' = |cos t| - decay y: a kink in y' wherever cos t = 0, which its switch function marks.
/// With no decay, y(t) - y(0) is the integral of |cos|.
pub struct AbsCos {
    pub decay: f64,
}

impl Ode for AbsCos {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = t.cos().abs() - self.decay * y[0];
    }
}

impl Switching for AbsCos {
    fn switches(&self, t: f64, _y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize {
        out[0] = t.cos();
        1
    }
}

/// y'' = -y as a system: y = (cos t, -sin t) from (1, 0).
pub struct Harmonic;

impl Ode for Harmonic {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = y[1];
        dydt[1] = -y[0];
    }
}
