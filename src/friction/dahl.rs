//! Dahl friction (Leus & Gutowski, eq. 2.8-2.9):
//! `FT = kt z`, `dz/dt = vr * sgn(u)|u|^alpha`, `u = 1 - (kt/FC) sgn(vr) z`.

use super::{relax, sgn};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dahl {
    pub kt: f64,
    pub fc: f64,
    pub alpha: f64,
}

impl Dahl {
    pub fn force(&self, z: f64) -> f64 {
        self.kt * z
    }

    pub fn rate(&self, z: f64, v: f64) -> f64 {
        let u = 1.0 - self.kt / self.fc * sgn(v) * z;
        // The paper's alpha = 1 (the default) without the power, the same number: a power is
        // most of the rate's cost.
        if self.alpha == 1.0 {
            return v * u;
        }
        v * sgn(u) * u.abs().powf(self.alpha)
    }

    /// The sliding distance after which a bristle at `z`, sliding in direction `s` (+-1), is
    /// within `slack` of saturation in `u` (0 when it is already): finite only for alpha < 1.
    ///
    /// `u` obeys `du/dx = -c sgn(u)|u|^alpha` in the sliding distance x (see [`Dahl::advance`]),
    /// which takes it to 0 after `|u0|^(1-alpha) / (c (1-alpha))` when alpha < 1. There the
    /// rate's slope `alpha c |u|^(alpha-1)` is unbounded, so a solver must stop short of it
    /// rather than step across it; `slack` bounds that slope.
    pub fn distance_to_saturation(&self, z: f64, s: f64, slack: f64) -> f64 {
        if self.alpha >= 1.0 {
            return f64::INFINITY;
        }
        let c = self.kt / self.fc;
        let u = (1.0 - c * s * z).abs();
        if u <= slack {
            return 0.0;
        }
        let power = 1.0 - self.alpha;
        (u.powf(power) - slack.powf(power)) / (c * power)
    }

    /// The deflection at saturation in direction `s`, where the force is `s FC`.
    pub fn saturated(&self, s: f64) -> f64 {
        s * self.fc / self.kt
    }

    /// Exact `(z(h), integral of z)` for `v` frozen over `h`, any `alpha > 0`.
    ///
    /// With `c = kt/FC`, `u` obeys `du/dt = -c|v| sgn(u)|u|^alpha`, which integrates in closed
    /// form: `|u(h)| = |u0| (1 + (alpha-1) c|v| h |u0|^(alpha-1))^(-1/(alpha-1))`, the sign of u
    /// kept; for alpha < 1 u reaches 0 in finite time and stays there. alpha = 1 is the
    /// exponential [`relax`], whose integral is closed form too; otherwise Simpson's rule on the
    /// exact trajectory gives the integral.
    pub fn advance(&self, z0: f64, v: f64, h: f64) -> (f64, f64) {
        let c = self.kt / self.fc;
        let s = sgn(v);
        if s == 0.0 {
            return (z0, z0 * h);
        }
        if self.alpha == 1.0 {
            return relax(z0, s / c, c * v.abs(), h);
        }
        let at = |t: f64| {
            let u0 = 1.0 - c * s * z0;
            let x = (self.alpha - 1.0) * c * v.abs() * t * u0.abs().powf(self.alpha - 1.0);
            let u = if u0 == 0.0 || x <= -1.0 {
                0.0
            } else {
                // ln_1p(x)/(alpha-1) tends to c|v|t|u0|^(alpha-1) as alpha -> 1: no blow-up there.
                u0 * (-(x.ln_1p()) / (self.alpha - 1.0)).exp()
            };
            (1.0 - u) / (c * s)
        };
        let z_half = at(0.5 * h);
        let z1 = at(h);
        (z1, h / 6.0 * (z0 + 4.0 * z_half + z1))
    }
}

#[cfg(test)]
mod tests {
    use super::{sgn, Dahl};

    /// alpha = 1 skips the power and gives its number to the bit, over deflections on both
    /// sides of saturation and both directions of slip.
    #[test]
    fn alpha_one_is_the_power_law_to_the_bit() {
        let law = Dahl {
            kt: 5.6e4,
            fc: 0.01962,
            alpha: 1.0,
        };
        let z_saturated = law.fc / law.kt;
        for i in -300..=300 {
            let z = f64::from(i) / 200.0 * z_saturated;
            for v in [-0.41, -1e-9, 0.0, 3e-7, 0.146] {
                let u = 1.0 - law.kt / law.fc * sgn(v) * z;
                let power = v * sgn(u) * u.abs().powf(1.0);
                assert_eq!(law.rate(z, v).to_bits(), power.to_bits(), "z {z} v {v}");
            }
        }
    }

    /// Below alpha 1 the exact update is `slack` short of saturation at the predicted distance,
    /// and saturated just past the distance for no slack.
    #[test]
    fn saturation_distance_agrees_with_the_exact_update() {
        for alpha in [0.2, 0.5, 0.9] {
            let law = Dahl {
                kt: 5.6e4,
                fc: 0.01962,
                alpha,
            };
            let (z0, v) = (-2e-7, 0.3);
            let x = law.distance_to_saturation(z0, 1.0, 0.0);
            let near = law.distance_to_saturation(z0, 1.0, 1e-6);
            let (z_near, _) = law.advance(z0, v, near / v);
            let u_near = 1.0 - law.kt / law.fc * z_near;
            assert!(
                (u_near - 1e-6).abs() < 1e-12,
                "alpha {alpha}: u {u_near} for 1e-6"
            );
            let (after, _) = law.advance(z0, v, 1.001 * x / v);
            let z_sat = law.saturated(1.0);
            assert!(
                (after - z_sat).abs() < 1e-15 * z_sat,
                "alpha {alpha}: {after}"
            );
        }
        let smooth = Dahl {
            kt: 1.0,
            fc: 1.0,
            alpha: 1.0,
        };
        assert_eq!(smooth.distance_to_saturation(0.0, 1.0, 0.0), f64::INFINITY);
    }

    /// The closed-form update must agree with a fine explicit integration of the ODE itself.
    #[test]
    fn advance_matches_fine_integration_for_several_alphas() {
        for alpha in [0.5, 1.0, 1.7, 3.0] {
            let law = Dahl {
                kt: 5.6e4,
                fc: 0.01962,
                alpha,
            };
            let (v, h) = (0.2, 2e-6);
            let (z_exact, _) = law.advance(-1e-7, v, h);
            let n = 200_000;
            let dt = h / n as f64;
            let mut z = -1e-7;
            for _ in 0..n {
                // midpoint rule
                let zm = z + 0.5 * dt * law.rate(z, v);
                z += dt * law.rate(zm, v);
            }
            assert!(
                (z - z_exact).abs() < 1e-9 * law.fc / law.kt,
                "alpha {alpha}: {z} vs {z_exact}"
            );
        }
    }
}
