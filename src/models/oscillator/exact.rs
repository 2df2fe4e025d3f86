//! The exact non-smooth dry-friction oscillator (switch model): `m u'' + c u' + k u = F(t) - s h`
//! while sliding with `s = sgn(u')`, `u' = 0` while stuck.
//!
//! Each sliding phase is a linear ODE with constant coefficients, so it is solved exactly with
//! the matrix exponential of the system augmented by the forcing: the states
//! `(u, u', P sin(wt), P cos(wt), q)` with `q = (held input force) - s h` obey `y' = M y` with a
//! constant M. Sliding ends where u' reaches 0, located by safeguarded Newton on that closed form
//! to round-off; a stuck phase ends where |F - k u| reaches the breakaway force, in closed form
//! (asin) for the sine forcing. So events fall anywhere inside a communication step.

use super::Forced;
use crate::error::{Error, Failure};
use crate::solve::expm::{expm, mul_vec, Matrix};
use crate::solve::{within_step_budget, Work};
use std::f64::consts::{PI, TAU};

/// What the mass is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    Stuck,
    /// Sliding in the direction of the sign (+1 or -1).
    Sliding(f64),
}

impl Mode {
    pub fn code(self) -> f64 {
        match self {
            Mode::Stuck => 0.0,
            Mode::Sliding(s) => s,
        }
    }

    pub fn from_code(code: f64) -> Option<Mode> {
        if code == 0.0 {
            Some(Mode::Stuck)
        } else if code == 1.0 || code == -1.0 {
            Some(Mode::Sliding(code))
        } else {
            None
        }
    }
}

/// A change of mode: when, where, and into what.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event {
    pub t: f64,
    pub u: f64,
    pub mode: Mode,
}

/// The dynamic state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    pub t: f64,
    pub u: f64,
    pub v: f64,
    pub mode: Mode,
    /// Energy dissipated by friction since the start, the integral of H u'.
    pub dissipated: f64,
}

/// Parameters and the precomputed propagator of one grid step.
#[derive(Clone, Debug, PartialEq)]
pub struct Switch {
    pub plant: Forced,
    /// Sliding (kinetic) friction force.
    pub h: f64,
    /// Breakaway (static) friction force, h or h + ha.
    pub hs: f64,
    /// Longest propagation between checks for a sign change of u'.
    pub grid: f64,
    generator: Matrix<5>,
    grid_propagator: Matrix<5>,
}

/// Most events one call to [`Switch::advance`] may meet per grid interval before it reports the
/// motion as not resolvable (a Zeno-like chatter of stick and slip).
const EVENTS_PER_GRID: f64 = 50.0;

impl Switch {
    pub fn new(plant: Forced, (h, hs): (f64, f64), steps_per_period: f64) -> Result<Self, Error> {
        let Forced { m, c, k, w, .. } = plant;
        let mut generator = [[0.0; 5]; 5];
        generator[0][1] = 1.0;
        generator[1] = [-k / m, -c / m, 1.0 / m, 0.0, 1.0 / m];
        generator[2][3] = w;
        generator[3][2] = -w;
        // The grid resolves the fastest motion: the forcing, the free oscillation and the decay
        // of the velocity under damping.
        let mut shortest = TAU / w;
        if k > 0.0 {
            shortest = shortest.min(TAU * (m / k).sqrt());
        }
        if c > 0.0 {
            shortest = shortest.min(TAU * m / c);
        }
        let grid = shortest / steps_per_period;
        if !(grid > 0.0 && grid.is_finite()) {
            return Err(Error::combination(
                format!("m, c, k and w with a shortest time scale of {shortest} s"),
                "a time scale the exact law resolves (check m, c, k and w)",
            ));
        }
        let grid_propagator = expm(&scaled(&generator, grid))?;
        Ok(Switch {
            plant,
            h,
            hs,
            grid,
            generator,
            grid_propagator,
        })
    }

