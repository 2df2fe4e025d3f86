//! Dense LU with partial pivoting on fixed-size arrays, for the small systems of the implicit
//! integrators and the matrix exponential (no allocation: the caller owns the storage).

// Index loops mirror the textbook formulas of elimination and substitution.
#![allow(clippy::needless_range_loop)]

/// Factorises the leading `n x n` block of `a` in place (L below the diagonal with unit
/// diagonal, U on and above it) and records the row swaps in `pivots`. False if singular.
pub fn lu_factor<const N: usize>(a: &mut [[f64; N]; N], n: usize, pivots: &mut [usize; N]) -> bool {
    for k in 0..n {
        let mut p = k;
        for i in k + 1..n {
            if a[i][k].abs() > a[p][k].abs() {
                p = i;
            }
        }
        pivots[k] = p;
        if a[p][k] == 0.0 || !a[p][k].is_finite() {
            return false;
        }
        a.swap(k, p);
        let pivot = a[k][k];
        for i in k + 1..n {
            let factor = a[i][k] / pivot;
            a[i][k] = factor;
            if factor != 0.0 {
                for j in k + 1..n {
                    a[i][j] -= factor * a[k][j];
                }
            }
        }
    }
    true
}

/// Solves `A x = b` in place with a factorisation from [`lu_factor`].
pub fn lu_solve<const N: usize>(lu: &[[f64; N]; N], n: usize, pivots: &[usize; N], b: &mut [f64]) {
    // Whole rows (L included) were swapped during factorisation: permute b first, then
    // substitute forward.
    for k in 0..n {
        b.swap(k, pivots[k]);
    }
    // Row by row (the same operations in the same order as column by column) so each b[i] is
    // accumulated in a register and L is read along its rows.
    for i in 1..n {
        let mut acc = b[i];
        for k in 0..i {
            acc -= lu[i][k] * b[k];
        }
        b[i] = acc;
    }
    for k in (0..n).rev() {
        // Accumulated in a local: through b[k] every subtraction would wait on a store.
        let mut acc = b[k];
        for j in k + 1..n {
            acc -= lu[k][j] * b[j];
        }
        b[k] = acc / lu[k][k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: A x computed back equals b to round-off, for a matrix that needs pivoting.
    #[test]
    fn solves_a_system_that_needs_pivoting() {
        let a0 = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let mut lu = a0;
        let mut pivots = [0; 3];
        assert!(lu_factor(&mut lu, 3, &mut pivots));
        let b0 = [1.0, 2.0, 3.0];
        let mut x = b0;
        lu_solve(&lu, 3, &pivots, &mut x);
        for i in 0..3 {
            let ax: f64 = (0..3).map(|j| a0[i][j] * x[j]).sum();
            assert!((ax - b0[i]).abs() < 1e-14);
        }
        let mut singular = [[1.0, 2.0], [2.0, 4.0]];
        let mut pivots = [0; 2];
        assert!(!lu_factor(&mut singular, 2, &mut pivots));
    }
}
