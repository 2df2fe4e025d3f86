//! `exponential`: scene T's contact-specific scheme, fixed steps h = 1/(f n). The bristle is
//! advanced by the exact solution of z' = w - a z for the relative velocity w and the slip rate
//! a frozen (linear in z then: stable however large a h is; a = kt |v|/FC reaches 3e7 1/s at
//! kt x 1000, where explicit methods need h < 3/a); the mechanics (x, x', y, y', lambda and the
//! quadratures) by the explicit midpoint rule with the contact force from the bristle's midpoint
//! value:
//!
//! 1. an Euler half step of the mechanics from the step's start;
//! 2. the exact bristle update over h/2, with the body velocity moving linearly between the two;
//! 3. the full mechanical step with the contact force at that midpoint;
//! 4. the exact bristle update over h from the step's start, the body velocity moving linearly
//!    between the start and the new end.
//!
//! A step across a kink of the slip rate (v1 or v2 changing sign under the split law, v1 + v2
//! under the total) is retaken in pieces that end on it ([`step_over_kinks`]).
//!
//! Without vibration (a trimmed model, [`super::axial`]) the same steps run on the 1D state,
//! where the slip rate depends on x' alone and the bristle update needs no predictor.
//!
//! Not the Strang splitting (bristle h/2, mechanics h with the bristle held, bristle h/2): when
//! a h >> 1 the bristle is slaved to the velocities and a held bristle feeds the mechanics the
//! force of the step's start, which measured first order at kt x 1000. Here every frozen
//! velocity is taken where the exact solution weighs it ([`bristle`]), so the scheme is second
//! order both when a h << 1 and when a h >> 1. What stays explicit is the body-contact
//! oscillation sqrt(kt/m) while the contact sticks (a Stormer-Verlet pair then): stable for
//! h sqrt(kt/m) < 2, i.e. more than 2 steps a period at 3 kHz and the paper's kt, 60 at kt x 1000.

use super::{Clocked, Params, VX, VY, ZX, ZY};
use crate::error::{Error, Failure};
use crate::friction::lugre2d::{direction, SlipLaw};
use crate::solve::failures;
use crate::solve::{Ode, Work, MAX_DIM, MAX_STEPS_PER_DO_STEP};
use nalgebra::Vector2;

/// The stability bound of the explicit midpoint step on the body's oscillation on the stuck
/// contact (a Stormer-Verlet pair): h omega < 2.
const STABLE_H_OMEGA: f64 = 2.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponential {
    pub steps_per_period: u32,
}

impl Exponential {
    /// Splits `[t0, t1]` into equal steps no longer than 1/(f n) and takes them. Accumulates
    /// the integral of FFx in `y[Q]`.
    pub fn advance(
        &self,
        eq: &Stepper,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        let h_max = 1.0 / (eq.p.f * f64::from(self.steps_per_period));
        // A hair of slack so an interval of exactly k steps is not split into k + 1.
        let steps = ((t1 - t0) / h_max * (1.0 - 1e-12)).ceil().max(1.0);
        if steps.is_nan() || steps > MAX_STEPS_PER_DO_STEP as f64 {
            return Err(failures::too_many_fixed_steps(
                "exponential",
                steps,
                h_max,
                t1,
            ));
        }
        let h = (t1 - t0) / steps;
        // Past the bound the explicit mechanics grow without limit; that can stay finite for a
        // step or two, so it is refused before the step rather than looked for after it.
        let omega = eq.p.sticking_frequency();
        if h * omega >= STABLE_H_OMEGA {
            let needed = (omega / (STABLE_H_OMEGA * eq.p.f)).ceil();
            return Err(Error::step(
                "exponential",
                Failure::BeyondStability,
                format!(
                    "steps of {h:.3e} s with sqrt((kt + kd)/m) = {omega:.4e} 1/s give h sqrt((kt + kd)/m) = {:.3}, where the explicit step of the body is stable only below {STABLE_H_OMEGA}",
                    h * omega
                ),
                format!("steps_per_period > {needed:.0} (or a shorter communication step, or the radau5 solver)"),
            ));
        }
        let mut signs = kinks(eq, t0, y);
        work.rhs_evaluations += 1;
        for i in 0..steps as u64 {
            // t from the index, not by accumulation, so long runs do not drift.
            let t_end = if i + 1 == steps as u64 {
                t1
            } else {
                t0 + (i + 1) as f64 * h
            };
            signs = step_over_kinks(eq, t0 + i as f64 * h, t_end, signs, y, work);
        }
        if y.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(failures::fixed_step_not_finite("exponential", t1))
        }
    }
}

