//! Dormand-Prince 8(5,3) with step-size control and dense output (Hairer, Norsett & Wanner,
//! Solving ODEs I, II.10, and Hairer's `dop853` code), with steps that end where a switching
//! function changes sign and the narrow-feature watch, as [`super::dopri::Dopri5`] has them.
//!
//! An eighth-order pair spends twelve right-hand sides a step where dopri5 spends six, and takes
//! far longer steps at tight tolerances on a smooth solution (scene T's steady vibration under
//! the total slip law: docs/performance.md). It has no integrating factor: Lawson's, as dopri5
//! takes it, cost this pair accuracy on scene T (the factor e^(sigma tau) enters what the
//! stages integrate), so a decaying component sets its step once h sigma nears the stability
//! bound (about 6); on stiff contacts dopri5 (with the factor) or radau5 is the choice. A kink
//! costs the step that crosses it, the dense output's three further stages, and the step
//! retaken to end on it: no kink is foreseen from the step before, so where kinks come every
//! few steps (the split law) dopri5 is cheaper.

use super::failures;
use super::narrow::{Verdict, Watch};
use super::starting_step::starting_step;
use super::stepping::Stepping;
use super::stiffness::StiffnessTest;
use super::switching::{crossed, Smooth, Switching, MAX_SWITCHES};
use super::{Integrator, Ode, Work, MAX_DIM};
use crate::error::Error;

