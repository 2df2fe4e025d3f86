//! Scene L's `closed_form` solver: at alpha = 1 the Dahl bristle's ODE is linear. Over a
//! sub-step where vr keeps the sign s, `u = 1 - (kt/FC) s z` obeys `u' = -(kt/FC) |vr| u`, so
//! with x(t) the distance slid since the sub-step's start (s x >= 0)
//!
//! `z(t) = z0 - s u0 expm1(-c s x(t)) / c`, `c = kt/FC`,
//!
//! exactly, along the velocity itself (the `exponential` solver freezes it). The work of the
//! force, `FT vr = kt z x'`, integrates in closed form too; the force integral, which FT_mean
//! and S read, is `kt z0 h - FC s u0` times the integral of `expm1(-c s x(t))`, taken by
//! adaptive Gauss-Kronrod quadrature ([`GaussKronrod`]) to the tolerance.

use crate::error::Error;
use crate::friction::dahl::Dahl;
use crate::solve::quadrature::GaussKronrod;
use crate::solve::Work;

/// What a sub-step gives: the deflection at its end, the integral of the force and that of its
/// power (the work on the sliding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Advanced {
    pub z: f64,
    pub force_integral: f64,
    pub power_integral: f64,
}

/// The sliding over one sub-step, from its start: the direction `s` (+-1, or 0 where vr is 0
/// throughout) and the distance slid `slid(t)` at time `t` after the start.
pub struct Sliding<F: Fn(f64) -> f64> {
    pub s: f64,
    pub slid: F,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedForm {
    /// The tolerance asked.
    pub rtol: f64,
    pub quadrature: GaussKronrod,
}

impl ClosedForm {
    /// `rtol` of the force integral, relative to that of `force_scale` (the saturated force FC,
    /// or the spring force of the farthest slide in a period when that is less) over the
    /// sub-step.
    pub fn new(rtol: f64, fc: f64, force_scale: f64) -> Self {
        // The integrand is bounded by 1 and its factor FC |u0| by 2 FC.
        ClosedForm {
            rtol,
            quadrature: GaussKronrod::new(0.5 * rtol * (force_scale / fc).min(1.0)),
        }
    }

    /// Advances the bristle `z0` of `law` (alpha = 1) over `h`; the force integral only when
    /// `with_force_integral`.
    pub fn advance(
        &mut self,
        law: &Dahl,
        sliding: Sliding<impl Fn(f64) -> f64>,
        (z0, h): (f64, f64),
        with_force_integral: bool,
        work: &mut Work,
    ) -> Result<Advanced, Error> {
        let Sliding { s, slid } = sliding;
        // A sub-step counts as a step; with the quadrature, each of its panels does instead.
        if s == 0.0 || !with_force_integral {
            work.steps += 1;
        }
        if s == 0.0 {
            return Ok(Advanced {
                z: z0,
                force_integral: law.kt * z0 * h,
                power_integral: 0.0,
            });
        }
        let c = law.kt / law.fc;
        let u0 = 1.0 - c * s * z0;
        let x1 = slid(h);
        work.rhs_evaluations += 1;
        let decay = (-c * s * x1).exp_m1();
        let force_integral = if with_force_integral {
            // The integral of expm1(-c s x) as that of exp(-c s x) less h: exp is the cheaper,
            // and the difference loses only round-off of h, far below any tolerance times h.
            let integral = self
                .quadrature
                .integrate(|t| (-c * s * slid(t)).exp(), 0.0, h, work)?
                - h;
            law.kt * z0 * h - law.fc * s * u0 * integral
        } else {
            0.0
        };
        Ok(Advanced {
            z: z0 - s * u0 * decay / c,
            force_integral,
            power_integral: law.fc * (s * x1 + u0 * decay / c),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::dopri::Dopri5;
    use crate::solve::{Integrator, Ode, MAX_DIM};

    const LAW: Dahl = Dahl {
        kt: 5.6e4,
        fc: 0.01962,
        alpha: 1.0,
    };

    /// vr = 0.1 + 0.05 cos(3e5 t): positive throughout.
    fn velocity(t: f64) -> f64 {
        0.1 + 0.05 * (3e5 * t).cos()
    }

    fn slid(t: f64) -> f64 {
        0.1 * t + 0.05 / 3e5 * (3e5 * t).sin()
    }

    /// (z, q, w) by the rate itself.
    struct Bristle;

    impl Ode for Bristle {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
            let v = velocity(t);
            dydt[0] = LAW.rate(y[0], v);
            dydt[1] = LAW.force(y[0]);
            dydt[2] = LAW.force(y[0]) * v;
        }
    }

    /// The closed form and its quadrature agree with a tight integration of the ODE, from a
    /// bristle deflected against the slip (the fast transient) and from one at rest.
    #[test]
    fn agrees_with_the_ode_integrated_tightly() {
        let h = 2e-5;
        for z0 in [-0.9 * LAW.fc / LAW.kt, 0.0] {
            let mut y = [z0, 0.0, 0.0];
            Dopri5::new(1e-13, [1e-22; MAX_DIM], h)
                .integrate(&Bristle, 0.0, h, &mut y, &mut Work::default())
                .unwrap();
            for rtol in [1e-6, 1e-10] {
                let mut solver = ClosedForm::new(rtol, LAW.fc, LAW.fc);
                let mut work = Work::default();
                let sliding = Sliding { s: 1.0, slid };
                let got = solver
                    .advance(&LAW, sliding, (z0, h), true, &mut work)
                    .unwrap();
                let z_scale = LAW.fc / LAW.kt;
                assert!((got.z - y[0]).abs() < 1e-12 * z_scale, "{got:?} {y:?}");
                assert!(
                    (got.force_integral - y[1]).abs() < rtol * LAW.fc * h,
                    "rtol {rtol}: {got:?} {y:?}"
                );
                assert!(
                    (got.power_integral - y[2]).abs() < 1e-11 * LAW.fc * slid(h),
                    "{got:?} {y:?}"
                );
            }
        }
    }

    /// Where vr is 0 the bristle holds and does no work.
    #[test]
    fn no_slip_holds_the_bristle() {
        let mut solver = ClosedForm::new(1e-8, LAW.fc, LAW.fc);
        let sliding = Sliding {
            s: 0.0,
            slid: |_| 0.0,
        };
        let got = solver
            .advance(&LAW, sliding, (1e-7, 1e-3), true, &mut Work::default())
            .unwrap();
        assert_eq!(got.z, 1e-7);
        assert_eq!(got.force_integral, LAW.kt * 1e-7 * 1e-3);
        assert_eq!(got.power_integral, 0.0);
    }
}
