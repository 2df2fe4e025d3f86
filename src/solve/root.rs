//! Where a switching function changes sign inside a step: the kink-locating root finder both
//! adaptive solvers share.

/// The zero of `f` on [0, 1] given `f(0) = f0` and `f(1) = f1` of opposite signs, by Illinois
/// false position (superlinear, and safe: the bracket always shrinks), to `tolerance` in the step
/// fraction or within `max_iterations` evaluations. Returns the far end of the final bracket, so
/// the zero lies inside a step ended there; or `None` where `f` does not pass through zero but
/// jumps across it (`JUMP`).
pub fn first_zero(
    mut f: impl FnMut(f64) -> f64,
    f0: f64,
    f1: f64,
    tolerance: f64,
    max_iterations: usize,
) -> Option<f64> {
    let (mut a, mut fa, mut b, mut fb) = (0.0, f0, 1.0, f1);
    // f at the bracket's ends as evaluated (fa and fb are halved by the Illinois rule).
    let (mut at_a, mut at_b) = (f0, f1);
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
            return Some(m);
        }
        // Halving the value kept twice in a row is what makes false position converge fast.
        if (fm > 0.0) == (fa > 0.0) {
            a = m;
            fa = fm;
            at_a = fm;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            fb = fm;
            at_b = fm;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    let jumps = at_a.abs().min(at_b.abs()) > JUMP * f0.abs().max(f1.abs());
    (!jumps).then_some(b)
}

/// A sign change is a jump, not a zero, when both ends of the final bracket still hold this
/// fraction of the larger end value: there f changes by a finite amount over no time. Across
/// a zero, the ends hold about `tolerance` times the end values. Such a switching function
/// has no kink to end a step on: on scene T the bristle's direction, and with it every radial
/// rate, flips sign where the deflection passes exactly through zero, while the right-hand
/// side, even in that direction, does not change. Chasing the flip as a kink cost radau5 steps
/// of 1e-18 s and then the run.
const JUMP: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use super::first_zero;

    #[test]
    fn finds_the_zero_of_a_curved_function_to_the_tolerance() {
        let root = 0.3f64;
        let f = |x: f64| (x - root) * (1.0 + 5.0 * x * x);
        let x = first_zero(f, f(0.0), f(1.0), 1e-15, 100).unwrap();
        assert!((x - root).abs() < 1e-14, "{x}");
        assert!(x >= root, "the far end of the bracket: {x}");
    }

    /// A function that jumps across zero has no zero to find; one that passes through it
    /// steeply, over a millionth of the interval, has.
    #[test]
    fn a_jump_across_zero_is_told_from_a_steep_zero() {
        let jump = |x: f64| if x < 0.3 { -1.0 } else { 2.0 };
        assert_eq!(first_zero(jump, -1.0, 2.0, 1e-12, 100), None);
        let steep = |x: f64| ((x - 0.3) * 1e6).tanh();
        let x = first_zero(steep, steep(0.0), steep(1.0), 1e-12, 100).unwrap();
        assert!((x - 0.3).abs() < 1e-11, "{x}");
    }
}