    /// The excitation force at t (`held` is the input over the current step).
    pub fn force(&self, t: f64, held: f64) -> f64 {
        self.plant.force(t, held)
    }

    /// The mode a mass at rest takes: stuck while the static friction can hold it.
    pub fn settle(&self, t: f64, u: f64, held: f64) -> Mode {
        let f = self.force(t, held) - self.plant.k * u;
        if f.abs() <= self.hs {
            Mode::Stuck
        } else {
            Mode::Sliding(f.signum())
        }
    }

    /// The mode at the start, from the initial velocity.
    pub fn initial_mode(&self, t: f64, u: f64, v: f64, held: f64) -> Mode {
        if v == 0.0 {
            self.settle(t, u, held)
        } else {
            Mode::Sliding(v.signum())
        }
    }

    /// `(H, u'')` in a state: `H = s h` sliding; stuck, the force that holds the mass (clipped
    /// to the breakaway force, so an input set beyond it shows the acceleration it will cause).
    pub fn friction_and_acceleration(&self, st: &State, held: f64) -> (f64, f64) {
        let f = self.force(st.t, held) - self.plant.k * st.u - self.plant.c * st.v;
        let friction = match st.mode {
            Mode::Sliding(s) => s * self.h,
            Mode::Stuck => f.clamp(-self.hs, self.hs),
        };
        (friction, (f - friction) / self.plant.m)
    }

    fn augmented(&self, t: f64, u: f64, v: f64, s: f64, held: f64) -> [f64; 5] {
        let (sin, cos) = if self.plant.input {
            (0.0, 0.0)
        } else {
            (self.plant.w * t).sin_cos()
        };
        let q = if self.plant.input { held } else { 0.0 } - s * self.h;
        [u, v, self.plant.p * sin, self.plant.p * cos, q]
    }

    fn acceleration(&self, y: &[f64; 5]) -> f64 {
        (0..5).map(|j| self.generator[1][j] * y[j]).sum()
    }

    /// Advances `st` to `t_end`. Returns the largest |u| met (u has its extremes where u' = 0,
    /// which are events or stuck phases, so this is exact). `log` receives every mode change.
    /// Each grid step and event counts in `work` as a step, within the communication step's
    /// budget from `at_start`: a grid too fine for the step (a tiny m/c, say) ends in an error,
    /// not in a call that never returns.
    pub fn advance(
        &self,
        st: &mut State,
        t_end: f64,
        held: f64,
        mut log: Option<&mut Vec<Event>>,
        (work, at_start): (&mut Work, &Work),
    ) -> Result<f64, Error> {
        let mut largest = st.u.abs();
        let budget = 10.0 + EVENTS_PER_GRID * ((t_end - st.t) / self.grid).ceil();
        let mut events = 0.0;
        while st.t < t_end {
            work.steps += 1;
            within_step_budget("exact", work, at_start, st.t).map_err(|e| self.too_fine(e))?;
            let (before, u_before) = (st.mode, st.u);
            match st.mode {
                Mode::Stuck => self.stuck(st, t_end, held),
                Mode::Sliding(s) => {
                    self.slide(st, s, t_end, held, (work, at_start))?;
                    // H = h s and u' keeps the sign s over the phase: the work is h |u1 - u0|.
                    st.dissipated += self.h * s * (st.u - u_before);
                }
            }
            largest = largest.max(st.u.abs());
            if st.mode != before {
                events += 1.0;
                if let Some(log) = log.as_deref_mut() {
                    log.push(Event {
                        t: st.t,
                        u: st.u,
                        mode: st.mode,
                    });
                }
                if events > budget {
                    return Err(Error::step(
                        "exact",
                        Failure::Chatter,
                        format!(
                            "the motion switched between sticking and sliding {events} times before t = {}",
                            st.t
                        ),
                        "a motion that does not chatter, which the exact law resolves",
                    ));
                }
            }
        }
        Ok(largest)
    }

