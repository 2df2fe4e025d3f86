//! What a peer is given: the equations (the project's own right-hand sides, wrapped), the start,
//! the absolute-tolerance scales and the reading to take.
//!
//! Every peer runs the same two legs, as a user of that solver would: the transient up to the
//! last period with the states the right-hand side reads, then the last period afresh from
//! there, with the force integral started at 0 (scenes T and L) or the extremes of u located
//! (scene O). Starting the integral there keeps the peers' error control on it as tight as
//! ours, whose integral restarts every period.

use friction_fmu::friction::dahl::Dahl;
use friction_fmu::models::oscillator::{Equations as OscillatorEquations, Forced};
use friction_fmu::models::transverse::{Equations as TransverseEquations, COUPLED, DIM, Q};
use friction_fmu::solve::phase::cos_turns;
use friction_fmu::solve::Ode;
use std::cell::Cell;

/// y' = f(t, y) over `y.len()` states, and root functions for the events of a reading.
pub trait Problem {
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    fn root_count(&self) -> usize {
        0
    }
    fn roots(&self, _t: f64, _y: &[f64], _g: &mut [f64]) {}
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reading {
    /// The mean over [t_read, t_end] of the rate of the state after the transient's: the
    /// integral the second leg starts at 0, over the period.
    Mean { period: f64 },
    /// max |y0| over [t_read, t_end], the extremes found where y1 (= y0') changes sign.
    Amplitude,
}

pub struct Spec<P: Problem> {
    pub problem: P,
    /// The start of the transient (its states only).
    pub y0: Vec<f64>,
    /// Absolute-tolerance scales of the reading leg's states (atol = tolerance x scale); the
    /// transient leg uses the first `y0.len()`.
    pub scale: Vec<f64>,
    pub t_read: f64,
    pub t_end: f64,
    pub reading: Reading,
}

/// Scene T's right-hand side ([`TransverseEquations`], the one the simulation's solvers call) on
/// the five states it reads, [v_x, z_x, lambda, v_y, z_y], and the force integral q after them.
pub struct Transverse {
    pub equations: TransverseEquations<'static>,
}

impl Problem for Transverse {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let mut state = [0.0; DIM];
        state[..COUPLED].copy_from_slice(&y[..COUPLED]);
        let mut rate = [0.0; DIM];
        self.equations.rhs(t, &state, &mut rate);
        dy[..COUPLED].copy_from_slice(&rate[..COUPLED]);
        if dy.len() > COUPLED {
            dy[COUPLED] = rate[Q];
        }
    }
}

/// Scene L's bristle with the Dahl law ([`Dahl::rate`], [`Dahl::force`]) under the prescribed
/// vr = vc + va cos(2 pi f t): [z], then the force integral.
pub struct Longitudinal {
    pub law: Dahl,
    pub vc: f64,
    pub va: f64,
    pub f: f64,
}

impl Problem for Longitudinal {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let v = self.vc + self.va * cos_turns(t * self.f);
        dy[0] = self.law.rate(y[0], v);
        if dy.len() > 1 {
            dy[1] = self.law.force(y[0]);
        }
    }
}

/// Scene O's regularised equations ([`OscillatorEquations`] without the work): [u, u'], with
/// u' as the root function for the extremes of u.
pub struct Oscillator {
    pub equations: OscillatorEquations,
}

impl Problem for Oscillator {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.equations.rhs(t, y, dy);
    }
    fn root_count(&self) -> usize {
        1
    }
    fn roots(&self, _t: f64, y: &[f64], g: &mut [f64]) {
        g[0] = y[1];
    }
}

/// What the mass does in the exact switch model: sliding in the direction of the sign, or
/// stuck (0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode(pub f64);

/// Scene O's exact law as a peer must integrate it: `m u'' + c u' + k u = P sin(wt) - s h`
/// while sliding (s = +-1), u' = 0 while stuck; the events are root functions: u' = 0 while
/// sliding, F - k u = +-h while stuck. The equations of
/// [`friction_fmu::models::oscillator::exact`], restated for a general integrator (the simulation
/// solves each phase in closed form).
pub struct Switch {
    pub plant: Forced,
    pub h: f64,
    pub mode: Cell<Mode>,
}

impl Switch {
    /// The force the friction must hold at (t, u) for the mass to stay: F - k u.
    pub fn unbalanced(&self, t: f64, u: f64) -> f64 {
        self.plant.force(t, 0.0) - self.plant.k * u
    }

    /// The mode after an event at (t, u) with u' = 0: stuck while the friction holds the mass,
    /// else sliding the way the unbalanced force pushes.
    pub fn settle(&self, t: f64, u: f64) -> Mode {
        let f = self.unbalanced(t, u);
        if f.abs() <= self.h {
            Mode(0.0)
        } else {
            Mode(f.signum())
        }
    }
}

impl Problem for Switch {
    #[inline]
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let s = self.mode.get().0;
        if s == 0.0 {
            dy[0] = 0.0;
            dy[1] = 0.0;
        } else {
            let pl = &self.plant;
            dy[0] = y[1];
            dy[1] = (pl.force(t, 0.0) - pl.c * y[1] - pl.k * y[0] - s * self.h) / pl.m;
        }
    }
    fn root_count(&self) -> usize {
        3
    }
    fn roots(&self, t: f64, y: &[f64], g: &mut [f64]) {
        if self.mode.get().0 == 0.0 {
            let f = self.unbalanced(t, y[0]);
            g[0] = 1.0;
            g[1] = f - self.h;
            g[2] = f + self.h;
        } else {
            g[0] = y[1];
            g[1] = 1.0;
            g[2] = 1.0;
        }
    }
}
