//! Narrow features of a right-hand side: a term such as exp(-(v/vs)^2) that is negligible except
//! in a thin band of one coordinate r = v/vs, and large inside it.
//!
//! An adaptive step sets its length from the smooth part of the motion. Where r sweeps through
//! the band within one step, or dips into it and out again, the stages can all fall outside it:
//! the step misses the feature, and so does its error estimate, since both embedded solutions are
//! built from the same stages (seen on scene T, split law at va 8 mm/s: docs/performance.md,
//! "Benchmarks", Large vibration amplitudes). So the adaptive integrators keep every step
//! to a change of at most [`MAX_CHANGE`] in r inside the band, and look for a pass by sampling r
//! along the step's continuous output whenever r is near the band at either end.

/// A narrow feature's coordinate at one point, in units of the feature's width, and the
/// half-width of the band |r| < band outside which the feature is negligible.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Narrow {
    pub r: f64,
    pub band: f64,
}

/// How far r may move inside the band in one step: one width of the feature. The stages then
/// sample it at most half a width apart (dopri5's widest gap is from 0.3 to 0.8 of the step),
/// and the error estimate sees it. On scene T at the paper's larger amplitudes one width keeps
/// FFx_mean's error near the tolerance and two widths do not (docs/performance.md,
/// "Measurements behind the code").
pub const MAX_CHANGE: f64 = 1.0;

/// A step is sampled when r at either end lies within this many band half-widths of 0, or
/// changes sign. Farther out r would have to turn around faster than the step resolves the
/// motion to reach the band; on scene T sampling every step changes no step count
/// (docs/performance.md, "Benchmarks", Large vibration amplitudes).
const WATCH: f64 = 16.0;

/// Points per step at which r is sampled where it does not run straight (the last is the
/// step's end).
const SAMPLES: usize = 8;

/// How far r at mid-step may lie from the middle of its ends for the step to count as straight
/// (judged on its ends and midpoint alone).
const STRAIGHT: f64 = 0.25 * MAX_CHANGE;

/// How far r moves inside the band |r| < `band`, and in all, along `points`.
fn moves(band: f64, mut points: impl Iterator<Item = f64>) -> (f64, f64) {
    let clip = |r: f64| r.clamp(-band, band);
    let (mut inside, mut total) = (0.0, 0.0);
    if let Some(mut a) = points.next() {
        for b in points {
            inside += (clip(b) - clip(a)).abs();
            total += (b - a).abs();
            a = b;
        }
    }
    (inside, total)
}

/// The step a retake or a cap asks for is this fraction of the one that would just do.
const SAFETY: f64 = 0.9;

/// What to do with a step that passed the error test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Verdict {
    /// Keep it; the next step is at most `cap` long (it starts in or next to the band).
    Keep { cap: Option<f64> },
    /// Take it again with this length.
    Retake(f64),
}

/// Judges the steps of one integration call.
#[derive(Clone, Copy, Debug, Default)]
pub struct Watch {
    /// The last retake: its start time and how far r moved inside the band. A retake from the
    /// same point that moves r nearly as far means r jumps there (it is discontinuous in the
    /// state: the bristle's direction where its deflection passes through zero), which no
    /// shorter step resolves.
    retaken: Option<(f64, f64)>,
}

impl Watch {
    /// Whether a step with r at its ends `r0` and `r1` comes near enough to the band to be
    /// judged: the cheap test every step makes.
    #[inline]
    pub fn near(r0: Narrow, r1: f64) -> bool {
        r0.r.abs().min(r1.abs()) < WATCH * r0.band || (r0.r > 0.0) != (r1 > 0.0)
    }

