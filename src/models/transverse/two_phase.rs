//! The paper's own algorithm (paper T, eq. 11-29, Fig. 2-3), kept as the paper writes it: per
//! step the body moves first (N -> N1', M slides along M N1'), then the support carries M
//! (M1' -> M1''), each phase updating the deflection with an explicit Euler step of eq. 3.
//!
//! Our readings where the paper is silent: the force uses `sdot = (s1 - s)/dt` and
//! `vr = vr1 + vr2`; the body moves by semi-implicit Euler under the forces of the previous step;
//! a deflection that an Euler update drives below zero puts M on the other side of N.
//! The mean of FFx sums FFx at the step ends times the step, the integral form of eq. 30.

use super::{Clocked, Ramp, LAMBDA, Q, VX, VY, W, X, Y, ZX, ZY};
use crate::error::Error;
use crate::solve::failures;
use crate::solve::Work;
use nalgebra::Vector2;

/// Numbers [`TwoPhase::save`] writes.
pub const SAVED: usize = 7;

#[derive(Clone, Debug, PartialEq)]
pub struct TwoPhase {
    pub steps_per_period: u32,
    /// Origin of the step grid (steps end on t0 + k dt).
    grid_origin: f64,
    /// FF, FFx, FFy, s, beta at the end of the last step: the forces the body feels next step.
    ff: f64,
    ffx: f64,
    ffy: f64,
    s: f64,
    beta: f64,
    /// Direction N - M, kept for the degenerate case N1' = M.
    e: Vector2<f64>,
}

impl TwoPhase {
    /// At `t0`, the absolute time `p`'s equations count from.
    pub fn new(p: &Clocked, t0: f64, y: &[f64], steps_per_period: u32) -> Self {
        let c = p.contact(0.0, y);
        TwoPhase {
            steps_per_period,
            grid_origin: t0,
            ff: c.ff,
            ffx: c.ffx(),
            ffy: c.ffy(),
            s: c.s,
            beta: c.beta(),
            e: c.e,
        }
    }

    pub fn forces(&self) -> (f64, f64, f64, f64, f64) {
        (self.ff, self.ffx, self.ffy, self.s, self.beta)
    }

    pub fn save(&self) -> [f64; SAVED] {
        [
            self.ff, self.ffx, self.ffy, self.s, self.beta, self.e.x, self.e.y,
        ]
    }

    pub fn restore(&mut self, saved: &[f64]) {
        self.ff = saved[0];
        self.ffx = saved[1];
        self.ffy = saved[2];
        self.s = saved[3];
        self.beta = saved[4];
        self.e = Vector2::new(saved[5], saved[6]);
    }

    /// Steps from `t0` to `t1` (after the absolute time `origin`, which `p`'s and `vd`'s times
    /// count from) on the grid `dt = 1/(f n)`, cutting the first and last step where `t0`, `t1`
    /// fall between grid points. Accumulates the integral of FFx in `y[Q]`.
    pub fn advance(
        &mut self,
        p: &Clocked,
        vd: Ramp,
        (origin, t0, t1): (f64, f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        let dt = 1.0 / (p.f * f64::from(self.steps_per_period));
        if (t1 - t0) / dt > crate::solve::MAX_STEPS_PER_DO_STEP as f64 {
            return Err(failures::too_many_fixed_steps(
                "two_phase",
                (t1 - t0) / dt,
                dt,
                t1,
            ));
        }
        // The grid in the equations' time: its origin relative to theirs.
        let grid_origin = self.grid_origin - origin;
        let mut t = t0;
        while t < t1 {
            // The grid point after t; round-off may put (t - origin)/dt just below an integer.
            let mut k = ((t - grid_origin) / dt).floor() + 1.0;
            if grid_origin + k * dt <= t + 1e-9 * dt {
                k += 1.0;
            }
            let mut next = grid_origin + k * dt;
            if next > t1 - 1e-9 * dt {
                next = t1;
            }
            self.step(p, vd, t, next - t, y);
            work.steps += 1;
            t = next;
        }
        if y.iter().all(|v| v.is_finite()) && self.ff.is_finite() {
            Ok(())
        } else {
            Err(failures::fixed_step_not_finite("two_phase", t1))
        }
    }

    /// One step of eq. 11-29 over `h`. The drive stretch takes the exact integral of vd over the
    /// step (its midpoint value, vd being linear in t).
    fn step(&mut self, p: &Clocked, vd: Ramp, t: f64, h: f64, y: &mut [f64]) {
        let law = &p.law;
        let n_old = Vector2::new(y[X], y[Y]);
        let z = Vector2::new(y[ZX], y[ZY]);
        let s = z.norm();
        let m_point = n_old - z;

        // The body under the drive and the previous step's contact force (eq. 7-10).
        let vd_mid = vd.at(t + 0.5 * h);
        if p.held {
            y[LAMBDA] += h * vd_mid;
        } else {
            let fd = p.drive_force(y, vd.at(t));
            y[VX] += h * (fd - self.ffx) / p.m;
            y[VY] += h * self.ffy / p.m;
            y[X] += h * y[VX];
            y[Y] += h * y[VY];
            y[LAMBDA] += h * (vd_mid - y[VX]);
        }
        let n1 = Vector2::new(y[X], y[Y]);

        // Phase 1 (eq. 11-18): N moved to N1', M slides on the line M N1'.
        let d1 = n1 - m_point;
        let mn1 = d1.norm();
        let mut e1 = if mn1 > 0.0 { d1 / mn1 } else { self.e };
        let vr1 = (mn1 - s) / h;
        let mut s1p = s + (vr1 - vr1.abs() / law.g(vr1) * s) * h;
        if s1p < 0.0 {
            s1p = -s1p;
            e1 = -e1;
        }
        let m1p = n1 - s1p * e1;

        // Phase 2 (eq. 19-25): the support carries M by eta * dyp.
        let dyp = p.support_position(t + h) - p.support_position(t);
        let m1pp = m1p + Vector2::new(0.0, p.eta * dyp);
        let d2 = n1 - m1pp;
        let n1m1pp = d2.norm();
        let mut e2 = if n1m1pp > 0.0 { d2 / n1m1pp } else { e1 };
        let vr2 = (n1m1pp - s1p) / h;
        let mut s1 = s1p + (vr2 - vr2.abs() / law.g(vr2) * s1p) * h;
        if s1 < 0.0 {
            s1 = -s1;
            e2 = -e2;
        }

        // eq. 26-29 with sdot = (s1 - s)/dt and vr = vr1 + vr2.
        let vr = vr1 + vr2;
        let ff = law.force(s1, (s1 - s) / h, vr);
        let z1 = s1 * e2;
        y[ZX] = z1.x;
        y[ZY] = z1.y;
        self.e = e2;
        self.s = s1;
        self.ff = ff;
        self.ffx = ff * e2.x;
        self.ffy = -ff * e2.y;
        self.beta = (-e2.y).atan2(e2.x);
        y[Q] += self.ffx * h;
        // The work on the contact with the force at the step's end, as the body's update uses it.
        y[W] += ff * vr * h;
    }
}
