//! LuGre friction, 1D standard form (Canudas de Wit et al. 1995):
//! `F = sigma0 z + sigma1 dz/dt + sigma2 v`, `dz/dt = v - sigma0 |v|/g(v) z`,
//! `g(v) = FC + (FS - FC) exp(-(v/vs)^2)`.

use super::{relax, sgn};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LuGre {
    pub sigma0: f64,
    pub sigma1: f64,
    pub sigma2: f64,
    pub fc: f64,
    pub fs: f64,
    pub vs: f64,
}

impl LuGre {
    /// Steady-state friction force g(v) (Stribeck curve), in N.
    pub fn g(&self, v: f64) -> f64 {
        self.fc + (self.fs - self.fc) * (-(v / self.vs).powi(2)).exp()
    }

    pub fn rate(&self, z: f64, v: f64) -> f64 {
        v - self.sigma0 * v.abs() / self.g(v) * z
    }

    pub fn force(&self, z: f64, v: f64) -> f64 {
        self.sigma0 * z + self.sigma1 * self.rate(z, v) + self.sigma2 * v
    }

    /// Exact `(z(h), integral of F)` for `v` frozen over `h`: the bristle equation is linear in
    /// z then, so [`relax`] solves it at any stiffness. The damping term integrates to
    /// `sigma1 * (z(h) - z0)` exactly.
    pub fn advance(&self, z0: f64, v: f64, h: f64) -> (f64, f64) {
        let g = self.g(v);
        let (z1, z_integral) = relax(z0, sgn(v) * g / self.sigma0, self.sigma0 * v.abs() / g, h);
        let force_integral =
            self.sigma0 * z_integral + self.sigma1 * (z1 - z0) + self.sigma2 * v * h;
        (z1, force_integral)
    }
}

#[cfg(test)]
mod tests {
    use super::LuGre;

    #[test]
    fn steady_sliding_force_is_the_stribeck_curve() {
        let law = LuGre {
            sigma0: 1e5,
            sigma1: 3.0,
            sigma2: 0.5,
            fc: 1.0,
            fs: 1.5,
            vs: 0.01,
        };
        let v = 0.01;
        let (z, _) = law.advance(0.0, v, 1.0);
        let expected = law.g(v) + law.sigma2 * v;
        assert!((law.force(z, v) - expected).abs() < 1e-12);
    }
}
