//! Scene T's equations: the parameters they read ([`Params`]), the continuous-time ODE with
//! its switching functions ([`Equations`]), and the absolute tolerances on the scale of each
//! state ([`tolerance_scales`]). The 1D equations without vibration are `axial`'s.

use super::{COUPLED, DIM, LAMBDA, Q, VX, VY, W, X, Y, ZX, ZY};
use crate::friction::lugre2d::{radial_rates, Contact, LuGre2d, SlipLaw};
use crate::models::ramp::Ramp;
use crate::solve::narrow::Narrow;
use crate::solve::phase::{cos_turns, turns};
use crate::solve::switching::{Switching, MAX_SWITCHES};
use crate::solve::{Ode, MAX_DIM};
use nalgebra::Vector2;
use std::cell::Cell;
use std::f64::consts::TAU;

/// Half-width of the band |v1 + v2| < BAND vs where ht and g vary; dopri5 ends steps on its
/// edges and moves v1 + v2 by at most vs a step inside it ([`crate::solve::narrow`]), so the
/// damping pulse there (tens of ns wide at the paper's values) is never stepped over.
/// exp(-BAND^2) ~ 1e-7 outside.
pub(super) const BAND: f64 = 4.0;

/// The damping band's coordinate (the rate in units of vs) read off its edges, switches 0 and
/// 1 of both the plane and the axial equations: the narrow feature dopri5 and radau5 watch.
#[inline]
pub(super) fn band_coordinate(sw: &[f64; MAX_SWITCHES], vs: f64) -> Narrow {
    Narrow {
        r: 0.5 * (sw[0] + sw[1]) / vs,
        band: BAND,
    }
}

/// Writes, from `out[k]`, the switching functions of a rate `v` whose absolute value has a
/// kink: v itself and v -+ m vs for the band's `points` ([`solver::band_points`]). Returns the next
/// free index.
#[inline]
pub(super) fn kink_switches(
    v: f64,
    vs: f64,
    points: &[f64],
    out: &mut [f64; MAX_SWITCHES],
    k: usize,
) -> usize {
    out[k] = v;
    let mut k = k + 1;
    for &m in points {
        out[k] = v - m * vs;
        out[k + 1] = v + m * vs;
        k += 2;
    }
    k
}

/// Switching function `j` of those [`kink_switches`] writes for the rate `v` from its first
/// index: v itself, then v -+ m vs for each of the band's `points`.
#[inline]
pub(super) fn kink_switch(v: f64, vs: f64, points: &[f64], j: usize) -> f64 {
    match j {
        0 => v,
        _ => {
            let m = points[(j - 1) / 2];
            if j % 2 == 1 {
                v - m * vs
            } else {
                v + m * vs
            }
        }
    }
}

/// Everything the equations need, fixed at build time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub law: LuGre2d,
    pub slip: SlipLaw,
    pub m: f64,
    pub kd: f64,
    pub hd: f64,
    pub eta: f64,
    pub va: f64,
    pub f: f64,
    /// Body held at x = y = 0 (Fig. 4b).
    pub held: bool,
}

/// [`Params`] on the equations' clock. The equations run on the time since the simulation's
/// current time, so that neither the forcing's phase nor the solvers' steps lose digits to a
/// large start time; `phase0` is the support's phase, in turns, then. Params stay as built;
/// the clock moves with the simulation (`Clocked::set_time`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clocked {
    pub p: Params,
    pub phase0: f64,
}

impl std::ops::Deref for Clocked {
    type Target = Params;

    fn deref(&self) -> &Params {
        &self.p
    }
}

impl Clocked {
    /// `p` with the equations' time starting at the absolute time `t`.
    pub fn at(p: Params, t: f64) -> Self {
        Clocked {
            p,
            phase0: turns(t, p.f),
        }
    }

    /// Moves the time origin of the equations to the absolute time `t`.
    pub(super) fn set_time(&mut self, t: f64) {
        self.phase0 = turns(t, self.p.f);
    }

    /// The velocity of the contact point M carried by the support: eta * (0, yp'), `t` after
    /// the simulation's current time (as every time these equations take).
    #[inline]
    pub fn support_velocity(&self, t: f64) -> Vector2<f64> {
        Vector2::new(
            0.0,
            self.eta * self.va * cos_turns(self.phase0 + t * self.f),
        )
    }

