//! The matrix exponential of a small constant matrix: the exact propagator of a linear ODE
//! `y' = M y`, used where a phase of motion is linear (the sliding phases of a dry-friction
//! oscillator), so that the solution is exact to round-off at any step.
//!
//! Scaling and squaring with the degree-13 Pade approximant (Higham 2005, SIAM J. Matrix Anal.
//! Appl. 26(4)), which is accurate to round-off for every norm.

use super::dense::{lu_factor, lu_solve};
use crate::error::{Error, Failure};

pub type Matrix<const N: usize> = [[f64; N]; N];

/// Pade(13) coefficients b_0..b_13.
const B: [f64; 14] = [
    64_764_752_532_480_000.0,
    32_382_376_266_240_000.0,
    7_771_770_303_897_600.0,
    1_187_353_796_428_800.0,
    129_060_195_264_000.0,
    10_559_470_521_600.0,
    670_442_572_800.0,
    33_522_128_640.0,
    1_323_241_920.0,
    40_840_800.0,
    960_960.0,
    16_380.0,
    182.0,
    1.0,
];

/// The norm below which Pade(13) needs no scaling (Higham 2005, Table 2.3).
const THETA_13: f64 = 5.371_920_351_148_152;

pub fn mul<const N: usize>(a: &Matrix<N>, b: &Matrix<N>) -> Matrix<N> {
    let mut c = [[0.0; N]; N];
    for i in 0..N {
        for k in 0..N {
            let aik = a[i][k];
            if aik != 0.0 {
                for j in 0..N {
                    c[i][j] += aik * b[k][j];
                }
            }
        }
    }
    c
}

pub fn mul_vec<const N: usize>(a: &Matrix<N>, x: &[f64; N]) -> [f64; N] {
    let mut y = [0.0; N];
    for i in 0..N {
        y[i] = (0..N).map(|j| a[i][j] * x[j]).sum();
    }
    y
}