fn body_velocity(p: &Params, y: &[f64]) -> Vector2<f64> {
    if p.held {
        Vector2::zeros()
    } else {
        Vector2::new(y[VX], y[VY])
    }
}

/// The equations the steps advance: the planar ones or the 1D ones (`axial`).
pub struct Stepper<'a> {
    pub p: &'a Clocked,
    pub eq: &'a dyn Ode,
    pub axial: bool,
}

/// The arguments of the |.| in the slip rate (v1 and v2 for the split law, v1 + v2 for the
/// total; x' in 1D), whose sign changes are kinks of the right-hand side.
fn kinks(eq: &Stepper, t: f64, y: &[f64]) -> [f64; 2] {
    let p = eq.p;
    if eq.axial {
        return [body_velocity(p, y).x, 1.0];
    }
    let c = p.contact(t, y);
    match p.slip {
        SlipLaw::Split => [c.v1, c.v2],
        SlipLaw::Total => [c.v1 + c.v2, 1.0],
    }
}

/// The most pieces one step is cut into (two kinks a period per slip rate argument, rarely two
/// in one step).
const MAX_PIECES: usize = 4;

/// Steps from `t` to `t_end`, ending pieces where an argument of the kinks changes sign: a step
/// across a kink drops to first order locally, and over a period the kinks' positions on the
/// grid make the error jump about instead of falling as h^2. The sign change is placed by
/// linear interpolation between the step's ends (an O(h^2) error in its position, O(h^3) in
/// the state). `before` holds the arguments at `t`; returns them at `t_end`.
fn step_over_kinks(
    eq: &Stepper,
    mut t: f64,
    t_end: f64,
    mut before: [f64; 2],
    y: &mut [f64],
    work: &mut Work,
) -> [f64; 2] {
    let n = eq.eq.dim();
    let mut trial = [0.0; MAX_DIM];
    for piece in 0..MAX_PIECES {
        trial[..n].copy_from_slice(&y[..n]);
        step(eq, t, t_end - t, &mut trial);
        let after = kinks(eq, t_end, &trial);
        work.steps += 1;
        // The mechanics' two right-hand sides and the kinks' (the bristle updates are algebraic).
        work.rhs_evaluations += 3;
        let mut fraction: f64 = 1.0;
        for (b, a) in before.iter().zip(after) {
            if b * a < 0.0 {
                fraction = fraction.min(b / (b - a));
            }
        }
        // A kink within 1 % of either end costs less than another piece would save.
        if !(0.01..=0.99).contains(&fraction) || piece + 1 == MAX_PIECES {
            y[..n].copy_from_slice(&trial[..n]);
            return after;
        }
        let t_cut = t + fraction * (t_end - t);
        step(eq, t, t_cut - t, y);
        before = kinks(eq, t_cut, y);
        work.steps += 1;
        work.rhs_evaluations += 3;
        t = t_cut;
    }
    before
}

/// One step over `[t, t + h]` (steps 1-4 of the module's comment).
fn step(eq: &Stepper, t: f64, h: f64, y: &mut [f64]) {
    let p = eq.p;
    let n = eq.eq.dim();
    let z0 = Vector2::new(y[ZX], y[ZY]);
    let v0 = body_velocity(p, y);
    // The bristle's update over `h` from `z0` to the body velocity `v1`.
    let update = |h: f64, v1: Vector2<f64>, y: &mut [f64]| {
        if eq.axial {
            y[ZX] = bristle_1d(p, h, z0.x, v0.x, v1.x);
        } else {
            let z = bristle(p, t, h, z0, v0, v1);
            y[ZX] = z.x;
            y[ZY] = z.y;
        }
    };
    let mut k = [0.0; MAX_DIM];
    let mut mid = [0.0; MAX_DIM];
    eq.eq.rhs(t, &y[..n], &mut k[..n]);
    for j in 0..n {
        mid[j] = y[j] + 0.5 * h * k[j];
    }
    update(0.5 * h, body_velocity(p, &mid), &mut mid);
    eq.eq.rhs(t + 0.5 * h, &mid[..n], &mut k[..n]);
    for j in (0..n).filter(|&j| j != ZX && j != ZY) {
        y[j] += h * k[j];
    }
    update(h, body_velocity(p, y), y);
}

