//! A textbook Dormand-Prince 8(5,3) pair (Hairer, Norsett & Wanner, Solving Ordinary Differential
//! Equations I, section II.10, and Hairer's `dop853` code): the eighth-order solution, the error
//! norm combined from the fifth- and third-order estimates, Hairer's step control (safety 0.9,
//! the step scaled by 1/3 to 6, exponent 1/8, no integral part) and initial step. No kink
//! handling, no integrating factor, no dense output: the peer a user writes from the book. It
//! stands beside ode_solvers' Dop853, which on scene T takes millions of right-hand sides without
//! meeting the tolerance (results.md).

use crate::problem::Problem;
// The method's coefficients (the numbers are the method's, whoever writes the stepper).
use friction_fmu::solve::dop853::{A, C, E3, E5};

/// Every step's end (times, states) and the right-hand sides taken.
pub type Steps<const N: usize> = (Vec<f64>, Vec<[f64; N]>, u64);

/// More steps than this in one leg end it with an error.
const MAX_STEPS: u64 = 10_000_000;

/// Every step's end of an integration from `t0` to `t1` (the last one `t1`), and the right-hand
/// sides it took. The error of state i is measured against `tol (scale[i] + |y_i|)`, the same
/// absolute tolerance per state as the other peers are given.
#[allow(clippy::needless_range_loop)]
pub fn integrate<P: Problem, const N: usize>(
    problem: &P,
    (t0, t1): (f64, f64),
    y0: [f64; N],
    tol: f64,
    scale: &[f64],
) -> Result<Steps<N>, String> {
    let weight = |y: &[f64; N], y_new: &[f64; N], i: usize| {
        tol * (scale[i] + y[i].abs().max(y_new[i].abs()))
    };
    let mut y = y0;
    let mut k = [[0.0; N]; 12];
    problem.rhs(t0, &y, &mut k[0]);
    let mut evaluations = 1;
    let mut h = initial_step(problem, t0, &y, &k[0], tol, scale, t1 - t0);
    evaluations += 1;
    let (mut ts, mut ys) = (vec![t0], vec![y]);
    let mut t = t0;
    let mut steps = 0;
    while t < t1 {
        steps += 1;
        if steps > MAX_STEPS {
            return Err(format!("more than {MAX_STEPS} steps (stopped at t = {t})"));
        }
        let last = t + 1.01 * h >= t1;
        if last {
            h = t1 - t;
        }
        let mut stage = [0.0; N];
        for s in 1..12 {
            for i in 0..N {
                let mut sum = 0.0;
                for r in 0..s {
                    sum += A[s][r] * k[r][i];
                }
                stage[i] = y[i] + h * sum;
            }
            let (_, rest) = k.split_at_mut(s);
            problem.rhs(t + C[s] * h, &stage, &mut rest[0]);
        }
        evaluations += 11;
        let mut y_new = [0.0; N];
        let (mut sum5, mut sum3) = (0.0, 0.0);
        for i in 0..N {
            let (mut b, mut e5, mut e3) = (0.0, 0.0, 0.0);
            for s in 0..12 {
                b += A[12][s] * k[s][i];
                e5 += E5[s] * k[s][i];
                e3 += E3[s] * k[s][i];
            }
            y_new[i] = y[i] + h * b;
            let w = weight(&y, &y_new, i);
            sum5 += (e5 / w).powi(2);
            sum3 += (e3 / w).powi(2);
        }
        let mut denominator = sum5 + 0.01 * sum3;
        if denominator <= 0.0 {
            denominator = 1.0;
        }
        let err = h * sum5 / (denominator * N as f64).sqrt();
        let fac = err.powf(0.125) / 0.9;
        if err <= 1.0 {
            t = if last { t1 } else { t + h };
            y = y_new;
            // First same as last: the next step's first stage.
            let mut first = [0.0; N];
            problem.rhs(t, &y, &mut first);
            evaluations += 1;
            k[0] = first;
            ts.push(t);
            ys.push(y);
            h /= fac.clamp(1.0 / 6.0, 3.0);
        } else {
            // A non-finite error (a step far past the stability bound overflowed) is a
            // rejection by the largest factor, as any error above it.
            h /= if fac.is_finite() { fac.min(3.0) } else { 3.0 };
            if t + h == t {
                return Err(format!("the step vanished at t = {t}"));
            }
        }
    }
    Ok((ts, ys, evaluations))
}

/// Hairer's initial step for an order-8 method (`hinit`): from the sizes of y, f and f's change
/// over an explicit Euler step (one right-hand side).
fn initial_step<P: Problem, const N: usize>(
    problem: &P,
    t: f64,
    y: &[f64; N],
    f: &[f64; N],
    tol: f64,
    scale: &[f64],
    span: f64,
) -> f64 {
    let w = |i: usize| tol * (scale[i] + y[i].abs());
    let norm = |v: &[f64; N]| {
        let sum: f64 = (0..N).map(|i| (v[i] / w(i)).powi(2)).sum();
        (sum / N as f64).sqrt()
    };
    let (dy, df) = (norm(y), norm(f));
    let mut h = if dy <= 1e-10 || df <= 1e-10 {
        1e-6
    } else {
        0.01 * dy / df
    };
    h = h.min(span);
    let mut euler = [0.0; N];
    for i in 0..N {
        euler[i] = y[i] + h * f[i];
    }
    let mut f1 = [0.0; N];
    problem.rhs(t + h, &euler, &mut f1);
    let mut change = [0.0; N];
    for i in 0..N {
        change[i] = f1[i] - f[i];
    }
    let d2 = norm(&change) / h;
    let size = df.max(d2);
    let h1 = if size <= 1e-15 {
        (1e-6f64).max(h * 1e-3)
    } else {
        (0.01 / size).powf(0.125)
    };
    (100.0 * h).min(h1).min(span)
}
