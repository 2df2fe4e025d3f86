//! Classical fourth-order Runge-Kutta with a fixed step: the plain explicit reference method of
//! the error-against-run-time tables (and the same-integrator checks of scene T).

use super::failures;
use super::stepping::Stepping;
use super::switching::Switching;
use super::{Integrator, Ode, Work, MAX_DIM};
use crate::error::{Error, Failure};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rk4 {
    /// The largest step; each call splits `[t0, t1]` into equal steps no longer than this.
    pub h_max: f64,
}

impl Integrator for Rk4 {
    fn integrate(
        &mut self,
        ode: &dyn Ode,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        let n = ode.dim();
        if n > MAX_DIM || y.len() < n {
            return Err(failures::states_do_not_fit("rk4", n, MAX_DIM));
        }
        // Written so that NaN fails too.
        let valid = self.h_max > 0.0 && t1 >= t0;
        if !valid {
            return Err(Error::step(
                "rk4",
                Failure::Misuse,
                format!("h_max = {} and the interval [{t0}, {t1}]", self.h_max),
                "h_max > 0 and t1 >= t0",
            ));
        }
        // A hair of slack so an interval of exactly k steps is not split into k + 1.
        let steps = ((t1 - t0) / self.h_max * (1.0 - 1e-12)).ceil().max(1.0);
        if steps > super::MAX_STEPS_PER_DO_STEP as f64 {
            return Err(failures::too_many_fixed_steps("rk4", steps, self.h_max, t1));
        }
        let h = (t1 - t0) / steps;
        let mut k = [[0.0; MAX_DIM]; 4];
        let mut tmp = [0.0; MAX_DIM];
        for i in 0..steps as u64 {
            // t from the index, not by accumulation, so long runs do not drift.
            let t = t0 + i as f64 * h;
            ode.rhs(t, &y[..n], &mut k[0][..n]);
            for j in 0..n {
                tmp[j] = y[j] + 0.5 * h * k[0][j];
            }
            ode.rhs(t + 0.5 * h, &tmp[..n], &mut k[1][..n]);
            for j in 0..n {
                tmp[j] = y[j] + 0.5 * h * k[1][j];
            }
            ode.rhs(t + 0.5 * h, &tmp[..n], &mut k[2][..n]);
            for j in 0..n {
                tmp[j] = y[j] + h * k[2][j];
            }
            ode.rhs(t + h, &tmp[..n], &mut k[3][..n]);
            for j in 0..n {
                y[j] += h / 6.0 * (k[0][j] + 2.0 * (k[1][j] + k[2][j]) + k[3][j]);
            }
            work.steps += 1;
            work.rhs_evaluations += 4;
        }
        if y[..n].iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(failures::fixed_step_not_finite("rk4", t1))
        }
    }
}

/// A fixed step: no tolerance, nothing carried between calls, and the switching functions
/// ignored (its steps are as long wherever the kinks lie).
impl Stepping for Rk4 {
    fn name(&self) -> &'static str {
        "rk4"
    }
    fn tolerance(&self) -> Option<f64> {
        None
    }
    fn step_hint(&self) -> f64 {
        0.0
    }
    fn set_step_hint(&mut self, _h: f64) {}
    fn advance<S: Switching>(
        &mut self,
        ode: &S,
        (t0, t1): (f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        self.integrate(ode, t0, t1, y, work)
    }
    /// The classical RK4's stability region lies within |h lambda| < 3 (2.96 at most, 2.79 on
    /// the real axis and 2.83 on the imaginary one): past 3 a step is unstable whatever the
    /// eigenvalue's direction.
    fn stability_bound(&self) -> Option<f64> {
        Some(3.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::test_odes::Harmonic;

    fn error(h: f64) -> f64 {
        let mut y = [1.0, 0.0];
        Rk4 { h_max: h }
            .integrate(&Harmonic, 0.0, 2.0, &mut y, &mut Work::default())
            .unwrap();
        (y[0] - 2f64.cos()).hypot(y[1] + 2f64.sin())
    }

    /// Oracle: the closed-form solution; halving the step divides the error by 2^4.
    #[test]
    fn fourth_order_on_the_harmonic_oscillator() {
        let ratio = error(0.1) / error(0.05);
        assert!((14.0..18.0).contains(&ratio), "error ratio {ratio}");
    }
}
