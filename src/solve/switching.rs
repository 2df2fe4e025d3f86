//! Switching functions: an ODE whose right-hand side is smooth except where one of a few
//! functions of (t, y) is zero. The solvers end their steps on those zeros (a kink inside a step
//! drops a Runge-Kutta method to first order over it, and costs an implicit one's error
//! estimate and Newton iteration dearly); a model gives them with its equations.

use super::narrow::Narrow;
use super::Ode;

/// The most switching functions an ODE may report.
pub const MAX_SWITCHES: usize = 12;

/// An ODE whose right-hand side is smooth except where one of a few functions of (t, y) is zero.
pub trait Switching: Ode {
    /// Writes the switching functions into `out`; returns how many there are. They read the
    /// coupled states alone ([`Ode::coupled`]): the solvers locate kinks on an interpolant of
    /// those.
    fn switches(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize;

    /// Switching function `i` alone, as [`Switching::switches`] writes it; an ODE with many
    /// switches gives it for less, since a kink's root finder asks for one at a time.
    fn switch(&self, t: f64, y: &[f64], i: usize) -> f64 {
        let mut out = [0.0; MAX_SWITCHES];
        self.switches(t, y, &mut out);
        out[i]
    }

    /// The switching functions, and the rate sigma >= 0 at which the components
    /// [`Switching::decaying`] relax now (their right-hand side holds a term -sigma y_j).
    fn switches_and_decay(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> (usize, f64) {
        (self.switches(t, y, out), 0.0)
    }

    /// The components (at most [`MAX_DECAYING`](super::dopri::MAX_DECAYING)) whose linear decay dopri5 takes exactly
    /// within each step, at a rate frozen over it (Lawson's integrating factor): that of the
    /// step's start, or of its middle ([`Switching::decay_follows_trend`]).
    fn decaying(&self) -> &[usize] {
        &[]
    }

    /// Whether the right-hand side stays C1 where switch `i` changes sign (only its second
    /// derivative jumps): [`Dopri5::integrate_to_kink`](super::dopri::Dopri5::integrate_to_kink) then lets a step across it stand when
    /// the step passes its error test, and stops a little past the kink instead of retaking the
    /// step to end on it.
    fn smooth_across(&self, _i: usize) -> bool {
        false
    }

    /// Whether the decay rate's trend over the last step foretells it over the next (it varies
    /// smoothly along the solution between the switches): dopri5 then freezes the rate at the
    /// middle of each step, extrapolated, instead of at its start.
    fn decay_follows_trend(&self) -> bool {
        false
    }

    /// The coordinate of a narrow feature of the right-hand side ([`crate::solve::narrow`]),
    /// from the switching functions' values at a point: steps that pass through its band are
    /// held short enough for the stages to sample it. None: no such feature.
    fn narrow(&self, _switches: &[f64; MAX_SWITCHES]) -> Option<Narrow> {
        None
    }
}

/// Has the switching function gone from `old` to `new` across zero? An old value of exactly 0
/// (the step started on the switch) does not count.
pub(super) fn crossed(old: f64, new: f64) -> bool {
    old != 0.0 && (new == 0.0 || (new > 0.0) != (old > 0.0))
}

/// The switches among the first `count` that [`crossed`] from `old` to `new`, as a mask (bit i:
/// switch i), tested over all the slots without branches (in vector instructions).
#[inline]
pub(super) fn crossings(old: &[f64; MAX_SWITCHES], new: &[f64; MAX_SWITCHES], count: usize) -> u32 {
    const _: () = assert!(MAX_SWITCHES < 32);
    let mut mask = 0u32;
    for i in 0..MAX_SWITCHES {
        let (o, n) = (old[i], new[i]);
        let crossed = (o != 0.0) & ((n == 0.0) | ((n > 0.0) != (o > 0.0)));
        mask |= u32::from(crossed) << i;
    }
    mask & ((1u32 << count.min(MAX_SWITCHES)) - 1)
}

/// An ODE without switching functions, for the solvers that step on [`Switching`] alone.
pub(super) struct Smooth<'a>(pub(super) &'a dyn Ode);

impl Ode for Smooth<'_> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        self.0.rhs(t, y, dydt)
    }
    fn coupled(&self) -> usize {
        self.0.coupled()
    }
}

impl Switching for Smooth<'_> {
    fn switches(&self, _t: f64, _y: &[f64], _out: &mut [f64; MAX_SWITCHES]) -> usize {
        0
    }
}
