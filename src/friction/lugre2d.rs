//! LuGre contact in the sliding plane (paper T, eq. 2-6): a bristle `z = N - M` from the support
//! point M to the body point N, deflected by both motions and slipping back at a rate set by the
//! Stribeck curve.
//!
//! `g(v)` here is a deflection (m), as in the paper: the Stribeck force divided by kt.

use nalgebra::Vector2;

/// How the bristle slips back (paper T).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlipLaw {
    /// `|v1|/g(v1) + |v2|/g(v2)`: each motion slips the contact on its own, the limit of the
    /// paper's two-phase step.
    Split,
    /// `|v1 + v2|/g(v1 + v2)`: slip on the total radial rate.
    Total,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuGre2d {
    /// Tangential contact stiffness kt (N/m).
    pub kt: f64,
    /// Coulomb force FC (N).
    pub fc: f64,
    /// Static force FS (N).
    pub fs: f64,
    /// Stribeck velocity vs, also the damping cut-off ve (m/s).
    pub vs: f64,
    /// Contact damping without sliding, 2 zeta sqrt(m kt) (N s/m), eq. 5.
    pub h0: f64,
    /// Viscous coefficient hv (N s/m).
    pub hv: f64,
}

/// The contact's state of motion at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Unit vector N - M (along the relative velocity when the bristle is undeflected).
    pub e: Vector2<f64>,
    /// Deflection |z| (m).
    pub s: f64,
    /// Radial rate from the body's motion, e . v_body (m/s).
    pub v1: f64,
    /// Radial rate from the support's motion, -e . v_M (m/s).
    pub v2: f64,
    /// Bristle rate dz/dt (m/s).
    pub zdot: Vector2<f64>,
    /// Magnitude of the friction force FF (eq. 2), N.
    pub ff: f64,
    /// FF's two parts: the spring kt z, and the damping ht sdot + hv vr along e.
    elastic: Vector2<f64>,
    damping: f64,
}

impl Contact {
    /// FFx = FF cos(beta): the force resisting +x. Written as kt z_x + damping e_x rather than
    /// FF e_x: the spring part is ready as soon as z is, which keeps the right-hand side's
    /// longest chain of dependent operations short.
    #[inline]
    pub fn ffx(&self) -> f64 {
        self.elastic.x + self.damping * self.e.x
    }

    /// FFy = FF sin(beta): the y-force acting on the body (M - N = s (-cos beta, sin beta)).
    #[inline]
    pub fn ffy(&self) -> f64 {
        -(self.elastic.y + self.damping * self.e.y)
    }

    /// beta, the direction of the deflection (eq. 26-29).
    pub fn beta(&self) -> f64 {
        (-self.e.y).atan2(self.e.x)
    }
}

impl LuGre2d {
    /// exp(-(v/vs)^2), the Stribeck weight of g and ht. Beyond (v/vs)^2 = 745 exp underflows to
    /// 0 anyway; returning 0 there (tested without a division) skips libm's slow underflow path,
    /// which is where sliding spends almost all its time (v is hundreds of vs).
    #[inline]
    fn stribeck(&self, v: f64) -> f64 {
        let vs2 = self.vs * self.vs;
        if v * v < 745.0 * vs2 {
            (-(v * v) / vs2).exp()
        } else {
            0.0
        }
    }

    /// Stribeck deflection g(v) = (FC + (FS - FC) exp(-(v/vs)^2)) / kt (eq. 4), m.
    pub fn g(&self, v: f64) -> f64 {
        (self.fc + (self.fs - self.fc) * self.stribeck(v)) / self.kt
    }

    /// Contact damping ht(v) = 2 zeta sqrt(m kt) exp(-(v/ve)^2), ve = vs (eq. 6).
    pub fn ht(&self, v: f64) -> f64 {
        self.h0 * self.stribeck(v)
    }

    /// Slip rate |v|/g(v) (1/s) of eq. 3, written with one division: it runs in every
    /// right-hand side of scene T. The division takes only the Stribeck denominator, which
    /// outside the narrow band is a constant the processor has ready (the branch in `stribeck`
    /// is predicted), so it does not wait on v: |v| kt / d would put it on the right-hand
    /// side's longest chain.
    #[inline]
    pub fn slip_rate(&self, v: f64) -> f64 {
        v.abs() * (self.kt / (self.fc + (self.fs - self.fc) * self.stribeck(v)))
    }