    /// Judges the step of length `h` from `t`, with r at its ends `r0` and `r1` and at a
    /// fraction theta of it `r_at(theta)`. A retake shorter than `h_min` is not asked for.
    pub fn judge(
        &mut self,
        t: f64,
        h: f64,
        h_min: f64,
        r0: Narrow,
        r1: f64,
        mut r_at: impl FnMut(f64) -> f64,
    ) -> Verdict {
        if !Self::near(r0, r1) {
            return Verdict::Keep { cap: None };
        }
        let band = r0.band;
        let (a0, b0) = (r0.r, r1);
        let mid = r_at(0.5);
        let (mut inside, mut total) = moves(band, [a0, mid, b0].into_iter());
        // Where r runs nearly straight the midpoint is enough: a dip between the samples would
        // bend it. That spares six evaluations a step where r stays near the band for long (a
        // wide band on scene T, where all eight made every step much dearer: docs/performance.md,
        // "Benchmarks", Large vibration amplitudes).
        if (mid - 0.5 * (a0 + b0)).abs() > STRAIGHT {
            let points = (0..=SAMPLES).map(|i| match i {
                0 => a0,
                _ if i == SAMPLES => b0,
                _ if 2 * i == SAMPLES => mid,
                _ => r_at(i as f64 / SAMPLES as f64),
            });
            (inside, total) = moves(band, points);
        }
        if inside > MAX_CHANGE {
            let jump =
                matches!(self.retaken, Some((t0, before)) if t0 == t && inside > 0.5 * before);
            let retake = SAFETY * h * MAX_CHANGE / inside;
            if jump || retake < h_min {
                // Nothing to resolve, or not resolvable: the step stands, and the next is left
                // to the error control (a cap from a jump would shrink every step after it).
                return Verdict::Keep { cap: None };
            }
            self.retaken = Some((t, inside));
            return Verdict::Retake(retake);
        }
        // A step that ends in or next to the band holds the next one to the rate at which this
        // one moved r: it enters the band without a retake.
        let cap = (inside > 0.0 || b0.abs() < band + MAX_CHANGE) && total > 0.0;
        Verdict::Keep {
            cap: cap.then(|| (SAFETY * h * MAX_CHANGE / total).max(h_min)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BAND: f64 = 4.0;

    fn at(r: f64) -> Narrow {
        Narrow { r, band: BAND }
    }

    #[test]
    fn far_steps_are_not_sampled() {
        let mut w = Watch::default();
        let v = w.judge(0.0, 1.0, 1e-12, at(100.0), 90.0, |_| panic!("sampled"));
        assert_eq!(v, Verdict::Keep { cap: None });
    }

    #[test]
    fn a_sweep_through_the_band_is_cut_to_one_width() {
        let mut w = Watch::default();
        // r from 3 to -5 linearly: 7 widths inside the band.
        match w.judge(0.0, 1.0, 1e-12, at(3.0), -5.0, |th| 3.0 - 8.0 * th) {
            Verdict::Retake(h) => assert!((h - 0.9 / 7.0).abs() < 1e-12, "{h}"),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn a_graze_is_found_between_the_ends() {
        let mut w = Watch::default();
        // r from 6 down to 0.5 at mid-step and back to 6: both ends outside the band.
        let r = |th: f64| 0.5 + 22.0 * (th - 0.5) * (th - 0.5);
        assert!(matches!(
            w.judge(0.0, 1.0, 1e-12, at(r(0.0)), r(1.0), r),
            Verdict::Retake(_)
        ));
    }

    #[test]
    fn a_resolved_step_caps_the_next_at_its_rate() {
        let mut w = Watch::default();
        // r from 2 to 1.5 in a step of 1e-3: the next may move r by 0.9.
        let v = w.judge(0.0, 1e-3, 1e-12, at(2.0), 1.5, |th| 2.0 - 0.5 * th);
        match v {
            Verdict::Keep { cap: Some(c) } => assert!((c - 1.8e-3).abs() < 1e-15, "{c}"),
            v => panic!("{v:?}"),
        }
    }

    #[test]
    fn a_jump_is_kept_after_one_retake() {
        let mut w = Watch::default();
        // r jumps from 0 to -3.6 right at the start, whatever the step.
        let jump = |_| -3.6;
        assert!(matches!(
            w.judge(1.0, 1e-6, 1e-15, at(0.0), -3.6, jump),
            Verdict::Retake(_)
        ));
        assert_eq!(
            w.judge(1.0, 3e-7, 1e-15, at(0.0), -3.6, jump),
            Verdict::Keep { cap: None }
        );
    }

    #[test]
    fn no_retake_below_the_shortest_step() {
        let mut w = Watch::default();
        let v = w.judge(0.0, 1e-12, 1e-12, at(3.0), -5.0, |th| 3.0 - 8.0 * th);
        assert_eq!(v, Verdict::Keep { cap: None });
    }
}