    /// A stuck phase: ends at t_end or where |F - k u| passes the breakaway force.
    fn stuck(&self, st: &mut State, t_end: f64, held: f64) {
        st.v = 0.0;
        let f = self.force(st.t, held) - self.plant.k * st.u;
        if f.abs() > self.hs {
            st.mode = Mode::Sliding(f.signum());
            return;
        }
        match self.breakaway(st.t, st.u) {
            Some((t_break, s)) if t_break < t_end => {
                st.t = t_break;
                st.mode = Mode::Sliding(s);
            }
            _ => st.t = t_end,
        }
    }

    /// The first time >= t at which `P sin(wt) - k u` leaves [-hs, hs] for a mass stuck at u,
    /// with the direction of the slip that follows; None if it never does (or the force is a
    /// held input, constant over the step).
    pub fn breakaway(&self, t: f64, u: f64) -> Option<(f64, f64)> {
        if self.plant.input || self.plant.p == 0.0 {
            return None;
        }
        let phase = (self.plant.w * t).rem_euclid(TAU);
        // Crossings a hair behind the current phase are round-off of one happening now.
        let behind = 1e-12 * (1.0 + (self.plant.w * t).abs());
        let mut best: Option<(f64, f64)> = None;
        let mut consider = |crossing: f64, s: f64| {
            let mut ahead = (crossing - phase).rem_euclid(TAU);
            if ahead > TAU - behind {
                ahead = 0.0;
            }
            let time = t + ahead / self.plant.w;
            if best.is_none_or(|(b, _)| time < b) {
                best = Some((time, s));
            }
        };
        // Upward through +hs: P sin = k u + hs with sin rising (cos > 0).
        let up = (self.plant.k * u + self.hs) / self.plant.p;
        if up.abs() < 1.0 {
            consider(up.asin(), 1.0);
        }
        // Downward through -hs: P sin = k u - hs with sin falling (cos < 0).
        let down = (self.plant.k * u - self.hs) / self.plant.p;
        if down.abs() < 1.0 {
            consider(PI - down.asin(), -1.0);
        }
        best
    }

    /// The budget's error, with the grid that exhausted it.
    fn too_fine(&self, budget: Error) -> Error {
        Error {
            expected: format!(
                "{}; sign changes of u' are looked for every {:.3e} s (the fastest of the forcing, the free oscillation and the decay m/c, over steps_per_period): fewer steps_per_period",
                budget.expected, self.grid
            ),
            ..budget
        }
    }

    /// A sliding phase in direction s: ends at t_end or where u' returns to 0.
    fn slide(
        &self,
        st: &mut State,
        s: f64,
        t_end: f64,
        held: f64,
        (work, at_start): (&mut Work, &Work),
    ) -> Result<(), Error> {
        while st.t < t_end {
            work.steps += 1;
            within_step_budget("exact", work, at_start, st.t).map_err(|e| self.too_fine(e))?;
            let dt = self.grid.min(t_end - st.t);
            let y0 = self.augmented(st.t, st.u, st.v, s, held);
            let propagator = if dt == self.grid {
                self.grid_propagator
            } else {
                expm(&scaled(&self.generator, dt))?
            };
            let y1 = mul_vec(&propagator, &y0);
            if let Some(tau) = self.stop_within(&y0, &y1, s, dt)? {
                let y = mul_vec(&expm(&scaled(&self.generator, tau))?, &y0);
                st.t += tau;
                st.u = y[0];
                st.v = 0.0;
                st.mode = self.settle(st.t, st.u, held);
                return Ok(());
            }
            st.t = if dt == t_end - st.t { t_end } else { st.t + dt };
            st.u = y1[0];
            st.v = y1[1];
        }
        Ok(())
    }

    /// `(s u', s u'')` at tau after y0.
    fn speed(&self, y0: &[f64; 5], s: f64, tau: f64) -> Result<(f64, f64), Error> {
        let y = mul_vec(&expm(&scaled(&self.generator, tau))?, y0);
        Ok((s * y[1], s * self.acceleration(&y)))
    }