    /// Slip rate of the bristle for the radial rates v1 (body) and v2 (support).
    #[inline]
    pub fn slip(&self, law: SlipLaw, v1: f64, v2: f64) -> f64 {
        match law {
            // |v1| kt/d1 + |v2| kt/d2 over one division, which (as in `slip_rate`) takes the
            // denominators alone and so does not wait on v1 and v2.
            SlipLaw::Split => {
                let d1 = self.fc + (self.fs - self.fc) * self.stribeck(v1);
                let d2 = self.fc + (self.fs - self.fc) * self.stribeck(v2);
                (self.kt / (d1 * d2)) * (v1.abs() * d2 + v2.abs() * d1)
            }
            SlipLaw::Total => self.slip_rate(v1 + v2),
        }
    }

    /// FF = kt s + ht(vr) sdot + hv vr (eq. 2).
    #[inline]
    pub fn force(&self, s: f64, sdot: f64, vr: f64) -> f64 {
        self.kt * s + self.damping(sdot, vr)
    }

    /// The damping part of FF, ht(vr) sdot + hv vr. Outside the Stribeck band ht is 0 and the
    /// branch (predicted) skips sdot, so the force does not wait on the bristle rate.
    #[inline]
    fn damping(&self, sdot: f64, vr: f64) -> f64 {
        let ht = self.ht(vr);
        if ht != 0.0 {
            ht * sdot + self.hv * vr
        } else {
            self.hv * vr
        }
    }

    /// The contact for bristle `z`, body velocity `v_body` and velocity `v_m` of the support point
    /// M (eta times the support's): the continuous-time law of paper T.
    #[inline]
    pub fn contact(
        &self,
        law: SlipLaw,
        z: Vector2<f64>,
        v_body: Vector2<f64>,
        v_m: Vector2<f64>,
    ) -> Contact {
        let s = z.norm();
        let (e, v1, v2) = radial_rates(z, v_body, v_m);
        let w = v_body - v_m;
        let zdot = w - self.slip(law, v1, v2) * z;
        let vr = v1 + v2;
        let damping = self.damping(e.dot(&zdot), vr);
        Contact {
            e,
            s,
            v1,
            v2,
            zdot,
            ff: self.kt * s + damping,
            elastic: self.kt * z,
            damping,
        }
    }
}

/// The bristle's direction e and the radial rates v1 = e . v_body and v2 = -e . v_M: all a
/// switching function or the slip rate needs, without the force.
#[inline]
pub fn radial_rates(
    z: Vector2<f64>,
    v_body: Vector2<f64>,
    v_m: Vector2<f64>,
) -> (Vector2<f64>, f64, f64) {
    let s2 = z.norm_squared();
    if s2 > 0.0 {
        // 1/s as s (1/s^2): the square root and the division both wait only for s^2 and run
        // side by side, where 1/sqrt(s^2) chains them, a measurable share of scene T's step
        // (docs/performance.md, "Measurements behind the code"). Below
        // 1e-300, 1/s^2 could overflow. The dot products with z wait only for z, not for 1/s:
        // one product after it instead of two (this runs in every right-hand side of scene T).
        let inv = if s2 > 1e-300 {
            s2.sqrt() * (1.0 / s2)
        } else {
            1.0 / s2.sqrt()
        };
        (z * inv, z.dot(&v_body) * inv, -z.dot(&v_m) * inv)
    } else {
        let e = direction(z, v_body - v_m);
        (e, e.dot(&v_body), -e.dot(&v_m))
    }
}

