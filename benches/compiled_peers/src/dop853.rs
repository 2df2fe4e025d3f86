//! A textbook Dormand-Prince 8(5,3) pair (Hairer, Norsett & Wanner, Solving Ordinary Differential
//! Equations I, section II.10, and Hairer's `dop853` code): the eighth-order solution, the error
//! norm combined from the fifth- and third-order estimates, Hairer's step control (safety 0.9,
//! the step scaled by 1/3 to 6, exponent 1/8, no integral part) and initial step. No kink
//! handling, no integrating factor, no dense output: the peer a user writes from the book. It
//! stands beside ode_solvers' Dop853, which on scene T takes millions of right-hand sides without
//! meeting the tolerance (results.md).

use crate::problem::Problem;

/// The nodes c_1 .. c_12.
const C: [f64; 12] = [
    0.0,
    0.05260015195876773,
    0.0789002279381516,
    0.1183503419072274,
    0.2816496580927726,
    0.3333333333333333,
    0.25,
    0.3076923076923077,
    0.6512820512820513,
    0.6,
    0.8571428571428571,
    1.0,
];
/// The stages' coefficients, row s holding a_{s+1, r+1} (the lower triangle).
const A: [[f64; 11]; 12] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        0.05260015195876773,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.0197250569845379,
        0.0591751709536137,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.02958758547680685,
        0.0,
        0.08876275643042054,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.2413651341592667,
        0.0,
        -0.8845494793282861,
        0.924834003261792,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.037037037037037035,
        0.0,
        0.0,
        0.17082860872947386,
        0.12546768756682242,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.037109375,
        0.0,
        0.0,
        0.17025221101954405,
        0.06021653898045596,
        -0.017578125,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.03709200011850479,
        0.0,
        0.0,
        0.17038392571223998,
        0.10726203044637328,
        -0.015319437748624402,
        0.008273789163814023,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.6241109587160757,
        0.0,
        0.0,
        -3.3608926294469414,
        -0.868219346841726,
        27.59209969944671,
        20.154067550477894,
        -43.48988418106996,
        0.0,
        0.0,
        0.0,
    ],
    [
        0.47766253643826434,
        0.0,
        0.0,
        -2.4881146199716677,
        -0.590290826836843,
        21.230051448181193,
        15.279233632882423,
        -33.28821096898486,
        -0.020331201708508627,
        0.0,
        0.0,
    ],
    [
        -0.9371424300859873,
        0.0,
        0.0,
        5.186372428844064,
        1.0914373489967295,
        -8.149787010746927,
        -18.52006565999696,
        22.739487099350505,
        2.4936055526796523,
        -3.0467644718982196,
        0.0,
    ],
    [
        2.273310147516538,
        0.0,
        0.0,
        -10.53449546673725,
        -2.0008720582248625,
        -17.9589318631188,
        27.94888452941996,
        -2.8589982771350235,
        -8.87285693353063,
        12.360567175794303,
        0.6433927460157636,
    ],
];
/// The weights of the eighth-order solution.
const B: [f64; 12] = [
    0.054293734116568765,
    0.0,
    0.0,
    0.0,
    0.0,
    4.450312892752409,
    1.8915178993145003,
    -5.801203960010585,
    0.3111643669578199,
    -0.1521609496625161,
    0.20136540080403034,
    0.04471061572777259,
];
/// The weights of the fifth-order error estimate.
const E5: [f64; 12] = [
    0.01312004499419488,
    0.0,
    0.0,
    0.0,
    0.0,
    -1.2251564463762044,
    -0.4957589496572502,
    1.6643771824549864,
    -0.35032884874997366,
    0.3341791187130175,
    0.08192320648511571,
    -0.022355307863886294,
];
/// The weights of the third-order error estimate.
const E3: [f64; 12] = [
    -0.18980075407240762,
    0.0,
    0.0,
    0.0,
    0.0,
    4.450312892752409,
    1.8915178993145003,
    -5.801203960010585,
    -0.4226823213237919,
    -0.1521609496625161,
    0.20136540080403034,
    0.02265179219836082,
];

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
                b += B[s] * k[s][i];
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