    /// The first tau in (0, dt] where the speed s*u' drops to 0, if any.
    fn stop_within(
        &self,
        y0: &[f64; 5],
        y1: &[f64; 5],
        s: f64,
        dt: f64,
    ) -> Result<Option<f64>, Error> {
        let (g0, d0) = (s * y0[1], s * self.acceleration(y0));
        let (g1, d1) = (s * y1[1], s * self.acceleration(y1));
        let (mut lo, mut hi) = (0.0, dt);
        if g1 <= 0.0 {
            if g0 <= 0.0 {
                // The phase starts at rest (breakaway): the speed is positive just after the
                // start, find a point where it is.
                let mut found = false;
                for _ in 0..60 {
                    let mid = 0.5 * hi;
                    if self.speed(y0, s, mid)?.0 > 0.0 {
                        lo = mid;
                        found = true;
                        break;
                    }
                    hi = mid;
                }
                if !found {
                    return Ok(Some(0.0));
                }
            }
        } else {
            // Both ends positive: a dip to zero in between needs the speed to fall then rise.
            // Right after a breakaway (speed 0 at the start) the speed only grows at first.
            if g0 <= 0.0 || !(d0 < 0.0 && d1 > 0.0) {
                return Ok(None);
            }
            let predicted = hermite_minimum(g0, d0 * dt, g1, d1 * dt);
            if predicted > 0.5 * g0.min(g1) {
                return Ok(None);
            }
            let bottom = self.bottom(y0, s, dt)?;
            if self.speed(y0, s, bottom)?.0 > 0.0 {
                return Ok(None);
            }
            hi = bottom;
        }
        self.root(y0, s, lo, hi).map(Some)
    }

    /// Where s*u' has its minimum in (0, dt), knowing s*u'' < 0 at 0 and > 0 at dt.
    fn bottom(&self, y0: &[f64; 5], s: f64, dt: f64) -> Result<f64, Error> {
        let (mut lo, mut hi) = (0.0, dt);
        while hi - lo > 4.0 * f64::EPSILON * dt {
            let mid = 0.5 * (lo + hi);
            if self.speed(y0, s, mid)?.1 < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Ok(hi)
    }

    /// The zero of s*u' in [lo, hi] (positive at lo, not at hi), by Newton kept inside the
    /// bracket, to round-off.
    fn root(&self, y0: &[f64; 5], s: f64, mut lo: f64, mut hi: f64) -> Result<f64, Error> {
        let mut tau = lo;
        for _ in 0..200 {
            let (g, d) = self.speed(y0, s, tau)?;
            if g > 0.0 {
                lo = tau;
            } else {
                hi = tau.max(lo);
            }
            if g == 0.0 {
                return Ok(tau);
            }
            let newton = tau - g / d;
            let next = if newton > lo && newton < hi && d.is_finite() && d != 0.0 {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - tau).abs() <= 2.0 * f64::EPSILON * hi.max(f64::MIN_POSITIVE)
                || hi - lo <= 2.0 * f64::EPSILON * hi
            {
                return Ok(next);
            }
            tau = next;
        }
        Ok(hi)
    }
}

fn scaled(a: &Matrix<5>, x: f64) -> Matrix<5> {
    let mut r = *a;
    for row in r.iter_mut() {
        for v in row.iter_mut() {
            *v *= x;
        }
    }
    r
}

/// The minimum over [0, 1] of the cubic Hermite interpolant with values g0, g1 and slopes
/// d0, d1 (per unit interval): a cheap screen for a dip between two grid points.
fn hermite_minimum(g0: f64, d0: f64, g1: f64, d1: f64) -> f64 {
    (0..=32)
        .map(|i| {
            let x = f64::from(i) / 32.0;
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * g0
                + (x3 - 2.0 * x2 + x) * d0
                + (-2.0 * x3 + 3.0 * x2) * g1
                + (x3 - x2) * d1
        })
        .fold(f64::INFINITY, f64::min)
}