/// [`bristle`] without vibration: the slip rate |x'|/g(x') depends on the velocity alone, so
/// the centroid comes from the end's velocity and the rate from the centroid's, no predictor.
fn bristle_1d(p: &Params, h: f64, z0: f64, v0: f64, v1: f64) -> f64 {
    let theta = centroid(p.law.slip_rate(v1) * h);
    let w = v0 + (v1 - v0) * theta;
    let (decay, weight) = relaxation(p.law.slip_rate(w), h);
    z0 * decay + w * weight
}

/// The bristle at `t + h` from `z0` at `t`, the body velocity going linearly from `v0` to `v1`
/// and the support's following its law: the exact solution of z' = w - a z for w and a frozen
/// at one instant.
///
/// Which instant: the solution weighs w(s) by exp(-a (h - s)), so w frozen at that weight's
/// centroid is exact for w linear in s, whatever a h is: the midpoint when a h << 1 (second
/// order), 1/a before the end when a h >> 1 (the lag with which the true z follows w/a). The
/// slip rate a depends on z too, through e = z/|z| (v1 = e.v_body, v2 = -e.v_M), and the
/// vibration turns e every period, so a frozen at the start would be first order. One iteration
/// instead: a predictor with a at the start gives the end state; a there sets the centroid (when
/// a h >> 1 the lag is 1/a at the end: a changes by several % a step where w turns fastest, and
/// the start's a put the direction off by O(h)); a at the centroid, with z interpolated along the
/// predictor for its direction, makes the final update.
fn bristle(
    p: &Clocked,
    t: f64,
    h: f64,
    z0: Vector2<f64>,
    v0: Vector2<f64>,
    v1: Vector2<f64>,
) -> Vector2<f64> {
    // The body's and the support point's velocities a fraction `tau` into the step.
    let at = |tau: f64| (v0 + (v1 - v0) * tau, p.support_velocity(t + tau * h));
    let slip = |z: Vector2<f64>, (v_body, v_m): (Vector2<f64>, Vector2<f64>)| {
        let e = direction(z, v_body - v_m);
        p.law.slip(p.slip, e.dot(&v_body), -e.dot(&v_m))
    };
    let frozen_w = |tau: f64| {
        let (v_body, v_m) = at(tau);
        v_body - v_m
    };
    let a0 = slip(z0, at(0.0));
    let theta0 = centroid(a0 * h);
    let z_pred = relax(z0, frozen_w(theta0), a0, h);
    let theta = centroid(slip(z_pred, at(1.0)) * h);
    let (v_body, v_m) = at(theta);
    let a = slip(z0 + (z_pred - z0) * theta, (v_body, v_m));
    relax(z0, v_body - v_m, a, h)
}

/// Exact solution of z' = w - a z over `h` for constant `w` and `a >= 0`.
fn relax(z0: Vector2<f64>, w: Vector2<f64>, a: f64, h: f64) -> Vector2<f64> {
    let (decay, weight) = relaxation(a, h);
    z0 * decay + w * weight
}

/// `(e^{-ah}, (1 - e^{-ah})/a)`: z(h) = decay z0 + weight w.
fn relaxation(a: f64, h: f64) -> (f64, f64) {
    let ah = a * h;
    // e^{-ah} - 1 by exp_m1, so (1 - e^{-ah})/a stays accurate (and tends to h) as a h -> 0.
    let decay_m1 = (-ah).exp_m1();
    let weight = if ah > 0.0 { -decay_m1 / a } else { h };
    (1.0 + decay_m1, weight)
}

/// The centroid, as a fraction of the step, of exp(-x (1 - s)) on s in [0, 1]:
/// 1 - 1/x + 1/(e^x - 1), from 1/2 (x -> 0) to 1 (x -> infinity).
fn centroid(x: f64) -> f64 {
    if x < 1e-3 {
        // The closed form cancels catastrophically here; its series is exact to 1e-13.
        0.5 + x / 12.0
    } else if x > 40.0 {
        // 1/(e^x - 1) < 5e-18: below round-off, and its exp is the costliest part here.
        1.0 - 1.0 / x
    } else {
        1.0 - 1.0 / x + 1.0 / x.exp_m1()
    }
}

#[cfg(test)]
mod tests;