fn norm_1<const N: usize>(a: &Matrix<N>) -> f64 {
    (0..N)
        .map(|j| (0..N).map(|i| a[i][j].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// `sum_k c_k * m_k` plus `c_i * I`.
fn combine<const N: usize>(terms: &[(f64, &Matrix<N>)], c_identity: f64) -> Matrix<N> {
    let mut r = [[0.0; N]; N];
    for (c, m) in terms {
        for i in 0..N {
            for j in 0..N {
                r[i][j] += c * m[i][j];
            }
        }
    }
    for (i, row) in r.iter_mut().enumerate() {
        row[i] += c_identity;
    }
    r
}

/// The norm above which [`expm`] balances: balancing saves squarings, whose round-off a
/// non-normal matrix amplifies, but below four of them it costs more than it can save (a third
/// of a 7 x 7 exponential).
const BALANCE_ABOVE: f64 = 16.0 * THETA_13;

/// `(d, b)` with `b = D^-1 a D`, `D = diag(d)` of powers of 2 (so exact), whose rows and columns
/// have comparable norms (Parlett & Reinsch 1969, as LAPACK's dgebal without permutations).
fn balance<const N: usize>(a: &Matrix<N>) -> ([f64; N], Matrix<N>) {
    let mut b = *a;
    let mut d = [1.0; N];
    // Each scaling applied shrinks its row and column's sum by at least 5 %, so the sweeps end;
    // the bound only guards against a loop.
    for _ in 0..200 {
        let mut converged = true;
        for i in 0..N {
            let off = |x: f64, k: usize| if k == i { 0.0 } else { x.abs() };
            let column: f64 = (0..N).map(|k| off(b[k][i], k)).sum();
            let row: f64 = (0..N).map(|k| off(b[i][k], k)).sum();
            if column == 0.0 || row == 0.0 {
                continue;
            }
            // The power of 2 f that brings column f and row / f within a factor 2 of each other
            // (c tracks column f^2).
            let (mut c, mut f) = (column, 1.0);
            while c < row / 2.0 {
                f *= 2.0;
                c *= 4.0;
            }
            while c >= row * 2.0 {
                f /= 2.0;
                c /= 4.0;
            }
            if (c + row) / f < 0.95 * (column + row) {
                converged = false;
                d[i] *= f;
                for x in b[i].iter_mut() {
                    *x /= f;
                }
                for row in b.iter_mut() {
                    row[i] *= f;
                }
            }
        }
        if converged {
            break;
        }
    }
    (d, b)
}

/// `exp(a)`; an error if `a` is not finite or the Pade denominator is singular (it is not for
/// any finite matrix after scaling, so that only guards against NaN input).
///
/// A badly scaled `a` (a motor with a tiny inertia: entries from 1e-13 to 1e15) is balanced
/// first, `exp(a) = D exp(D^-1 a D) D^-1`: its norm, and with it the number of squarings whose
/// round-off a non-normal matrix amplifies, can fall by many orders.
pub fn expm<const N: usize>(a: &Matrix<N>) -> Result<Matrix<N>, Error> {
    let norm = norm_1(a);
    if !norm.is_finite() {
        return Err(Error::step(
            "matrix exponential",
            Failure::NotFinite,
            format!("a matrix with norm {norm}"),
            "a finite matrix",
        ));
    }
    if norm > BALANCE_ABOVE {
        let (d, balanced) = balance(a);
        let balanced_norm = norm_1(&balanced);
        if balanced_norm < norm {
            let mut e = expm_unbalanced(&balanced, balanced_norm)?;
            for (i, row) in e.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x *= d[i] / d[j];
                }
            }
            return Ok(e);
        }
    }
    expm_unbalanced(a, norm)
}

/// `exp(a)` for `a` of 1-norm `norm`: scaling by a power of 2, Pade(13), squaring.
#[inline]
fn expm_unbalanced<const N: usize>(a: &Matrix<N>, norm: f64) -> Result<Matrix<N>, Error> {
    let squarings = if norm > THETA_13 {
        (norm / THETA_13).log2().ceil() as i32
    } else {
        0
    };
    let scale = 2f64.powi(-squarings);
    let mut a1 = *a;
    for row in a1.iter_mut() {
        for x in row.iter_mut() {
            *x *= scale;
        }
    }
    let a2 = mul(&a1, &a1);
    let a4 = mul(&a2, &a2);
    let a6 = mul(&a4, &a2);
    let inner_u = combine(&[(B[13], &a6), (B[11], &a4), (B[9], &a2)], 0.0);
    let outer_u = combine(&[(B[7], &a6), (B[5], &a4), (B[3], &a2)], B[1]);
    let u_even = mul(&a6, &inner_u);
    let u_even = combine(&[(1.0, &u_even), (1.0, &outer_u)], 0.0);
    let u = mul(&a1, &u_even);
    let inner_v = combine(&[(B[12], &a6), (B[10], &a4), (B[8], &a2)], 0.0);
    let v = mul(&a6, &inner_v);
    let v = combine(&[(1.0, &v), (B[6], &a6), (B[4], &a4), (B[2], &a2)], B[0]);
    // exp(a1) - I ~ (V - U)^-1 (V + U) - I = (V - U)^-1 2U, solved column by column. The
    // squarings below carry E = exp - I, never exp itself: a stiff matrix's slow modes are
    // parts in 1e13 or less of I in exp(a1), so 1 + E rounds them away and the squarings
    // multiply what is left (a motor with L = 1e-15 H had its current 26 % off), while E keeps
    // them to round-off of their own size.
    let mut lhs = combine(&[(1.0, &v), (-1.0, &u)], 0.0);
    let rhs = combine(&[(2.0, &u)], 0.0);
    let mut pivots = [0; N];
    if !lu_factor(&mut lhs, N, &mut pivots) {
        return Err(Error::step(
            "matrix exponential",
            Failure::NotFinite,
            "a singular Pade denominator",
            "a matrix whose exponential f64 holds",
        ));
    }
    let mut r = [[0.0; N]; N];
    for j in 0..N {
        let mut col = [0.0; N];
        for i in 0..N {
            col[i] = rhs[i][j];
        }
        lu_solve(&lhs, N, &pivots, &mut col);
        for i in 0..N {
            r[i][j] = col[i];
        }
    }
    // (I + E)^2 = I + (2E + E^2).
    for _ in 0..squarings {
        r = combine(&[(2.0, &r), (1.0, &mul(&r, &r))], 0.0);
    }
    for (i, row) in r.iter_mut().enumerate() {
        row[i] += 1.0;
    }
    Ok(r)
}

/// How many step sizes [`Propagators`] remembers.
const PROPAGATOR_SLOTS: usize = 4;

/// The propagators `expm(A h)` of one constant A for the last few step sizes h. A master whose
/// communication points are `t0 + i h` hands the FMU steps that differ from h, and from each
/// other, by round-off of t: two values take turns while t stays within one binade, so one
/// remembered step would miss on about every other call, and each miss costs a whole matrix
/// exponential. A remembered step is the same number, so its propagator is the one a new
/// exponential would give, bit for bit.
#[derive(Clone, Debug, PartialEq)]
pub struct Propagators<const N: usize> {
    /// (h, expm(A h)); h = 0 marks an empty slot (no step is 0).
    slots: [(f64, Matrix<N>); PROPAGATOR_SLOTS],
    /// The slot the next new step size replaces (the oldest).
    next: usize,
}

impl<const N: usize> Default for Propagators<N> {
    fn default() -> Self {
        Propagators {
            slots: [(0.0, [[0.0; N]; N]); PROPAGATOR_SLOTS],
            next: 0,
        }
    }
}

impl<const N: usize> Propagators<N> {
    /// The propagator of step `h > 0`: remembered, or made by `make(h)` and remembered.
    pub fn get<E>(
        &mut self,
        h: f64,
        make: impl FnOnce(f64) -> Result<Matrix<N>, E>,
    ) -> Result<&Matrix<N>, E> {
        let slot = match self.slots.iter().position(|&(step, _)| step == h) {
            Some(slot) => slot,
            None => {
                let slot = self.next;
                self.slots[slot] = (h, make(h)?);
                self.next = (slot + 1) % PROPAGATOR_SLOTS;
                slot
            }
        };
        Ok(&self.slots[slot].1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: the closed form of a damped harmonic oscillator's propagator,
    /// exp([[0, 1], [-w0^2, -2 z w0]] t) for z < 1, and of a rotation.
    #[test]
    fn matches_closed_forms() {
        let (w0, z) = (3.0f64, 0.1f64);
        for t in [1e-3, 0.7, 25.0] {
            let e = expm(&[[0.0, t], [-w0 * w0 * t, -2.0 * z * w0 * t]]).unwrap();
            let wd = w0 * (1.0 - z * z).sqrt();
            let decay = (-z * w0 * t).exp();
            let (s, c) = (wd * t).sin_cos();
            let exact = [
                [decay * (c + z * w0 / wd * s), decay * s / wd],
                [-decay * w0 * w0 / wd * s, decay * (c - z * w0 / wd * s)],
            ];
            for i in 0..2 {
                for j in 0..2 {
                    let scale = 1.0 + exact[i][j].abs().max(decay);
                    assert!(
                        (e[i][j] - exact[i][j]).abs() < 1e-13 * scale * (1.0 + t),
                        "t {t} ({i},{j}): {} vs {}",
                        e[i][j],
                        exact[i][j]
                    );
                }
            }
        }
        let r = expm(&[[0.0, 40.0], [-40.0, 0.0]]).unwrap();
        assert!((r[0][0] - 40f64.cos()).abs() < 1e-13);
        assert!((r[0][1] - 40f64.sin()).abs() < 1e-13);
        assert!(expm(&[[f64::NAN, 0.0], [0.0, 0.0]]).is_err());
    }

    /// A badly scaled damped oscillator, as a motor with a tiny inertia gives:
    /// exp([[0, x], [-w0^2/x, -2 z w0]] t) is the closed form above with the off-diagonal
    /// entries scaled by x and 1/x. Unbalanced, its norm w0^2 t/x needs 52 squarings at
    /// x = 1e-12, whose round-off the non-normal matrix amplifies until not one digit is right
    /// (7.39 for 0.048).
    #[test]
    fn badly_scaled_matrices_are_balanced() {
        let (w0, z, t) = (4e3f64, 0.3f64, 2e-3);
        for x in [1e-12, 1.0, 1e9] {
            let e = expm(&[[0.0, x * t], [-w0 * w0 / x * t, -2.0 * z * w0 * t]]).unwrap();
            let wd = w0 * (1.0 - z * z).sqrt();
            let decay = (-z * w0 * t).exp();
            let (s, c) = (wd * t).sin_cos();
            let exact = [
                [decay * (c + z * w0 / wd * s), x * decay * s / wd],
                [-decay * w0 * w0 / wd * s / x, decay * (c - z * w0 / wd * s)],
            ];
            for i in 0..2 {
                for j in 0..2 {
                    // Each entry against its own scale, the similarity's x^(j-i) times decay.
                    let scale =
                        decay * x.powi(j as i32 - i as i32) * [[1.0, 1.0 / wd], [wd, 1.0]][i][j];
                    assert!(
                        (e[i][j] - exact[i][j]).abs() < 1e-12 * scale,
                        "x {x} ({i},{j}): {} vs {}",
                        e[i][j],
                        exact[i][j]
                    );
                }
            }
        }
    }

    /// Oracle: a fresh exponential of each step. The steps a master's points t = i h hand the
    /// FMU are remembered after a few calls (two take turns within a binade of t), and each
    /// remembered propagator is the fresh one, bit for bit.
    #[test]
    fn propagators_remember_the_round_off_variants_of_a_step() {
        let a = [[-2.0, 1.0], [0.5, -3.0]];
        let scaled = |h: f64| expm(&[[a[0][0] * h, a[0][1] * h], [a[1][0] * h, a[1][1] * h]]);
        let mut cache = Propagators::<2>::default();
        let (mut made, mut t) = (0, 0.0);
        for i in 1..=100_000u32 {
            let target = f64::from(i) * 1e-6;
            let h = target - t;
            t = target;
            let remembered = *cache
                .get(h, |h| {
                    made += 1;
                    scaled(h)
                })
                .unwrap();
            assert_eq!(remembered, scaled(h).unwrap(), "step {i}");
        }
        // A few for each binade of t (17 here); one remembered step would make tens of thousands.
        assert!(made < 100, "{made} exponentials for 100 000 steps");
    }
}
