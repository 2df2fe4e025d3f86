//! The periodic orbit of a forced system: a fixed point of its one-period map P, found by
//! Newton's method on P(y) - y (shooting), with the Jacobian from differences of P (the same
//! solver, so the orbit is the one the simulation then integrates) and Broyden's update after that.
//!
//! A transient approaches the orbit at the rate of the slowest Floquet multiplier, which for a
//! lightly damped body is hundreds of periods to the tolerance; shooting costs one period per
//! slow state for the Jacobian and one per iteration. States that settle within a period (a
//! bristle's deflection: its multiplier is near 0) need no column of their own: the map
//! forgets them, and the Jacobian's column is that of P(y) - y alone, -1 on the diagonal.
//! Far from the orbit the maps are integrated to a looser tolerance, tightened with the
//! residual (an inexact Newton method): only the last ones cost what a period of the run does.

use crate::error::Error;
use nalgebra::{DMatrix, DVector};

/// The one-period map: the state one period after `y`, integrated to the relative tolerance
/// given (or why it could not be taken).
pub type PeriodMap<'a> = dyn FnMut(&[f64], f64) -> Result<Vec<f64>, Error> + 'a;

/// The tolerance of the maps far from the orbit (the Jacobian's differences, the first
/// iterations): Newton's step there needs a few digits, not the run's tolerance.
const COARSE: f64 = 1e-6;

/// What shooting found: the orbit's state, and how many periods it took to find it.
#[derive(Clone, Debug, PartialEq)]
pub struct Orbit {
    pub state: Vec<f64>,
    pub periods: usize,
}

/// The most Newton-Broyden iterations after the Jacobian.
const MAX_ITERATIONS: usize = 12;

/// Why shooting found no orbit and, where the iterations stalled short of the tolerance (a map
/// that is not smooth, at stick-slip, holds Newton's method back), the state nearest to closing
/// the period: a better start for the transient than the guess.
#[derive(Clone, Debug, PartialEq)]
pub struct NoOrbit {
    pub why: String,
    pub nearest: Option<Vec<f64>>,
}

impl From<Error> for NoOrbit {
    fn from(error: Error) -> Self {
        error.to_string().into()
    }
}

impl From<String> for NoOrbit {
    fn from(why: String) -> Self {
        NoOrbit { why, nearest: None }
    }
}

impl From<&str> for NoOrbit {
    fn from(why: &str) -> Self {
        why.to_string().into()
    }
}

impl From<NoOrbit> for String {
    fn from(no_orbit: NoOrbit) -> Self {
        no_orbit.why
    }
}

