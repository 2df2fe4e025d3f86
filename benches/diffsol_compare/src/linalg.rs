//! Our fixed-size LU (src/solve/dense.rs) and expm (src/solve/expm.rs) against nalgebra 0.33's
//! LU and `Matrix::exp` at the sizes the integrators use.

use friction_fmu::cpu_clock::time_cpu;
use friction_fmu::solve::dense::{lu_factor, lu_solve};
use friction_fmu::solve::expm::{expm, Matrix};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use std::hint::black_box;

/// Deterministic entries in (-1, 1).
fn filler(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
}

/// An `I - h A J`-like matrix: identity plus a dense random part of norm ~ `size`.
fn system<const N: usize>(size: f64) -> Matrix<N> {
    let mut next = filler(N as u64);
    let mut a = [[0.0; N]; N];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = size * next() + if i == j { 1.0 } else { 0.0 };
        }
    }
    a
}

/// Median per-call CPU time in ns of `calls` calls of f.
fn per_call(calls: usize, mut f: impl FnMut() -> f64) -> f64 {
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            time_cpu(|| {
                let mut acc = 0.0;
                for _ in 0..calls {
                    acc += f();
                }
                black_box(acc)
            })
            .1
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2] / calls as f64 * 1e9
}

fn residual<const N: usize>(a: &Matrix<N>, x: &[f64], b: &[f64]) -> f64 {
    (0..N)
        .map(|i| ((0..N).map(|j| a[i][j] * x[j]).sum::<f64>() - b[i]).abs())
        .fold(0.0, f64::max)
}

macro_rules! lu_row {
    ($n:literal, $calls:expr) => {{
    const N: usize = $n;
    let calls: usize = $calls;
    let a = system::<N>(0.5);
    let b: Vec<f64> = (0..N).map(|i| 1.0 + i as f64).collect();
    let ours = || {
        let mut lu = black_box(a);
        let mut pivots = [0; N];
        let mut x = [0.0; N];
        x.copy_from_slice(&b);
        lu_factor(&mut lu, N, &mut pivots);
        lu_solve(&lu, N, &pivots, &mut x);
        x
    };
    let sm = SMatrix::<f64, N, N>::from_fn(|i, j| a[i][j]);
    let sb = SVector::<f64, N>::from_column_slice(&b);
    let stat = || {
        black_box(sm)
            .lu()
            .solve(&sb)
            .expect("regular")
    };
    let dm = DMatrix::<f64>::from_fn(N, N, |i, j| a[i][j]);
    let db = DVector::<f64>::from_column_slice(&b);
    let dynamic = || black_box(dm.clone()).lu().solve(&db).expect("regular");
    let t_ours = per_call(calls, || ours()[0]);
    let t_stat = per_call(calls, || stat()[0]);
    let t_dyn = per_call(calls, || dynamic()[0]);
    println!(
        "| LU factor + solve {N}x{N} | {t_ours:.0} | {t_stat:.0} ({:.2}x) | {t_dyn:.0} ({:.2}x) | {:.1e} / {:.1e} |",
        t_stat / t_ours,
        t_dyn / t_ours,
        residual(&a, &ours(), &b),
        residual(&a, stat().as_slice(), &b),
    );
    }};
}

/// A generator with a closed-form exponential: 2x2 blocks [[a, b], [-b, a]] (and a 1x1 block when
/// N is odd), exp = e^a [[cos b, sin b], [-sin b, cos b]], conjugated by a unit upper triangular T.
macro_rules! generator {
    ($n:literal) => {{
        const N: usize = $n;
        let mut d = [[0.0; N]; N];
        let mut e = [[0.0; N]; N];
        let mut k = 0;
        while k + 1 < N {
            let (a, b) = (-0.5 * (k + 1) as f64, 3.0 + k as f64);
            d[k][k] = a;
            d[k + 1][k + 1] = a;
            d[k][k + 1] = b;
            d[k + 1][k] = -b;
            let s = a.exp();
            e[k][k] = s * b.cos();
            e[k + 1][k + 1] = s * b.cos();
            e[k][k + 1] = s * b.sin();
            e[k + 1][k] = -s * b.sin();
            k += 2;
        }
        if k < N {
            d[k][k] = -2.0;
            e[k][k] = (-2.0f64).exp();
        }
        let mut next = filler(100 + N as u64);
        let t = SMatrix::<f64, N, N>::from_fn(|i, j| {
            if i == j {
                1.0
            } else if j > i {
                0.5 * next()
            } else {
                0.0
            }
        });
        let t_inv = t.try_inverse().expect("unit triangular");
        let dm = SMatrix::<f64, N, N>::from_fn(|i, j| d[i][j]);
        let em = SMatrix::<f64, N, N>::from_fn(|i, j| e[i][j]);
        let a = t * dm * t_inv;
        let exact = t * em * t_inv;
        let a: Matrix<N> = std::array::from_fn(|i| std::array::from_fn(|j| a[(i, j)]));
        let exact: Matrix<N> = std::array::from_fn(|i| std::array::from_fn(|j| exact[(i, j)]));
        (a, exact)
    }};
}

macro_rules! expm_row {
    ($n:literal, $calls:expr) => {{
    const N: usize = $n;
    let calls: usize = $calls;
    let (a, exact) = generator!($n);
    let sm = SMatrix::<f64, N, N>::from_fn(|i, j| a[i][j]);
    let ours = || expm(&black_box(a)).expect("finite");
    let theirs = || black_box(sm).exp();
    let t_ours = per_call(calls, || ours()[0][0]);
    let t_theirs = per_call(calls, || theirs()[(0, 0)]);
    let norm = exact
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let e_ours = (0..N * N)
        .map(|k| (ours()[k / N][k % N] - exact[k / N][k % N]).abs())
        .fold(0.0, f64::max)
        / norm;
    let e_theirs = (0..N * N)
        .map(|k| (theirs()[(k / N, k % N)] - exact[k / N][k % N]).abs())
        .fold(0.0, f64::max)
        / norm;
    println!(
        "| expm {N}x{N} (norm {:.0}) | {t_ours:.0} | {t_theirs:.0} ({:.2}x) | - | {e_ours:.1e} / {e_theirs:.1e} |",
        (0..N)
            .map(|j| (0..N).map(|i| a[i][j].abs()).sum::<f64>())
            .fold(0.0, f64::max),
        t_theirs / t_ours
    );
    }};
}

pub fn tables() {
    println!("\n## Own small LU and expm against nalgebra 0.33 (ns per call, median of 5)");
    println!("| operation | ours | nalgebra SMatrix (time / ours) | nalgebra DMatrix (time / ours) | error ours / nalgebra SMatrix |");
    println!("|---|---|---|---|---|");
    lu_row!(3, 200_000);
    lu_row!(9, 100_000);
    lu_row!(27, 10_000);
    expm_row!(3, 50_000);
    expm_row!(7, 20_000);
    println!(
        "LU error: max |A x - b|; expm error: max |expm(A) - closed form| / max |closed form|."
    );
}