    /// Support displacement yp = u0 sin(wt), u0 = va/w.
    pub fn support_position(&self, t: f64) -> f64 {
        self.va / (TAU * self.f) * (TAU * (self.phase0 + t * self.f).fract()).sin()
    }

    #[inline]
    pub fn contact(&self, t: f64, y: &[f64]) -> Contact {
        self.contact_moving(y, self.support_velocity(t))
    }
}

impl Params {
    #[inline]
    pub(super) fn body_velocity(&self, y: &[f64]) -> Vector2<f64> {
        if self.held {
            Vector2::zeros()
        } else {
            Vector2::new(y[VX], y[VY])
        }
    }

    /// The angular frequency of the body on the stuck contact and the drive, sqrt((kt + kd)/m):
    /// the fastest motion an explicit step of the mechanics must resolve (none when held).
    pub fn sticking_frequency(&self) -> f64 {
        if self.held {
            0.0
        } else {
            ((self.law.kt + self.kd) / self.m).sqrt()
        }
    }

    /// The contact with the support point moving at `v_m`.
    #[inline]
    pub(super) fn contact_moving(&self, y: &[f64], v_m: Vector2<f64>) -> Contact {
        self.law.contact(
            self.slip,
            Vector2::new(y[ZX], y[ZY]),
            self.body_velocity(y),
            v_m,
        )
    }

    /// The radial rates (v1, v2) alone, for the switching functions, with the support point
    /// moving at `v_m`.
    #[inline]
    pub(super) fn radial_rates(&self, y: &[f64], v_m: Vector2<f64>) -> (f64, f64) {
        let (_, v1, v2) = radial_rates(Vector2::new(y[ZX], y[ZY]), self.body_velocity(y), v_m);
        (v1, v2)
    }

    pub fn drive_force(&self, y: &[f64], vd: f64) -> f64 {
        let vx = if self.held { 0.0 } else { y[VX] };
        self.kd * y[LAMBDA] + self.hd * (vd - vx)
    }
}

/// Absolute tolerances on the scale of each state, per unit of rtol: the deflection FC/kt, the
/// velocities in play (drive velocity `vd`), a period's worth of the force integral. The work is
/// left out of the error control (infinite): the steps the motion needs integrate it to the same
/// order. The force integral stays in it also when the mean is not read (q stays in the planar
/// state): its error control keeps the force as accurate as in the full model (ten times less
/// without, at rtol 1e-9 in stick-slip at 3 kHz).
pub fn tolerance_scales(p: &Params, vd: f64) -> [f64; MAX_DIM] {
    let law = &p.law;
    let z0 = law.fc / law.kt;
    let speed = vd.abs() + p.va + law.vs;
    let mut scale = [0.0; MAX_DIM];
    scale[X] = z0;
    scale[VX] = speed;
    scale[Y] = z0;
    scale[VY] = speed;
    scale[ZX] = z0;
    scale[ZY] = z0;
    scale[LAMBDA] = if p.kd > 0.0 { law.fc / p.kd } else { z0 };
    scale[Q] = law.fc / p.f;
    scale[W] = f64::INFINITY;
    scale
}

/// The continuous-time ODE with the drive velocity `vd(t)`.
pub struct Equations<'a> {
    p: &'a Clocked,
    vd: Ramp,
    /// Where steps also end inside the Stribeck band ([`solver::band_points`]).
    band_points: &'static [f64],
    /// The support velocity at the last time asked for: dopri5's last two stages and the
    /// switching functions after them all fall on the step's end, and the cos is a fifth of a
    /// right-hand side.
    last_support: Cell<(f64, Vector2<f64>)>,
}

impl<'a> Equations<'a> {
    pub fn new(p: &'a Clocked, vd: Ramp, band_points: &'static [f64]) -> Self {
        Equations {
            p,
            vd,
            band_points,
            // NaN: equal to no time.
            last_support: Cell::new((f64::NAN, Vector2::zeros())),
        }
    }

    /// `Params::support_velocity`, remembered for one time. Always inlined, with its cos: the
    /// compiler leaves both as calls otherwise, which makes a step measurably dearer
    /// (docs/performance.md, "Measurements behind the code").
    #[inline(always)]
    fn support_velocity(&self, t: f64) -> Vector2<f64> {
        let (t_last, v_last) = self.last_support.get();
        if t == t_last {
            return v_last;
        }
        let v = self.p.support_velocity(t);
        self.last_support.set((t, v));
        v
    }
}