/// Finds y with P(y) = y to `tolerance` in each component relative to `scale` (the size each
/// state takes on the orbit), from `guess`; `settling` marks the states that settle within a
/// period. Errors say why it did not converge: the caller falls back to the transient.
pub fn periodic_orbit(
    guess: &[f64],
    (scale, settling): (&[f64], &[bool]),
    tolerance: f64,
    map: &mut PeriodMap,
) -> Result<Orbit, NoOrbit> {
    let n = guess.len();
    let mut periods = 0;
    let coarse = COARSE.max(tolerance);
    let mut residual = |y: &DVector<f64>, accuracy: f64, periods: &mut usize| {
        *periods += 1;
        let next = map(y.as_slice(), accuracy).map_err(|e| e.to_string())?;
        if next.len() != n || next.iter().any(|v| !v.is_finite()) {
            return Err("the one-period map left the finite numbers".into());
        }
        Ok::<_, String>(DVector::from_vec(next) - y)
    };
    let size = |r: &DVector<f64>| {
        r.iter()
            .zip(scale)
            .map(|(r, s)| (r / s).abs())
            .fold(0.0, f64::max)
    };
    let mut y = DVector::from_column_slice(guess);
    let mut r = residual(&y, coarse, &mut periods)?;
    let mut accuracy = coarse;
    if size(&r) <= tolerance && accuracy <= tolerance {
        return Ok(Orbit {
            state: y.as_slice().to_vec(),
            periods,
        });
    }
    // The residual's Jacobian at y (where it is r), the slow states' columns differenced with
    // coarse maps. Differences of a map integrated to a relative tolerance rtol are good to
    // about rtol / eps of the step eps; the square root of the tolerance balances that against
    // the curvature.
    type Residual<'r> =
        dyn FnMut(&DVector<f64>, f64, &mut usize) -> Result<DVector<f64>, String> + 'r;
    let differenced =
        |residual: &mut Residual, y: &DVector<f64>, r: &DVector<f64>, periods: &mut usize| {
            let mut jacobian = -DMatrix::<f64>::identity(n, n);
            for j in (0..n).filter(|&j| !settling.get(j).copied().unwrap_or(false)) {
                let step = coarse.sqrt() * scale[j];
                let mut shifted = y.clone();
                shifted[j] += step;
                let column = (residual(&shifted, coarse, periods)? - r) / step;
                jacobian.set_column(j, &column);
            }
            Ok::<_, String>(jacobian)
        };
    let mut jacobian = differenced(&mut residual, &y, &r, &mut periods)?;
    let mut nearest = (size(&r), y.clone());
    for _ in 0..MAX_ITERATIONS {
        let Some(delta) = jacobian.clone().lu().solve(&(-&r)) else {
            return Err("the one-period map's Jacobian is singular".into());
        };
        let y_next = &y + &delta;
        // A hundredth of the residual now is as close as the next step can come.
        accuracy = (1e-2 * size(&r)).clamp(tolerance, coarse);
        let r_next = residual(&y_next, accuracy, &mut periods)?;
        if size(&r_next) <= tolerance && accuracy <= tolerance {
            // Newton's method finds unstable orbits as readily as stable ones, and the motion
            // never settles on those: the eigenvalues of the map's Jacobian at the orbit (its
            // Floquet multipliers) must lie inside the unit circle. Broyden's updates know that
            // Jacobian only along the steps taken, so it is differenced again there.
            let map_jacobian = differenced(&mut residual, &y_next, &r_next, &mut periods)?
                + DMatrix::<f64>::identity(n, n);
            let multipliers = map_jacobian.complex_eigenvalues();
            let largest = multipliers.iter().map(|m| m.norm()).fold(0.0, f64::max);
            if largest > 1.0 {
                return Err(format!(
                    "the period-1 orbit found is unstable (a Floquet multiplier of size {largest:.3}): the motion settles elsewhere, maybe on a longer period"
                )
                .into());
            }
            return Ok(Orbit {
                state: y_next.as_slice().to_vec(),
                periods,
            });
        }
        if size(&r_next) > 1e3 * size(&r) {
            return Err(format!(
                "Newton's iteration diverged (residual {:.1e} of the states' scale)",
                size(&r_next)
            )
            .into());
        }
        // Broyden's rank-one update: the secant condition J delta = r_next - r.
        let dd = delta.dot(&delta);
        if dd > 0.0 {
            let correction = (&r_next - &r - &jacobian * &delta) / dd;
            jacobian += correction * delta.transpose();
        }
        if size(&r_next) < nearest.0 {
            nearest = (size(&r_next), y_next.clone());
        }
        (y, r) = (y_next, r_next);
    }
    Err(NoOrbit {
        why: format!(
            "no periodic orbit to the tolerance after {MAX_ITERATIONS} iterations (residual {:.1e} of the states' scale at the nearest): the motion may not be period-1",
            nearest.0
        ),
        nearest: Some(nearest.1.as_slice().to_vec()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: the closed form of the fixed point. A linear map is solved by the first Newton
    /// step after the Jacobian, to the differences' accuracy, and by a second to round-off.
    #[test]
    fn finds_the_orbit_of_a_linear_map_in_one_step() {
        let a = (-std::f64::consts::TAU).exp();
        let mut map = |y: &[f64], _: f64| Ok(vec![a * y[0] + 0.5 * (1.0 - a)]);
        let orbit = periodic_orbit(&[3.0], (&[1.0], &[false]), 1e-12, &mut map).unwrap();
        assert!((orbit.state[0] - 0.5).abs() < 1e-12, "{orbit:?}");
        assert!(orbit.periods <= 5, "{orbit:?}");
    }

    /// A nonlinear two-state map with a slow and a fast multiplier converges in a few
    /// iterations; a map with no fixed point (a drift) is reported, not returned.
    #[test]
    fn converges_on_a_nonlinear_map_and_reports_a_drift() {
        let mut map = |y: &[f64], _: f64| {
            Ok(vec![
                0.99 * y[0] + 0.01 * (1.0 + 0.3 * y[1] * y[1]),
                0.01 * y[1] + 0.2 * y[0].sin(),
            ])
        };
        let orbit =
            periodic_orbit(&[0.0, 0.0], (&[1.0, 1.0], &[false, false]), 1e-12, &mut map).unwrap();
        let next = map(&orbit.state, 0.0).unwrap();
        for (a, b) in next.iter().zip(&orbit.state) {
            assert!((a - b).abs() < 1e-12);
        }
        assert!(orbit.periods < 15, "{orbit:?}");
        let mut drift = |y: &[f64], _: f64| Ok(vec![y[0] + 1.0]);
        assert!(periodic_orbit(&[0.0], (&[1.0], &[false]), 1e-10, &mut drift).is_err());
        // y -> 2 y - 1 has the fixed point 1, which repels: refused as unstable.
        let mut repelling = |y: &[f64], _: f64| Ok(vec![2.0 * y[0] - 1.0]);
        let refused = periodic_orbit(&[0.5], (&[1.0], &[false]), 1e-10, &mut repelling);
        assert!(refused.unwrap_err().why.contains("unstable"));
    }
}