/// The unit vector of `z`; for `z = 0` the one the bristle is about to take, along the relative
/// velocity `w` (so the force at s = 0 is the damping of 1D LuGre, -(ht + hv) w); +x if both
/// vanish.
#[inline]
pub fn direction(z: Vector2<f64>, w: Vector2<f64>) -> Vector2<f64> {
    let s = z.norm();
    if s > 0.0 {
        // One division, two products: this runs in every right-hand side of scene T.
        z * (1.0 / s)
    } else {
        let speed = w.norm();
        if speed > 0.0 {
            w / speed
        } else {
            Vector2::new(1.0, 0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> LuGre2d {
        let fc = 0.178 * 0.56 * 9.81;
        LuGre2d {
            kt: 6.286e7,
            fc,
            fs: 1.1 * fc,
            vs: 1e-6,
            h0: 2.0 * (0.56f64 * 6.286e7).sqrt(),
            hv: 0.3,
        }
    }

    /// Oracle: eq. 4 and 6 at v = 0 and far beyond vs.
    #[test]
    fn stribeck_and_damping_limits() {
        let l = law();
        assert!((l.g(0.0) * l.kt - l.fs).abs() < 1e-15);
        assert!((l.g(1e-3) * l.kt - l.fc).abs() < 1e-15);
        assert_eq!(l.ht(0.0), l.h0);
        assert_eq!(l.ht(1e-3), 0.0);
    }

    /// Oracle: along x the 2D law is 1D LuGre, F = kt z + ht(v) z' + hv v, z' = v - |v|/g(v) z,
    /// for either sign of the deflection and the velocity.
    #[test]
    fn one_dimensional_motion_is_classical_lugre() {
        let l = law();
        for (z, v) in [(1e-8, 3e-7), (-1e-8, 3e-7), (1.2e-8, -2e-6), (-4e-9, -5e-4)] {
            for slip in [SlipLaw::Split, SlipLaw::Total] {
                let c = l.contact(
                    slip,
                    Vector2::new(z, 0.0),
                    Vector2::new(v, 0.0),
                    Vector2::zeros(),
                );
                let zdot = v - v.abs() / l.g(v) * z;
                let f = l.kt * z + l.ht(v) * zdot + l.hv * v;
                assert!((c.zdot.x - zdot).abs() <= 1e-15 * v.abs().max(1e-9));
                assert!((c.ffx() - f).abs() <= 1e-12 * f.abs(), "{} vs {f}", c.ffx());
                assert_eq!(c.ffy(), 0.0);
            }
        }
    }

    /// Oracle: with the body still and the support moving, the bristle sees -v_M: 1D LuGre in
    /// the support's velocity, along y.
    #[test]
    fn support_motion_alone_is_lugre_along_y() {
        let l = law();
        let (z, vm) = (7e-9, 4e-7);
        let c = l.contact(
            SlipLaw::Split,
            Vector2::new(0.0, z),
            Vector2::zeros(),
            Vector2::new(0.0, vm),
        );
        let v = -vm;
        let zdot = v - v.abs() / l.g(v) * z;
        let f = l.kt * z + l.ht(v) * zdot + l.hv * v;
        assert!((c.zdot.y - zdot).abs() < 1e-20);
        // The y-force on the body is -F (FFy = -FF e_y).
        assert!((c.ffy() + f).abs() <= 1e-12 * f.abs());
    }

    /// Oracle: eq. 2 with FFx = FF cos(beta) and FFy = FF sin(beta), whichever way the force is
    /// summed; in and out of the Stribeck band, at s = 0 and in the plane.
    #[test]
    fn force_components_are_ff_along_the_bristle() {
        let l = LuGre2d { hv: 0.3, ..law() };
        for (z, vb, vm) in [
            ((1e-8, 5e-9), (3e-7, 1e-7), (0.0, -2e-7)),
            ((-4e-9, 1.1e-8), (5e-4, -2e-5), (0.0, 1.4e-3)),
            ((0.0, 0.0), (2e-7, 0.0), (0.0, 1e-7)),
            ((0.0, 0.0), (3e-4, 0.0), (0.0, -1e-3)),
        ] {
            for slip in [SlipLaw::Split, SlipLaw::Total] {
                let c = l.contact(
                    slip,
                    Vector2::new(z.0, z.1),
                    Vector2::new(vb.0, vb.1),
                    Vector2::new(vm.0, vm.1),
                );
                let ff = l.kt * c.s + l.ht(c.v1 + c.v2) * c.e.dot(&c.zdot) + l.hv * (c.v1 + c.v2);
                assert!(
                    (c.ff - ff).abs() <= 1e-12 * ff.abs(),
                    "{z:?}: {} vs {ff}",
                    c.ff
                );
                assert!((c.ffx() - ff * c.e.x).abs() <= 1e-12 * ff.abs(), "{z:?}");
                assert!((c.ffy() + ff * c.e.y).abs() <= 1e-12 * ff.abs(), "{z:?}");
            }
        }
    }

    /// The slip term is continuous at z = 0 and the split and total laws agree when only one
    /// motion is present.
    #[test]
    fn slip_laws_agree_with_one_motion_and_vanish_at_zero_deflection() {
        let l = law();
        let v_body = Vector2::new(3e-4, -1e-4);
        let tiny = Vector2::new(1e-30, 2e-30);
        let c = l.contact(SlipLaw::Split, tiny, v_body, Vector2::zeros());
        assert!((c.zdot - v_body).norm() < 1e-18);
        let z = Vector2::new(1e-8, 5e-9);
        let a = l.contact(SlipLaw::Split, z, v_body, Vector2::zeros());
        let b = l.contact(SlipLaw::Total, z, v_body, Vector2::zeros());
        assert!((a.zdot - b.zdot).norm() < 1e-18);
        // With both motions the laws differ: |v1| + |v2| >= |v1 + v2|.
        let vm = Vector2::new(0.0, 1e-3);
        let a = l.contact(SlipLaw::Split, z, v_body, vm);
        let b = l.contact(SlipLaw::Total, z, v_body, vm);
        assert!(l.slip(SlipLaw::Split, a.v1, a.v2) > l.slip(SlipLaw::Total, b.v1, b.v2));
    }
}
