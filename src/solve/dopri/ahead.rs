//! A dopri5 step read inside: an interpolant of the step's own order, for the communication
//! points that fall inside a step taken past them.
//!
//! Hairer's `contd5`, which locates kinks, is of order 4 inside the step, one below the step
//! itself: read at every point it lands several times the tolerance off (docs/performance.md,
//! "Cost per call"). Two more right-hand sides raise it to order 5 (bootstrapping, as Enright,
//! Jackson, Norsett and Thomsen, "Interpolants for Runge-Kutta formulas", 1986): the
//! derivative at theta = 1/3 and 2/3, evaluated at contd5's state there, whose error the step
//! then multiplies by h. The quintic matches the step's ends, the derivatives there and those
//! two. With the integrating factor it is the quintic of u = e^(sigma tau) (y - c), as contd5's.

use super::{Decaying, Dense, Switching, Trial, MAX_DECAYING, MAX_SWITCHES};
use crate::solve::{Work, MAX_DIM};

/// The interior nodes whose derivatives the quintic matches.
const NODES: [f64; 2] = [1.0 / 3.0, 2.0 / 3.0];

/// u(theta) = u0 + sum_m a_m theta^m, m = 1..5, from D = u1 - u0 and the derivatives times h at
/// 0, 1/3, 2/3 and 1 (rows: a_1..a_5; columns: D, F0, F(1/3), F(2/3), F1).
const WEIGHTS: [[f64; 5]; 5] = [
    [0.0, 1.0, 0.0, 0.0, 0.0],
    [30.0, -13.0 / 2.0, -27.0 / 4.0, -27.0 / 2.0, -13.0 / 4.0],
    [-110.0, 67.0 / 4.0, 135.0 / 4.0, 189.0 / 4.0, 49.0 / 4.0],
    [135.0, -18.0, -189.0 / 4.0, -54.0, -63.0 / 4.0],
    [-54.0, 27.0 / 4.0, 81.0 / 4.0, 81.0 / 4.0, 27.0 / 4.0],
];

/// One accepted dopri5 step, read at any point inside it to the step's order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quintic {
    /// The step's start and length, in the equations' time.
    pub t: f64,
    pub h: f64,
    /// The states covered.
    n: usize,
    /// u0 and a_1..a_5 of each state.
    coefficients: [[f64; MAX_DIM]; 6],
    /// sigma h, the components whose quintic is that of u, and their shift c.
    sigma_h: f64,
    decaying: Decaying,
    shift: [f64; MAX_DECAYING],
}

/// What a step taken ahead leaves for the next, which starts at its end: the derivative there
/// (the next step's first stage), the switching functions there (a kink the step ended on
/// marked as crossed), how many, and the decay rate; and the switches at the step's start,
/// which with its quintic foretell a kink in the next step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Carry {
    /// The step's end, in its run's time.
    pub(super) end: f64,
    pub(super) k1: [f64; MAX_DIM],
    pub(super) sw: [f64; MAX_SWITCHES],
    pub(super) count: usize,
    pub(super) sigma: f64,
    pub(super) sw_prev: [f64; MAX_SWITCHES],
}

/// How many numbers [`Carry::write`] writes.
pub const CARRY_SAVED: usize = 3 + MAX_DIM + 2 * MAX_SWITCHES;

impl Carry {
    /// Appends [`CARRY_SAVED`] numbers that [`Carry::read`] takes back to the same bits.
    pub fn write(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&[self.end, self.count as f64, self.sigma]);
        out.extend_from_slice(&self.k1);
        out.extend_from_slice(&self.sw);
        out.extend_from_slice(&self.sw_prev);
    }

    /// What [`Carry::write`] wrote; None where the numbers cannot be one.
    pub fn read(saved: &[f64]) -> Option<Self> {
        if saved.len() != CARRY_SAVED {
            return None;
        }
        let count = saved[1];
        if !(count >= 0.0 && count <= MAX_SWITCHES as f64 && count.fract() == 0.0) {
            return None;
        }
        let (k1, rest) = saved[3..].split_at(MAX_DIM);
        let (sw, sw_prev) = rest.split_at(MAX_SWITCHES);
        Some(Carry {
            end: saved[0],
            count: count as usize,
            sigma: saved[2],
            k1: k1.try_into().ok()?,
            sw: sw.try_into().ok()?,
            sw_prev: sw_prev.try_into().ok()?,
        })
    }
}

/// How many numbers [`Quintic::write`] writes.
pub const SAVED_LEN: usize = 5 + 6 * MAX_DIM + 2 * MAX_DECAYING;

