//! Scene T without vibration (va or eta fixed at 0 by a variant): the support point M stays
//! put, nothing pushes the body or the bristle across, so y, y' and z_y stay 0 and the contact is
//! 1D LuGre along x (paper T, Fig. 4a). Both slip laws agree there: v2 = -e.v_M = 0, so
//! |v1|/g(v1) + |v2|/g(v2) = |v1 + v2|/g(v1 + v2) = |x'|/g(x'), and with e = (sgn z_x, 0)
//! `FFx = FF e_x = kt z_x + ht(x') z_x' + hv x'`, `z_x' = x' - |x'|/g(x') z_x`, the power on
//! the contact FF (v1 + v2) = FFx x'.
//!
//! The state is the general one's first `dim` entries, so the simulation's outputs read it
//! unchanged: `[x', z_x, lambda]`, which the right-hand side reads, then y' and z_y at rest and the
//! quadratures `[x, w, q]` (q only when the mean force is read).

use super::{
    band_coordinate, kink_switches, Params, Ramp, BAND, COUPLED_AXIAL, LAMBDA, Q, VX, VY, W, X, ZX,
    ZY,
};
use crate::solve::narrow::Narrow;
use crate::solve::switching::{Switching, MAX_SWITCHES};
use crate::solve::Ode;

pub struct Axial<'a> {
    pub p: &'a Params,
    pub vd: Ramp,
    /// Without the force integral q, or with it (`Trim::dim`).
    pub dim: usize,
    /// Where steps also end inside the Stribeck band, as in the plane.
    pub band_points: &'static [f64],
}

impl Axial<'_> {
    fn velocity(&self, y: &[f64]) -> f64 {
        if self.p.held {
            0.0
        } else {
            y[VX]
        }
    }
}

impl Ode for Axial<'_> {
    fn dim(&self) -> usize {
        self.dim
    }

    fn coupled(&self) -> usize {
        COUPLED_AXIAL
    }

    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let p = self.p;
        let v = self.velocity(y);
        let vd = self.vd.at(t);
        let zdot = v - p.law.slip_rate(v) * y[ZX];
        let ffx = p.law.force(y[ZX], zdot, v);
        if p.held {
            dydt[X] = 0.0;
            dydt[VX] = 0.0;
        } else {
            dydt[X] = v;
            dydt[VX] = (p.drive_force(y, vd) - ffx) / p.m;
        }
        dydt[ZX] = zdot;
        dydt[LAMBDA] = vd - v;
        dydt[VY] = 0.0;
        dydt[ZY] = 0.0;
        dydt[W] = ffx * v;
        if self.dim > Q {
            dydt[Q] = ffx;
        }
    }
}

impl Switching for Axial<'_> {
    /// The Stribeck band's edges and the kink of |x'| (the general model's v1 = e_x x' also
    /// changes sign where z_x does, which is no kink here), and the points inside the band the
    /// plane resolves.
    fn switches(&self, _t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize {
        let v = self.velocity(y);
        let vs = self.p.law.vs;
        out[0] = v - BAND * vs;
        out[1] = v + BAND * vs;
        kink_switches(v, vs, self.band_points, out, 2)
    }

    /// z_x relaxes at the slip rate |x'|/g(x'), taken exactly within each dopri5 step as in the
    /// plane.
    fn switches_and_decay(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> (usize, f64) {
        let n = self.switches(t, y, out);
        (n, self.p.law.slip_rate(self.velocity(y)))
    }

    fn decaying(&self) -> &[usize] {
        &[ZX]
    }

    /// x' in units of vs, from the band's edges, as v1 + v2 in the plane.
    #[inline]
    fn narrow(&self, sw: &[f64; MAX_SWITCHES]) -> Option<Narrow> {
        Some(band_coordinate(sw, self.p.law.vs))
    }
}
