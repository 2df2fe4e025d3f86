//! The largest stable communication step of a coupling through an input, estimated from how
//! fast the exchanged values grow at the step taken.
//!
//! The estimate takes the coupling loop as one real mode, `x' = -lambda x`, closed through the
//! input: the model integrates `x' = -lambda u` over a step of `h`, `u` being what the scheme
//! makes of the values of `x` at the communication points. Its amplification a step depends on
//! `z = lambda h` alone; past the scheme's critical `z` (2 held, 1 extrapolated, 6/11
//! corrected) it exceeds 1. The growth observed gives `z`, and the loop's `lambda` with it; the
//! largest stable step is then `h z_critical / z`. Against the drive-coupled system with its body
//! held (a loop of several modes, which the engine's Jacobi exchange closes through both models)
//! it is within 10 % of the exact bound of the linear analysis near the bound
//! (`tests/reference/drive/stability.py`).

use super::{Extrapolator, InputScheme};
use nalgebra::Matrix5;

/// The one-mode loop's state: x, the two values before it, what the last step's input
/// integrated to and the integral still owed.
const DIM: usize = 5;

/// The one-mode loop's amplification a step (its spectral radius) at `z = lambda h`.
pub fn growth(scheme: InputScheme, z: f64) -> f64 {
    let step = |state: [f64; DIM]| -> [f64; DIM] {
        let [x, u1, u0, used, debt] = state;
        // The values at -2 and -1; the call records x at 0 and moves the input over [0, 1].
        let mut input = Extrapolator {
            samples: [(-3.0, 0.0), (-2.0, u0), (-1.0, u1)],
            count: 3,
            used,
            debt,
            ..Extrapolator::default()
        };
        let ramp = input.ramp(scheme, 0.0, x, 1.0);
        [
            x - z * ramp.integral(0.0, 1.0),
            x,
            u1,
            input.used,
            input.debt,
        ]
    };
    let columns: Vec<[f64; DIM]> = (0..DIM)
        .map(|j| {
            let mut e = [0.0; DIM];
            e[j] = 1.0;
            step(e)
        })
        .collect();
    let matrix = Matrix5::from_fn(|i, j| columns[j][i]);
    matrix
        .complex_eigenvalues()
        .iter()
        .map(|mu| mu.norm())
        .fold(0.0, f64::max)
}

/// The `z` past which the one-mode loop grows.
pub fn critical(scheme: InputScheme) -> f64 {
    match scheme {
        InputScheme::Held => 2.0,
        InputScheme::Extrapolated => 1.0,
        InputScheme::Corrected => 6.0 / 11.0,
    }
}

/// The largest stable step under each scheme of a loop that grows `observed`-fold a step (> 1)
/// at the step `h` under `scheme`, taking it for the one-mode loop: its `lambda` is
/// `z_under(scheme, observed) / h`, and `critical(target) / lambda` the bound under `target`.
pub fn largest_stable_steps(
    scheme: InputScheme,
    h: f64,
    observed: f64,
) -> impl Fn(InputScheme) -> f64 {
    let lambda = z_under(scheme, observed) / h;
    move |target| critical(target) / lambda
}

/// The `z` at which `scheme`'s one-mode loop grows `observed`-fold a step (bisection: the
/// growth rises with z past the critical one).
pub fn z_under(scheme: InputScheme, observed: f64) -> f64 {
    let (mut low, mut high) = (critical(scheme), 4.0 * (1.0 + observed));
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        if growth(scheme, middle) > observed {
            high = middle;
        } else {
            low = middle;
        }
    }
    low
}