/// The nodes: the twelve stages of a step, the end (where the next step's first stage is
/// taken) and the three stages only the dense output takes.
pub const C: [f64; 16] = [
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
    1.0,
    0.1,
    0.2,
    0.7777777777777778,
];
/// Row s: the coefficients of stages 0 .. s in stage s; row 12 the weights of the
/// eighth-order solution.
pub const A: [[f64; 15]; 16] = [
    [
        0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ],
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
        0.0,
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
        0.0,
        0.0,
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
        0.0,
        0.0,
        0.0,
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
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
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
        0.0,
        0.0,
        0.0,
    ],
    [
        0.056167502283047954,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        0.25350021021662483,
        -0.2462390374708025,
        -0.12419142326381637,
        0.15329179827876568,
        0.00820105229563469,
        0.007567897660545699,
        -0.008298,
        0.0,
        0.0,
    ],
    [
        0.03183464816350214,
        0.0,
        0.0,
        0.0,
        0.0,
        0.028300909672366776,
        0.053541988307438566,
        -0.05492374857139099,
        0.0,
        0.0,
        -0.00010834732869724932,
        0.0003825710908356584,
        -0.00034046500868740456,
        0.1413124436746325,
        0.0,
    ],
    [
        -0.42889630158379194,
        0.0,
        0.0,
        0.0,
        0.0,
        -4.697621415361164,
        7.683421196062599,
        4.06898981839711,
        0.3567271874552811,
        0.0,
        0.0,
        0.0,
        -0.0013990241651590145,
        2.9475147891527724,
        -9.15095847217987,
    ],
];
/// The weights of the fifth-order error estimate.
pub const E5: [f64; 12] = [
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
pub const E3: [f64; 12] = [
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
/// The dense output's higher coefficients from the sixteen stages.
const D: [[f64; 16]; 4] = [
    [
        -8.428938276109013,
        0.0,
        0.0,
        0.0,
        0.0,
        0.5667149535193777,
        -3.0689499459498917,
        2.38466765651207,
        2.117034582445028,
        -0.871391583777973,
        2.2404374302607883,
        0.6315787787694688,
        -0.08899033645133331,
        18.148505520854727,
        -9.194632392478356,
        -4.436036387594894,
    ],
    [
        10.427508642579134,
        0.0,
        0.0,
        0.0,
        0.0,
        242.28349177525817,
        165.20045171727028,
        -374.5467547226902,
        -22.113666853125306,
        7.733432668472264,
        -30.674084731089398,
        -9.332130526430229,
        15.697238121770845,
        -31.139403219565178,
        -9.35292435884448,
        35.81684148639408,
    ],
    [
        19.985053242002433,
        0.0,
        0.0,
        0.0,
        0.0,
        -387.0373087493518,
        -189.17813819516758,
        527.8081592054236,
        -11.57390253995963,
        6.8812326946963,
        -1.0006050966910838,
        0.7777137798053443,
        -2.778205752353508,
        -60.19669523126412,
        84.32040550667716,
        11.99229113618279,
    ],
    [
        -25.69393346270375,
        0.0,
        0.0,
        0.0,
        0.0,
        -154.18974869023643,
        -231.5293791760455,
        357.6391179106141,
        93.40532418362432,
        -37.45832313645163,
        104.0996495089623,
        29.8402934266605,
        -43.53345659001114,
        96.32455395918828,
        -39.17726167561544,
        -149.72683625798564,
    ],
];

/// Hairer's step control: safety factor, and the bounds of the factor a step is scaled by.
const SAFETY: f64 = 0.9;
const GROW_MAX: f64 = 6.0;
const SHRINK_MAX: f64 = 1.0 / 3.0;

/// A last step of a call this much longer than the step the controller proposes is taken whole
/// (Hairer's 1.01).
const STRETCH: f64 = 1.01;

/// dop853's stability region reaches about 6.1 along the negative real axis (Hairer's value
/// in its stiffness test).
const STABILITY_BOUND: f64 = 6.1;

#[derive(Clone, Debug, PartialEq)]
pub struct Dop853 {
    pub rtol: f64,
    pub atol: [f64; MAX_DIM],
    pub h_max: f64,
    /// The step to try next (0: choose one).
    pub h: f64,
    pub max_steps: u64,
    stiffness: StiffnessTest,
}

/// One attempted step: the twelve stages (and, once the dense output is built, the derivative
/// at the end and the three further stages), the new state, the argument of the last stage
/// (for the stiffness test) and the error norm.
struct Trial {
    k: [[f64; MAX_DIM]; 16],
    y_new: [f64; MAX_DIM],
    last_argument: [f64; MAX_DIM],
    err: f64,
    /// Whether k[12], the derivative at y_new, has been evaluated.
    has_end: bool,
}

impl Trial {
    fn new() -> Self {
        Trial {
            k: [[0.0; MAX_DIM]; 16],
            y_new: [0.0; MAX_DIM],
            last_argument: [0.0; MAX_DIM],
            err: 0.0,
            has_end: false,
        }
    }
}

/// The dense output of a trial, of order 7 inside the step: y(t + theta h) =
/// y + theta (F0 + (1 - theta) (F1 + theta (F2 + ... (1 - theta) (F5 + theta F6)))).
struct Dense {
    y0: [f64; MAX_DIM],
    f: [[f64; MAX_DIM]; 7],
}

impl Dense {
    fn at(&self, theta: f64, out: &mut [f64; MAX_DIM]) {
        let u = 1.0 - theta;
        let f = &self.f;
        for j in 0..MAX_DIM {
            let mut acc = f[5][j] + theta * f[6][j];
            acc = f[4][j] + u * acc;
            acc = f[3][j] + theta * acc;
            acc = f[2][j] + u * acc;
            acc = f[1][j] + theta * acc;
            acc = f[0][j] + u * acc;
            out[j] = self.y0[j] + theta * acc;
        }
    }
}

impl Dop853 {
    pub fn new(rtol: f64, atol: [f64; MAX_DIM], h_max: f64) -> Self {
        Dop853 {
            rtol,
            atol,
            h_max,
            h: 0.0,
            max_steps: super::MAX_STEPS_PER_DO_STEP,
            stiffness: StiffnessTest::with_bound(STABILITY_BOUND),
        }
    }

    /// Where the test found the problem stiff, once.
    pub fn stiff_since(&mut self) -> Option<f64> {
        self.stiffness.take()
    }

    /// Takes the step `h` from `(t, y)` with first stage `k1` into `tr`.
    // The loops over the states index y, the stages and the results together.
    #[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
    fn trial<S: Switching + ?Sized>(
        &self,
        ode: &S,
        t: f64,
        y: &[f64],
        k1: &[f64; MAX_DIM],
        h: f64,
        tr: &mut Trial,
        work: &mut Work,
    ) {
        let n = ode.dim().min(MAX_DIM);
        // The stages before the last carry the coupled states alone (the right-hand side reads
        // no quadrature), as dopri5's do.
        let coupled = ode.coupled();
        tr.k[0] = *k1;
        tr.has_end = false;
        let mut arg = [0.0; MAX_DIM];
        arg[..n].copy_from_slice(&y[..n]);
        // The stages written out (constant rows of A), each skipping its zero coefficients.
        macro_rules! stages {
            ($($s:literal)*) => {$(
                Self::stage::<S, $s>(ode, (t, y, h), tr, coupled, &mut arg);
            )*};
        }
        stages!(1 2 3 4 5 6 7 8 9 10 11);
        work.rhs_evaluations += 11;
        tr.last_argument = arg;
        let (mut sum5, mut sum3, mut controlled) = (0.0, 0.0, 0);
        for j in 0..n {
            let (mut b, mut e5, mut e3) = (0.0, 0.0, 0.0);
            // Zero weights skipped (the compiler may not drop 0 * k itself); the sums' order
            // is the stages'.
            for s in 0..12 {
                let k = tr.k[s][j];
                if A[12][s] != 0.0 {
                    b += A[12][s] * k;
                }
                if E5[s] != 0.0 {
                    e5 += E5[s] * k;
                }
                if E3[s] != 0.0 {
                    e3 += E3[s] * k;
                }
            }
            tr.y_new[j] = y[j] + h * b;
            // An infinite atol leaves a quadrature out of the error control and the count.
            if self.atol[j] == f64::INFINITY {
                continue;
            }
            controlled += 1;
            let scale = self.atol[j] + self.rtol * y[j].abs().max(tr.y_new[j].abs());
            sum5 += (e5 / scale).powi(2);
            sum3 += (e3 / scale).powi(2);
        }
        let mut denominator = sum5 + 0.01 * sum3;
        if denominator <= 0.0 {
            denominator = 1.0;
        }
        let err = h * sum5 / (denominator * f64::from(controlled.max(1))).sqrt();
        tr.err = if err.is_finite() { err } else { f64::INFINITY };
    }

    /// Stage `ST` of the step `h` from `(t, y)`: its argument y + h sum_r a_sr k_r over the
    /// first `len` states (the others keep what `arg` holds), and the right-hand side there into
    /// k[ST]. The stage is a constant so that its row of A is one: the sums run row by row over
    /// the nonzero coefficients alone (half of dop853's are zero), in the stages' order.
    // The loops index the row of A, the stages and the sums together.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)]
    fn stage<S: Switching + ?Sized, const ST: usize>(
        ode: &S,
        (t, y, h): (f64, &[f64], f64),
        tr: &mut Trial,
        len: usize,
        arg: &mut [f64; MAX_DIM],
    ) {
        let n = ode.dim().min(MAX_DIM);
        let mut sum = [0.0; MAX_DIM];
        for r in 0..ST {
            let a = A[ST][r];
            if a != 0.0 {
                for j in 0..len {
                    sum[j] += a * tr.k[r][j];
                }
            }
        }
        for j in 0..len {
            arg[j] = y[j] + h * sum[j];
        }
        let (_, rest) = tr.k.split_at_mut(ST);
        ode.rhs(t + C[ST] * h, &arg[..n], &mut rest[0][..n]);
    }

    /// The derivative at the trial's end into k[12] (the next step's first stage), once.
    fn end_derivative<S: Switching + ?Sized>(ode: &S, t_end: f64, tr: &mut Trial, work: &mut Work) {
        if !tr.has_end {
            let n = ode.dim().min(MAX_DIM);
            ode.rhs(t_end, &tr.y_new[..n], &mut tr.k[12][..n]);
            work.rhs_evaluations += 1;
            tr.has_end = true;
        }
    }

    /// The dense output of the trial of length `h` from `(t, y)`: the derivative at its end
    /// and three stages more.
    #[allow(clippy::needless_range_loop)]
    fn dense<S: Switching + ?Sized>(
        ode: &S,
        t: f64,
        y: &[f64],
        h: f64,
        tr: &mut Trial,
        work: &mut Work,
    ) -> Dense {
        let n = ode.dim().min(MAX_DIM);
        Self::end_derivative(ode, t + h, tr, work);
        let mut arg = [0.0; MAX_DIM];
        Self::stage::<S, 13>(ode, (t, y, h), tr, n, &mut arg);
        Self::stage::<S, 14>(ode, (t, y, h), tr, n, &mut arg);
        Self::stage::<S, 15>(ode, (t, y, h), tr, n, &mut arg);
        work.rhs_evaluations += 3;
        let mut d = Dense {
            y0: [0.0; MAX_DIM],
            f: [[0.0; MAX_DIM]; 7],
        };
        d.y0[..n].copy_from_slice(&y[..n]);
        for j in 0..n {
            let dy = tr.y_new[j] - y[j];
            d.f[0][j] = dy;
            d.f[1][j] = h * tr.k[0][j] - dy;
            d.f[2][j] = 2.0 * dy - h * (tr.k[12][j] + tr.k[0][j]);
            for (row, coefficients) in D.iter().enumerate() {
                let mut sum = 0.0;
                for (s, c) in coefficients.iter().enumerate() {
                    sum += c * tr.k[s][j];
                }
                d.f[3 + row][j] = h * sum;
            }
        }
        d
    }

    /// The switching functions at `t + theta h` on the dense output.
    fn switches_on<S: Switching + ?Sized>(
        ode: &S,
        t: f64,
        dense: &Dense,
        h: f64,
        theta: f64,
    ) -> [f64; MAX_SWITCHES] {
        let n = ode.dim().min(MAX_DIM);
        let mut state = [0.0; MAX_DIM];
        let mut sw = [0.0; MAX_SWITCHES];
        dense.at(theta, &mut state);
        ode.switches(t + theta * h, &state[..n], &mut sw);
        sw
    }

    /// Switching function `i` at `t + theta h` on the dense output.
    fn switch_on<S: Switching + ?Sized>(
        ode: &S,
        t: f64,
        dense: &Dense,
        h: f64,
        i: usize,
        theta: f64,
    ) -> f64 {
        let mut state = [0.0; MAX_DIM];
        dense.at(theta, &mut state);
        ode.switch(t + theta * h, &state[..ode.dim().min(MAX_DIM)], i)
    }

    /// The factor a step is divided by after a trial with error `err` (Hairer's rule).
    fn shrink(err: f64) -> f64 {
        err.powf(0.125) / SAFETY
    }

    fn step_fell(&self, t: f64, h_tiny: f64) -> Error {
        failures::step_fell("dop853", (self.h, t, h_tiny), self.rtol)
    }

    /// Integrates `ode` from `t0` to `t1`, ending steps on the sign changes of its switching
    /// functions.
    pub fn integrate_switched<S: Switching + ?Sized>(
        &mut self,
        ode: &S,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        let n = ode.dim();
        if n > MAX_DIM || y.len() < n {
            return Err(failures::states_do_not_fit("dop853", n, MAX_DIM));
        }
        // Written so that NaN fails too.
        let valid = t1 >= t0 && self.rtol > 0.0 && self.h_max > 0.0;
        if !valid {
            return Err(failures::bad_settings(
                "dop853",
                (t0, t1),
                self.rtol,
                self.h_max,
            ));
        }
        if t1 == t0 {
            return Ok(());
        }
        let span = t1 - t0;
        let h_tiny = 16.0 * f64::EPSILON * t0.abs().max(t1.abs()).max(span);
        let mut k1 = [0.0; MAX_DIM];
        ode.rhs(t0, &y[..n], &mut k1[..n]);
        work.rhs_evaluations += 1;
        if self.h <= 0.0 {
            self.h = starting_step(
                (&y[..n], &k1[..n]),
                (self.rtol, &self.atol),
                (span, self.h_max),
                8,
            );
        }
        let mut t = t0;
        let mut sw_old = [0.0; MAX_SWITCHES];
        let mut sw_new = [0.0; MAX_SWITCHES];
        let mut sw_kink = [0.0; MAX_SWITCHES];
        let mut count = ode.switches(t, &y[..n], &mut sw_old);
        let mut tr = Trial::new();
        let mut retry = Trial::new();
        let mut watch = Watch::default();
        let mut steps = 0u64;
        while t < t1 {
            steps += 1;
            if steps > self.max_steps {
                return Err(failures::too_many_steps(
                    "dop853",
                    self.max_steps,
                    (t0, t1),
                    t,
                ));
            }
            let mut h = self.h.min(self.h_max);
            let rest = t1 - t;
            let last = t + h >= t1 - h_tiny || (rest <= STRETCH * h && rest <= self.h_max);
            if last {
                h = rest;
            }
            self.trial(ode, t, y, &k1, h, &mut tr, work);
            // The first sign change inside the step, on the dense output, looked for before the
            // error test: a step across a kink fails that test by a wide margin, and halving
            // towards the kink blindly costs several rejections.
            let count_new = ode.switches(t + h, &tr.y_new[..n], &mut sw_new);
            let mut first = None;
            let mut theta_min = 1.0;
            let mut dense = None;
            for i in 0..count.min(count_new) {
                if !crossed(sw_old[i], sw_new[i]) {
                    continue;
                }
                let d = dense.get_or_insert_with(|| Self::dense(ode, t, y, h, &mut tr, work));
                let at = |theta: f64| Self::switch_on(ode, t, d, h, i, theta);
                let located = super::root::first_zero(at, sw_old[i], sw_new[i], 1e-9, 100);
                if let Some(theta) = located {
                    if theta * h > h_tiny && theta < theta_min {
                        theta_min = theta;
                        first = Some(i);
                    }
                }
            }
            let mut h_taken = h;
            if first.is_some() {
                // Retake the step to end on the first kink.
                let h_kink = theta_min * h;
                self.trial(ode, t, y, &k1, h_kink, &mut retry, work);
                if retry.err > 1.0 {
                    work.rejected += 1;
                    self.h = h_kink / Self::shrink(retry.err).min(1.0 / SHRINK_MAX);
                    if self.h < h_tiny {
                        return Err(self.step_fell(t, h_tiny));
                    }
                    continue;
                }
                std::mem::swap(&mut tr, &mut retry);
                h_taken = h_kink;
                dense = None;
            } else if tr.err > 1.0 {
                work.rejected += 1;
                self.h = h / Self::shrink(tr.err).min(1.0 / SHRINK_MAX);
                if self.h < h_tiny {
                    return Err(self.step_fell(t, h_tiny));
                }
                continue;
            }
            let (count_end, sw_end) = if h_taken == h {
                (count_new, &sw_new)
            } else {
                let c = ode.switches(t + h_taken, &tr.y_new[..n], &mut sw_kink);
                (c, &sw_kink)
            };
            let mut cap = None;
            if let Some(r0) = ode.narrow(&sw_old) {
                let r1 = ode.narrow(sw_end).map_or(f64::INFINITY, |e| e.r);
                if Watch::near(r0, r1) {
                    let d =
                        dense.get_or_insert_with(|| Self::dense(ode, t, y, h_taken, &mut tr, work));
                    let verdict = watch.judge(t, h_taken, h_tiny, r0, r1, |theta| {
                        let sw = Self::switches_on(ode, t, d, h_taken, theta);
                        ode.narrow(&sw).map_or(f64::INFINITY, |e| e.r)
                    });
                    match verdict {
                        Verdict::Retake(h_short) => {
                            work.rejected += 1;
                            self.h = h_short;
                            continue;
                        }
                        Verdict::Keep { cap: c } => cap = c,
                    }
                }
            }
            work.steps += 1;
            Self::end_derivative(ode, t + h_taken, &mut tr, work);
            if self.stiffness.due() {
                self.stiffness.record(
                    Self::h_lambda(&tr, h_taken, ode.coupled()),
                    0.0,
                    t + h_taken,
                );
            }
            let full = first.is_none();
            t = if last && full { t1 } else { t + h_taken };
            y[..n].copy_from_slice(&tr.y_new[..n]);
            if y[..n].iter().any(|v| !v.is_finite()) {
                return Err(failures::not_finite("dop853", t));
            }
            k1 = tr.k[12];
            let far_side = sw_new;
            sw_old = *sw_end;
            count = count_end;
            if let Some(i) = first {
                // The step ended on the kink of switch i, which the next step must not find
                // again: where the end landed a hair short of it, take it as crossed.
                if crossed(sw_old[i], far_side[i]) {
                    sw_old[i] = f64::MIN_POSITIVE.copysign(far_side[i]);
                }
            } else {
                let fac = Self::shrink(tr.err.max(1e-300)).clamp(1.0 / GROW_MAX, 1.0 / SHRINK_MAX);
                // The last step of a call may be cut short; do not let that shrink the next.
                if last {
                    self.h = self.h.max(h / fac);
                } else {
                    self.h = h / fac;
                }
            }
            if let Some(cap) = cap {
                self.h = self.h.min(cap);
            }
        }
        Ok(())
    }

    /// The step times the Jacobian's size along the difference of the last stage and the
    /// derivative at the end, which both fall on the step's end (Hairer's stiffness estimate),
    /// over the `coupled` states: the last stage's argument carries no quadrature (the stages
    /// leave them at the step's start), and a quadrature is no part of the Jacobian the
    /// stability bound is about.
    fn h_lambda(tr: &Trial, h: f64, coupled: usize) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for j in 0..coupled {
            num += (tr.k[12][j] - tr.k[11][j]).powi(2);
            den += (tr.y_new[j] - tr.last_argument[j]).powi(2);
        }
        if den > 0.0 {
            h * (num / den).sqrt()
        } else {
            0.0
        }
    }
}

impl Stepping for Dop853 {
    fn name(&self) -> &'static str {
        "dop853"
    }
    fn tolerance(&self) -> Option<f64> {
        Some(self.rtol)
    }
    fn step_hint(&self) -> f64 {
        self.h
    }
    fn set_step_hint(&mut self, h: f64) {
        self.h = h;
    }
    fn stiff_since(&mut self) -> Option<f64> {
        Dop853::stiff_since(self)
    }
    fn advance<S: Switching>(
        &mut self,
        ode: &S,
        (t0, t1): (f64, f64),
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        self.integrate_switched(ode, t0, t1, y, work)
    }
}

