//! Hairer's test for stiffness in an explicit integrator (Solving ODEs II, IV.2, and the
//! `dopri5` code's IASTI/NONSTI counters): where the step times the Jacobian's size along the
//! solution's last stages stays near the method's stability bound, stability holds the step,
//! not the tolerance, and an implicit or exponential method would take far fewer steps.
//!
//! With Lawson's integrating factor the stages no longer see the decay it takes, so a second
//! sign counts too: the factor's exponent sigma h past the same bound while the stages still
//! see h |lambda| of at least `COUPLED_H_LAMBDA`. There the decay, coupled into the other
//! components, holds the step, as it does on a stiff contact; a decay the factor takes whole
//! (a relaxation that only follows its forcing) leaves the stages h |lambda| near 0.
//!
//! It only informs the user: the explicit solver still finishes, accurately but slowly.

/// h |lambda| past which a step counts as held by stability, unless the integrator gives its own
/// bound ([`StiffnessTest::with_bound`]): dopri5's stability region reaches 3.3 along the
/// negative real axis (Hairer's value).
const SUSPICIOUS_H_LAMBDA: f64 = 3.25;

/// h |lambda| of the stages past which a step whose integrating factor's exponent is past the
/// stability bound counts as held by the decay too.
const COUPLED_H_LAMBDA: f64 = 0.5;

/// How many suspicious tests in a row (not interrupted by [`CLEARING_TESTS`] clear ones) make
/// the problem stiff.
const STIFF_AFTER: u32 = 15;

/// How many clear tests in a row lift a suspicion.
const CLEARING_TESTS: u32 = 6;

/// Accepted steps between two tests while nothing is suspected (Hairer's NSTIFF): the test
/// costs about one stage's arithmetic, so it runs rarely until a test is suspicious.
const TEST_EVERY: u64 = 1000;

/// The counters of the test, kept by an integrator across its calls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StiffnessTest {
    /// h |lambda| past which a step counts as held by stability.
    bound: f64,
    accepted: u64,
    suspicious: u32,
    clear: u32,
    /// Where the problem was first found stiff, until [`StiffnessTest::take`] reports it.
    found_at: Option<f64>,
    /// Whether it has been reported: once per integrator is enough.
    reported: bool,
}

impl Default for StiffnessTest {
    fn default() -> Self {
        Self::with_bound(SUSPICIOUS_H_LAMBDA)
    }
}

impl StiffnessTest {
    /// The test of an integrator whose stability region reaches `bound` along the negative real
    /// axis.
    pub fn with_bound(bound: f64) -> Self {
        StiffnessTest {
            bound,
            accepted: 0,
            suspicious: 0,
            clear: 0,
            found_at: None,
            reported: false,
        }
    }

    /// Whether the accepted step now ending should be tested.
    pub fn due(&mut self) -> bool {
        self.accepted += 1;
        !self.reported
            && self.found_at.is_none()
            && (self.suspicious > 0 || self.accepted.is_multiple_of(TEST_EVERY))
    }

    /// Records the test of a step ending at `t`: `h_lambda` is the step times the Jacobian's
    /// size along the last stages, `sigma_h` the exponent of the integrating factor over the
    /// step (0 without one).
    pub fn record(&mut self, h_lambda: f64, sigma_h: f64, t: f64) {
        let held_by_decay = sigma_h > self.bound && h_lambda >= COUPLED_H_LAMBDA;
        if h_lambda > self.bound || held_by_decay {
            self.clear = 0;
            self.suspicious += 1;
            if self.suspicious == STIFF_AFTER {
                self.found_at = Some(t);
            }
        } else {
            self.clear += 1;
            if self.clear == CLEARING_TESTS {
                self.suspicious = 0;
            }
        }
    }

    /// Where the problem became stiff, the first time it is asked after that was found.
    pub fn take(&mut self) -> Option<f64> {
        let t = self.found_at.take()?;
        self.reported = true;
        Some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(test: &mut StiffnessTest, h_lambdas: impl IntoIterator<Item = f64>) {
        for (i, hl) in h_lambdas.into_iter().enumerate() {
            test.record(hl, 0.0, i as f64);
        }
    }

    /// A factor's exponent past the bound is suspicious only while the stages still see the
    /// decay.
    #[test]
    fn a_decay_the_factor_takes_whole_is_not_stiff() {
        let mut test = StiffnessTest::default();
        for i in 0..30 {
            test.record(0.05, 10.0, f64::from(i));
        }
        assert_eq!(test.take(), None);
        for i in 0..15 {
            test.record(0.9, 5.0, f64::from(i));
        }
        assert_eq!(test.take(), Some(14.0));
    }

    #[test]
    fn fifteen_suspicious_tests_in_a_row_make_it_stiff_once() {
        let mut test = StiffnessTest::default();
        run(&mut test, std::iter::repeat_n(3.3, 14));
        assert_eq!(test.take(), None);
        test.record(3.3, 0.0, 14.0);
        assert_eq!(test.take(), Some(14.0));
        assert_eq!(test.take(), None, "reported once");
        assert!(!test.due());
    }

    #[test]
    fn six_clear_tests_lift_a_suspicion() {
        let mut test = StiffnessTest::default();
        let pattern = [[3.3; 10].as_slice(), &[1.0; 6], &[3.3; 10]].concat();
        run(&mut test, pattern);
        assert_eq!(test.take(), None);
        // Five clear ones do not.
        let mut test = StiffnessTest::default();
        let pattern = [[3.3; 10].as_slice(), &[1.0; 5], &[3.3; 5]].concat();
        run(&mut test, pattern);
        assert_eq!(test.take(), Some(19.0));
    }

    #[test]
    fn tests_rarely_until_suspicious() {
        let mut test = StiffnessTest::default();
        let due: Vec<u64> = (1..=2500).filter(|_| test.due()).collect();
        assert_eq!(due.len(), 2);
        test.record(3.3, 0.0, 0.0);
        assert!(test.due(), "every step once suspicious");
    }
}