impl Ode for Equations<'_> {
    fn dim(&self) -> usize {
        DIM
    }

    fn coupled(&self) -> usize {
        COUPLED
    }

    #[inline]
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let p = self.p;
        let c = p.contact_moving(y, self.support_velocity(t));
        let vd = self.vd.at(t);
        if p.held {
            for j in [X, VX, Y, VY] {
                dydt[j] = 0.0;
            }
            dydt[LAMBDA] = vd;
        } else {
            let fd = p.drive_force(y, vd);
            // One division for both accelerations.
            let inv_m = 1.0 / p.m;
            dydt[X] = y[VX];
            dydt[VX] = (fd - c.ffx()) * inv_m;
            dydt[Y] = y[VY];
            dydt[VY] = c.ffy() * inv_m;
            dydt[LAMBDA] = vd - y[VX];
        }
        dydt[ZX] = c.zdot.x;
        dydt[ZY] = c.zdot.y;
        dydt[Q] = c.ffx();
        dydt[W] = c.ff * (c.v1 + c.v2);
    }
}

impl Switching for Equations<'_> {
    #[inline]
    fn switches(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize {
        let (v1, v2) = self.p.radial_rates(y, self.support_velocity(t));
        self.switches_of(v1, v2, out)
    }

    #[inline(always)]
    fn switch(&self, t: f64, y: &[f64], i: usize) -> f64 {
        let (v1, v2) = self.p.radial_rates(y, self.support_velocity(t));
        self.switch_of(v1, v2, i)
    }

    /// The bristle relaxes at the slip rate: z' = w - slip z.
    #[inline]
    fn switches_and_decay(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> (usize, f64) {
        let (v1, v2) = self.p.radial_rates(y, self.support_velocity(t));
        let slip = self.p.law.slip(self.p.slip, v1, v2);
        (self.switches_of(v1, v2, out), slip)
    }

    fn decaying(&self) -> &[usize] {
        &[ZX, ZY]
    }

    /// The total law's slip rate |v1 + v2| / g follows the vibration smoothly between its
    /// kinks. Frozen at a step's middle rather than its start, it gives FFx_mean in the steady
    /// vibration with less error for the same work (over a transient from the start it is
    /// neither better nor worse). The split law's error is set by the Stribeck band's bump
    /// instead, and there the middle costs more at equal error. Measured on the benchmark's
    /// case: docs/performance.md, "Benchmarks" and "Measurements behind the code".
    fn decay_follows_trend(&self) -> bool {
        self.p.slip == SlipLaw::Total
    }

    /// v1 + v2 in units of vs, from the band's edges (`switches_of`): the damping's pulse
    /// ht(v1 + v2) sdot. Where the body turns, v1 + v2 can also dip into the band and out again
    /// between two step ends, which the edges alone do not see.
    #[inline]
    fn narrow(&self, sw: &[f64; MAX_SWITCHES]) -> Option<Narrow> {
        Some(band_coordinate(sw, self.p.law.vs))
    }
}

impl Equations<'_> {
    #[inline(always)]
    pub(super) fn switches_of(&self, v1: f64, v2: f64, out: &mut [f64; MAX_SWITCHES]) -> usize {
        let vr = v1 + v2;
        let vs = self.p.law.vs;
        let band = BAND * vs;
        out[0] = vr - band;
        out[1] = vr + band;
        let points = self.band_points;
        match self.p.slip {
            // |v1| and |v2| have kinks.
            SlipLaw::Split => {
                let k = kink_switches(v1, vs, points, out, 2);
                kink_switches(v2, vs, points, out, k)
            }
            SlipLaw::Total => kink_switches(vr, vs, points, out, 2),
        }
    }

    /// `switches_of(v1, v2)[i]` alone.
    #[inline(always)]
    pub(super) fn switch_of(&self, v1: f64, v2: f64, i: usize) -> f64 {
        let vr = v1 + v2;
        let vs = self.p.law.vs;
        let points = self.band_points;
        match (i, self.p.slip) {
            (0, _) => vr - BAND * vs,
            (1, _) => vr + BAND * vs,
            (_, SlipLaw::Split) => {
                let family = 1 + 2 * points.len();
                if i - 2 < family {
                    kink_switch(v1, vs, points, i - 2)
                } else {
                    kink_switch(v2, vs, points, i - 2 - family)
                }
            }
            (_, SlipLaw::Total) => kink_switch(vr, vs, points, i - 2),
        }
    }
}