impl Integrator for Dop853 {
    fn integrate(
        &mut self,
        ode: &dyn Ode,
        t0: f64,
        t1: f64,
        y: &mut [f64],
        work: &mut Work,
    ) -> Result<(), Error> {
        self.integrate_switched(&Smooth(ode), t0, t1, y, work)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::dopri::Dopri5;
    use crate::solve::test_odes::{gauss_error, AbsCos, Harmonic, Scalar, GAUSS};

    fn dop(rtol: f64) -> Dop853 {
        Dop853::new(rtol, [rtol; MAX_DIM], f64::INFINITY)
    }

    /// Oracle: the closed form; the error follows the tolerance down over six decades.
    #[test]
    fn meets_the_tolerance_on_a_smooth_problem() {
        for rtol in [1e-4, 1e-7, 1e-10] {
            let err = gauss_error(&mut dop(rtol));
            assert!(err < 50.0 * rtol, "rtol {rtol}: error {err}");
        }
    }

    /// Oracle: the closed form; with a fixed step (tolerance too loose to refine it) the error
    /// falls as h^8 or faster: halving h gains more than a factor 100.
    #[test]
    fn eighth_order_at_fixed_step() {
        let err = |h: f64| {
            let mut d = dop(1e3);
            d.h = h;
            d.h_max = h;
            let mut y = [1.0, 0.0];
            d.integrate(&Harmonic, 0.0, 4.0, &mut y, &mut Work::default())
                .unwrap();
            (y[0] - 4.0f64.cos()).abs()
        };
        let ratio = err(0.4) / err(0.2);
        assert!(ratio > 100.0, "error ratio {ratio}");
    }

    /// Oracle: the closed form. At rtol 1e-10 over ten periods of the harmonic oscillator the
    /// eighth-order pair meets the tolerance with fewer right-hand sides than dopri5.
    #[test]
    fn fewer_right_hand_sides_than_dopri5_at_tight_tolerance() {
        let t1 = 20.0 * std::f64::consts::PI;
        let mut y = [1.0, 0.0];
        let mut ours = Work::default();
        dop(1e-10)
            .integrate(&Harmonic, 0.0, t1, &mut y, &mut ours)
            .unwrap();
        assert!((y[0] - 1.0).abs() < 1e-8, "error {}", y[0] - 1.0);
        let mut y = [1.0, 0.0];
        let mut theirs = Work::default();
        Dopri5::new(1e-10, [1e-10; MAX_DIM], f64::INFINITY)
            .integrate(&Harmonic, 0.0, t1, &mut y, &mut theirs)
            .unwrap();
        assert!(
            2 * ours.rhs_evaluations < theirs.rhs_evaluations,
            "{ours:?} against dopri5's {theirs:?}"
        );
    }

    /// Oracle: the closed form cos. The dense output inside one step of 0.3 is of order 7:
    /// within 1e-9 of the solution everywhere in the step.
    #[test]
    fn the_dense_output_follows_the_solution_inside_a_step() {
        let d = dop(1e-6);
        let ode = Smooth(&Harmonic);
        let (y, h) = ([1.0, 0.0], 0.3);
        let mut k1 = [0.0; MAX_DIM];
        Harmonic.rhs(0.0, &y, &mut k1[..2]);
        let mut tr = Trial::new();
        let mut work = Work::default();
        d.trial(&ode, 0.0, &y, &k1, h, &mut tr, &mut work);
        let dense = Dop853::dense(&ode, 0.0, &y, h, &mut tr, &mut work);
        for i in 0..=10 {
            let theta = f64::from(i) / 10.0;
            let mut out = [0.0; MAX_DIM];
            dense.at(theta, &mut out);
            let err = (out[0] - (theta * h).cos()).abs();
            assert!(err < 1e-9, "theta {theta}: error {err}");
        }
        assert_eq!(work.rhs_evaluations, 11 + 4);
    }

    /// Oracle: integral of |cos t| over [0, 10] = 6 + sin(10 - 3 pi). Ending the steps on the
    /// kinks keeps the error at the tolerance, with fewer right-hand sides than without.
    #[test]
    fn steps_end_on_kinks() {
        let ode = AbsCos { decay: 0.0 };
        let exact = 6.0 + (10.0 - 3.0 * std::f64::consts::PI).sin();
        for rtol in [1e-6, 1e-10] {
            let mut y = [0.0];
            let mut with = Work::default();
            dop(rtol)
                .integrate_switched(&ode, 0.0, 10.0, &mut y, &mut with)
                .unwrap();
            assert!((y[0] - exact).abs() < 10.0 * rtol, "error {}", y[0] - exact);
            let mut y = [0.0];
            let mut without = Work::default();
            dop(rtol)
                .integrate(&ode, 0.0, 10.0, &mut y, &mut without)
                .unwrap();
            assert!(with.rhs_evaluations < without.rhs_evaluations);
        }
    }

    /// A stiff relaxation at a loose tolerance: stability holds the step, and the test says so
    /// once.
    #[test]
    fn finds_stiffness_where_stability_holds_the_step() {
        let stiff = Scalar(|t, y| -1e5 * (y - t.cos()));
        let mut d = dop(1e-3);
        let mut y = [1.0];
        d.integrate(&stiff, 0.0, 1.0, &mut y, &mut Work::default())
            .unwrap();
        assert!((y[0] - 1f64.cos()).abs() < 1e-3);
        assert!(d.stiff_since().is_some());
        assert_eq!(d.stiff_since(), None, "said once");
        let mut calm = dop(1e-3);
        let mut y = [1.0];
        calm.integrate(&GAUSS, 0.0, 3.0, &mut y, &mut Work::default())
            .unwrap();
        assert_eq!(calm.stiff_since(), None);
    }
}
