//! The mean of a signal over the last complete period, as an integral (Leus & Gutowski eq. 3.1
//! and the `*_mean` outputs of every model).
//!
//! Periods are counted from the start time with an integer index, so the boundaries never drift
//! however long the run. A solver must end a sub-step on [`PeriodMean::next_boundary`] and call
//! [`PeriodMean::add`] with each sub-step's integral.

/// How close to the boundary of a `period` a time at `t` counts as on it: a billionth of the
/// period (the round-off of a master's clock), or, far from t = 0, four ulps of t, since a
/// master's clock rounds by that much there.
pub fn slack(period: f64, t: f64) -> f64 {
    (1e-9 * period).max(4.0 * f64::EPSILON * t.abs())
}

#[derive(Clone, Debug, PartialEq)]
pub struct PeriodMean {
    start_time: f64,
    period: f64,
    completed: u64,
    integral: f64,
    last_mean: f64,
}

impl PeriodMean {
    pub fn new(start_time: f64, period: f64) -> Self {
        PeriodMean {
            start_time,
            period,
            completed: 0,
            integral: 0.0,
            last_mean: 0.0,
        }
    }

    /// Whether a period has completed (the value is then the last one's mean, not the running
    /// mean).
    pub fn has_completed(&self) -> bool {
        self.completed > 0
    }

    /// The end of the period now being integrated.
    pub fn next_boundary(&self) -> f64 {
        self.start_time + (self.completed + 1) as f64 * self.period
    }

    /// See [`slack`].
    pub fn slack(&self, t: f64) -> f64 {
        slack(self.period, t)
    }

    /// Adds the integral over a sub-step ending at `t_end`; closes the period when `t_end` is on
    /// its boundary (to within [`PeriodMean::slack`]).
    pub fn add(&mut self, integral: f64, t_end: f64) {
        self.integral += integral;
        if t_end >= self.next_boundary() - self.slack(t_end) {
            self.last_mean = self.integral / self.period;
            self.integral = 0.0;
            self.completed += 1;
        }
    }

    /// The mean over the last complete period; before the first one completes, the mean since the
    /// start (and `instantaneous` at the start itself), so the output is always defined.
    pub fn value(&self, t: f64, instantaneous: f64) -> f64 {
        if self.completed > 0 {
            self.last_mean
        } else if t > self.start_time {
            self.integral / (t - self.start_time)
        } else {
            instantaneous
        }
    }

    /// The time derivative of [`PeriodMean::value`]: 0 once a period has completed (the value
    /// is held until the next one closes); before, that of the running mean, (F - mean) / (t -
    /// start), and F'/2 at the start itself.
    pub fn rate(&self, t: f64, instantaneous: f64, instantaneous_rate: f64) -> f64 {
        if self.completed > 0 {
            0.0
        } else if t > self.start_time {
            let elapsed = t - self.start_time;
            (instantaneous - self.integral / elapsed) / elapsed
        } else {
            0.5 * instantaneous_rate
        }
    }

    pub fn save(&self) -> [f64; 3] {
        [self.completed as f64, self.integral, self.last_mean]
    }

    pub fn restore(&mut self, saved: &[f64]) {
        self.completed = saved[0] as u64;
        self.integral = saved[1];
        self.last_mean = saved[2];
    }
}

#[cfg(test)]
mod tests {
    use super::PeriodMean;

    #[test]
    fn mean_of_a_constant_plus_a_sine_over_whole_periods() {
        // integral of 2 + sin(2 pi t) over sub-steps of 0.1 is exact in closed form.
        let mut mean = PeriodMean::new(0.0, 1.0);
        let prim = |t: f64| {
            2.0 * t - (2.0 * std::f64::consts::PI * t).cos() / (2.0 * std::f64::consts::PI)
        };
        for k in 0..25 {
            let (a, b) = (k as f64 * 0.1, (k + 1) as f64 * 0.1);
            mean.add(prim(b) - prim(a), b);
        }
        assert!((mean.value(2.5, 0.0) - 2.0).abs() < 1e-12);
    }
}
