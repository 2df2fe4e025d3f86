//! Where a switching function changes sign inside a step: the kink-locating root finder both
//! adaptive solvers share.

/// The zero of `f` on [0, 1] given `f(0) = f0` and `f(1) = f1` of opposite signs, by Illinois
/// false position (superlinear, and safe: the bracket always shrinks), to `tolerance` in the step
/// fraction or within `max_iterations` evaluations. Returns the far end of the final bracket, so
/// the zero lies inside a step ended there.
pub fn first_zero(
    mut f: impl FnMut(f64) -> f64,
    f0: f64,
    f1: f64,
    tolerance: f64,
    max_iterations: usize,
) -> f64 {
    let (mut a, mut fa, mut b, mut fb) = (0.0, f0, 1.0, f1);
    let mut side = 0;
    for _ in 0..max_iterations {
        if b - a <= tolerance {
            break;
        }
        let mut m = (a * fb - b * fa) / (fb - fa);
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
        }
        let fm = f(m);
        if fm == 0.0 {
            return m;
        }
        // Halving the value kept twice in a row is what makes false position converge fast.
        if (fm > 0.0) == (fa > 0.0) {
            a = m;
            fa = fm;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = fm;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::first_zero;

    #[test]
    fn finds_the_zero_of_a_curved_function_to_the_tolerance() {
        let root = 0.3f64;
        let f = |x: f64| (x - root) * (1.0 + 5.0 * x * x);
        let x = first_zero(f, f(0.0), f(1.0), 1e-15, 100);
        assert!((x - root).abs() < 1e-14, "{x}");
        assert!(x >= root, "the far end of the bracket: {x}");
    }
}