impl Quintic {
    /// The interpolant of the accepted trial `tr` of length `h` from `(t, y)`: two right-hand
    /// sides more, counted in `work`.
    pub(super) fn new<S: Switching + ?Sized>(
        ode: &S,
        (t, y): (f64, &[f64]),
        tr: &Trial,
        h: f64,
        work: &mut Work,
    ) -> Self {
        let n = ode.dim().min(MAX_DIM);
        let coupled = ode.coupled().min(n);
        // The right-hand side reads the coupled states alone (the decaying ones among them).
        let order_four = Dense::new(coupled, y, tr, h);
        let sigma = tr.sigma;
        // u'(theta) h at the nodes, from contd5's state there.
        let mut node_slopes = [[0.0; MAX_DIM]; 2];
        for (slopes, theta) in node_slopes.iter_mut().zip(NODES) {
            let mut y_node = [0.0; MAX_DIM];
            if cfg!(debug_assertions) {
                // A right-hand side that reads a quadrature it declared uncoupled gets NaN.
                y_node[coupled..n].fill(f64::NAN);
            }
            let back = order_four.at_with_decay(theta, coupled, &mut y_node);
            let mut f = [0.0; MAX_DIM];
            ode.rhs(t + theta * h, &y_node[..n], &mut f[..n]);
            for (m, j) in tr.decaying.iter().enumerate() {
                f[j] = (f[j] + sigma * (y_node[j] - tr.shift[m])) / back;
            }
            for j in 0..n {
                slopes[j] = h * f[j];
            }
        }
        work.rhs_evaluations += 2;
        let (u0, u1) = tr.ends_of_u(n, y);
        let mut coefficients = [[0.0; MAX_DIM]; 6];
        for j in 0..n {
            let data = [
                u1[j] - u0[j],
                h * tr.k[0][j],
                node_slopes[0][j],
                node_slopes[1][j],
                h * tr.k[6][j],
            ];
            coefficients[0][j] = u0[j];
            for (row, weights) in coefficients[1..].iter_mut().zip(&WEIGHTS) {
                row[j] = weights.iter().zip(&data).map(|(w, d)| w * d).sum();
            }
        }
        Quintic {
            t,
            h,
            n,
            coefficients,
            sigma_h: sigma * h,
            decaying: tr.decaying,
            shift: tr.shift,
        }
    }

    /// The step's end.
    pub fn end(&self) -> f64 {
        self.t + self.h
    }

    /// The states at time `t` (inside the step) into `out`.
    pub fn at(&self, t: f64, out: &mut [f64; MAX_DIM]) {
        self.at_theta((t - self.t) / self.h, self.n, out);
    }

    /// The first `len` states at `t + theta h` into `out` (past the step's end: extrapolated).
    pub(super) fn at_theta(&self, theta: f64, len: usize, out: &mut [f64; MAX_DIM]) {
        let c = &self.coefficients;
        for j in 0..len.min(self.n) {
            out[j] = c[0][j]
                + theta
                    * (c[1][j]
                        + theta
                            * (c[2][j] + theta * (c[3][j] + theta * (c[4][j] + theta * c[5][j]))));
        }
        if !self.decaying.is_empty() {
            let back = (-self.sigma_h * theta).exp();
            for (m, j) in self.decaying.iter().enumerate() {
                out[j] = self.shift[m] + out[j] * back;
            }
        }
    }

    /// Appends [`SAVED_LEN`] numbers that [`Quintic::read`] takes back to the same bits.
    pub fn write(&self, out: &mut Vec<f64>) {
        out.extend_from_slice(&[self.t, self.h, self.n as f64, self.sigma_h]);
        out.push(self.decaying.len as f64);
        for row in &self.coefficients {
            out.extend_from_slice(row);
        }
        out.extend(self.decaying.index.iter().map(|&j| j as f64));
        out.extend_from_slice(&self.shift);
    }

    /// The step [`Quintic::write`] wrote; None where the numbers cannot be one.
    pub fn read(saved: &[f64]) -> Option<Self> {
        if saved.len() != SAVED_LEN {
            return None;
        }
        let count = |x: f64, most: usize| {
            (x >= 0.0 && x <= most as f64 && x.fract() == 0.0).then_some(x as usize)
        };
        let n = count(saved[2], MAX_DIM)?;
        let len = count(saved[4], MAX_DECAYING)?;
        let mut coefficients = [[0.0; MAX_DIM]; 6];
        for (row, chunk) in coefficients.iter_mut().zip(saved[5..].chunks(MAX_DIM)) {
            row.copy_from_slice(chunk);
        }
        let rest = &saved[5 + 6 * MAX_DIM..];
        let mut decaying = Decaying::NONE;
        for (index, &x) in decaying.index.iter_mut().zip(&rest[..MAX_DECAYING]) {
            *index = count(x, n.saturating_sub(1))?;
        }
        decaying.len = len;
        let mut shift = [0.0; MAX_DECAYING];
        shift.copy_from_slice(&rest[MAX_DECAYING..]);
        let step = Quintic {
            t: saved[0],
            h: saved[1],
            n,
            coefficients,
            sigma_h: saved[3],
            decaying,
            shift,
        };
        (step.h > 0.0 && step.h.is_finite()).then_some(step)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::Relax;
    use super::super::{Dopri5, Switching};
    use super::*;
    use crate::solve::test_odes::Harmonic;

    /// The largest error at `t0 + 0.37 h` of one step of `h` from `(t0, y0)` read inside, against
    /// `exact` there.
    fn read_error<S: Switching>(ode: &S, (t0, y0): (f64, &[f64]), h: f64, exact: &[f64]) -> f64 {
        // A tolerance that accepts the step as proposed.
        let mut d = Dopri5::new(1e3, [1e3; MAX_DIM], h);
        d.h = h;
        let n = ode.dim();
        let mut y = [0.0; MAX_DIM];
        y[..n].copy_from_slice(y0);
        let (end, step, _) = d
            .run_ahead(
                ode,
                (t0, t0 + h, t0 + h),
                &mut y,
                &mut Work::default(),
                None,
            )
            .unwrap();
        assert!(end == t0 + h && (step.end() - end).abs() < 1e-12);
        let mut read = [0.0; MAX_DIM];
        step.at(t0 + 0.37 * h, &mut read);
        (0..n)
            .map(|j| (read[j] - exact[j]).abs())
            .fold(0.0, f64::max)
    }

    /// Oracle: the closed forms of the harmonic oscillator and of a forced relaxation under
    /// the integrating factor. Halving the step divides the error read inside
    /// it by about 64 (2^6, a local error of order 6, as the step's own); contd5's order-4
    /// reading would fall by 32.
    #[test]
    fn reads_inside_the_step_to_fifth_order() {
        let steps = [0.4, 0.2, 0.1, 0.05];
        let harmonic = steps.map(|h| {
            let t = 0.3 + 0.37 * h;
            read_error(
                &Harmonic,
                (0.3, &[0.3f64.cos(), -0.3f64.sin()]),
                h,
                &[t.cos(), -t.sin()],
            )
        });
        // y' = cos t - 30 y, the decay taken by the integrating factor.
        let relax = Relax::cosine(30.0);
        let relaxing = steps.map(|h| {
            let h = 0.1 * h;
            let start = [relax.exact(0.3)];
            read_error(&relax, (0.3, &start), h, &[relax.exact(0.3 + 0.37 * h)])
        });
        for errors in [harmonic, relaxing] {
            for pair in errors.windows(2) {
                let fall = pair[0] / pair[1];
                assert!((55.0..80.0).contains(&fall), "{errors:?}");
            }
        }
    }

    /// What [`Quintic::write`] and [`Carry::write`] write, their `read` takes back to the
    /// same step and carry; numbers that cannot be one are refused.
    #[test]
    fn a_written_step_reads_back() {
        let mut d = Dopri5::new(1e-6, [1e-6; MAX_DIM], 1.0);
        let mut y = [0.01; MAX_DIM];
        let (_, step, carry) = d
            .run_ahead(
                &Relax::cosine(30.0),
                // Past the first steps, which the start's guess keeps short.
                (0.3, 0.5, 1.0),
                &mut y,
                &mut Work::default(),
                None,
            )
            .unwrap();
        assert!(step.sigma_h > 0.0);
        let mut saved = Vec::new();
        step.write(&mut saved);
        assert_eq!(saved.len(), SAVED_LEN);
        assert_eq!(Quintic::read(&saved), Some(step));
        let mut bad = saved.clone();
        bad[2] = 1.5;
        assert_eq!(Quintic::read(&bad), None);
        assert_eq!(Quintic::read(&saved[1..]), None);

        let mut saved = Vec::new();
        carry.write(&mut saved);
        assert_eq!(saved.len(), CARRY_SAVED);
        assert_eq!(Carry::read(&saved), Some(carry));
        saved[1] = -1.0;
        assert_eq!(Carry::read(&saved), None);
    }
}
