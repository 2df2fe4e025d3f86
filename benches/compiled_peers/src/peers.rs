//! The compiled peers on a [`Spec`]: SUNDIALS CVODE (BDF, Adams), diffsol (bdf, esdirk34) and
//! ode_solvers (Dopri5, Dop853), each as its documentation sets it up, and a textbook Dop853
//! ([`crate::dop853`]), with the same relative tolerance and the same absolute tolerance per
//! state as ours.

use crate::cvode::{self, Cvode, Stop};
use crate::problem::{Mode, Problem, Reading, Spec, Switch};
use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector};
use ode_solvers::dop_shared::OutputType;
use ode_solvers::{Dop853, Dopri5, SVector, System};
use std::cell::{Cell, RefCell};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Peer {
    CvodeBdf,
    CvodeAdams,
    DiffsolBdf,
    DiffsolEsdirk34,
    Dopri5,
    Dop853,
    TextbookDop853,
}

pub const ALL: [Peer; 7] = [
    Peer::CvodeBdf,
    Peer::CvodeAdams,
    Peer::DiffsolBdf,
    Peer::DiffsolEsdirk34,
    Peer::Dopri5,
    Peer::Dop853,
    Peer::TextbookDop853,
];

impl Peer {
    pub fn name(self) -> &'static str {
        match self {
            Peer::CvodeBdf => "CVODE BDF",
            Peer::CvodeAdams => "CVODE Adams",
            Peer::DiffsolBdf => "diffsol bdf",
            Peer::DiffsolEsdirk34 => "diffsol esdirk34",
            Peer::Dopri5 => "ode_solvers Dopri5",
            Peer::Dop853 => "ode_solvers Dop853",
            Peer::TextbookDop853 => "textbook Dop853",
        }
    }

    /// Whether the peer locates events (root functions).
    pub fn locates_events(self) -> bool {
        !matches!(self, Peer::Dopri5 | Peer::Dop853 | Peer::TextbookDop853)
    }
}

/// What a peer's run gives: the reading and the right-hand sides it took.
pub struct Outcome {
    pub value: f64,
    pub rhs: u64,
}

/// One leg: the state at its end, the largest |y0| at the extremes found inside it (when
/// asked), the right-hand sides.
struct Leg {
    y: Vec<f64>,
    largest: f64,
    rhs: u64,
}

/// Runs `peer` on `spec` at tolerance `tol`: the transient, then the reading leg.
pub fn run<P: Problem>(peer: Peer, spec: &Spec<P>, tol: f64) -> Result<Outcome, String> {
    let n1 = spec.y0.len();
    let first = leg(
        peer,
        &spec.problem,
        (0.0, spec.t_read),
        &spec.y0,
        tol,
        &spec.scale[..n1],
        false,
    )?;
    let mut y = first.y.clone();
    y.resize(spec.scale.len(), 0.0);
    let extremes = spec.reading == Reading::Amplitude;
    let second = leg(
        peer,
        &spec.problem,
        (spec.t_read, spec.t_end),
        &y,
        tol,
        &spec.scale,
        extremes,
    )?;
    let value = match spec.reading {
        Reading::Mean { period } => second.y[n1] / period,
        Reading::Amplitude => second.largest.max(y[0].abs()).max(second.y[0].abs()),
    };
    Ok(Outcome {
        value,
        rhs: first.rhs + second.rhs,
    })
}

fn leg<P: Problem>(
    peer: Peer,
    problem: &P,
    span: (f64, f64),
    y0: &[f64],
    tol: f64,
    scale: &[f64],
    extremes: bool,
) -> Result<Leg, String> {
    match peer {
        Peer::CvodeBdf => cvode_leg(cvode::Method::Bdf, problem, span, y0, tol, scale, extremes),
        Peer::CvodeAdams => cvode_leg(
            cvode::Method::Adams,
            problem,
            span,
            y0,
            tol,
            scale,
            extremes,
        ),
        Peer::DiffsolBdf | Peer::DiffsolEsdirk34 => {
            unpanicked(|| diffsol_leg(peer, problem, span, y0, tol, scale, extremes))
        }
        Peer::Dopri5 | Peer::Dop853 | Peer::TextbookDop853 => match y0.len() {
            1 => explicit_leg::<1, P>(peer, problem, span, y0, tol, scale, extremes),
            2 => explicit_leg::<2, P>(peer, problem, span, y0, tol, scale, extremes),
            5 => explicit_leg::<5, P>(peer, problem, span, y0, tol, scale, extremes),
            6 => explicit_leg::<6, P>(peer, problem, span, y0, tol, scale, extremes),
            n => Err(format!("no explicit leg for {n} states")),
        },
    }
}

fn cvode_leg<P: Problem>(
    method: cvode::Method,
    problem: &P,
    (t0, t1): (f64, f64),
    y0: &[f64],
    tol: f64,
    scale: &[f64],
    extremes: bool,
) -> Result<Leg, String> {
    let atol: Vec<f64> = scale.iter().map(|s| tol * s).collect();
    let mut solver = Cvode::new(method, problem, t0, y0, tol, &atol, extremes)?;
    let mut largest = 0.0f64;
    while let Stop::Root = solver.advance(t1)? {
        largest = largest.max(solver.y()[0].abs());
    }
    Ok(Leg {
        y: solver.y().to_vec(),
        largest,
        rhs: solver.rhs_evaluations(),
    })
}

/// diffsol 0.18 panics in some runs with root functions (an `unwrap` on "stop time before
/// current time" inside its bdf step): such a run is a failure like any other.
fn unpanicked<T>(f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    std::panic::set_hook(hook);
    result.unwrap_or_else(|panic| {
        let message = panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("diffsol panicked: {message}"))
    })
}

type M = NalgebraMat<f64>;
type LS = NalgebraLU<f64>;

/// A forward-difference J v with the increments of radau5's Jacobian, reusing f(t, x) of the
/// last call at the same point, so a dense Jacobian costs n + 1 right-hand sides, as in radau5
/// (benches/diffsol_compare gives diffsol the same).
struct Differences<'a, P: Problem> {
    problem: &'a P,
    cache: RefCell<(f64, Vec<f64>, Vec<f64>)>,
    atol: Vec<f64>,
    evaluations: &'a Cell<u64>,
}

impl<P: Problem> Differences<'_, P> {
    fn jac_mul(&self, x: &[f64], t: f64, v: &[f64], y: &mut [f64]) {
        let n = x.len();
        let mut c = self.cache.borrow_mut();
        if !(c.0 == t && c.1 == x) {
            c.0 = t;
            c.1.copy_from_slice(x);
            self.problem.rhs(t, x, &mut c.2);
            self.evaluations.set(self.evaluations.get() + 1);
        }
        let mut delta = f64::INFINITY;
        let mut norm = 0.0f64;
        for i in 0..n {
            if v[i] != 0.0 {
                let d = (f64::EPSILON * x[i].abs().max(self.atol[i]).max(1e-12)).sqrt();
                delta = delta.min(d / v[i].abs());
                norm = norm.max(v[i].abs());
            }
        }
        if norm == 0.0 {
            y.fill(0.0);
            return;
        }
        let mut xp = [0.0; 8];
        for i in 0..n {
            xp[i] = x[i] + delta * v[i];
        }
        self.problem.rhs(t, &xp[..n], y);
        self.evaluations.set(self.evaluations.get() + 1);
        for (yi, fi) in y.iter_mut().zip(&c.2) {
            *yi = (*yi - fi) / delta;
        }
    }
}

fn diffsol_leg<P: Problem>(
    peer: Peer,
    problem: &P,
    (t0, t1): (f64, f64),
    y0: &[f64],
    tol: f64,
    scale: &[f64],
    extremes: bool,
) -> Result<Leg, String> {
    let n = y0.len();
    let evaluations = Cell::new(0u64);
    let atol: Vec<f64> = scale.iter().map(|s| tol * s).collect();
    let jacobian = Differences {
        problem,
        cache: RefCell::new((f64::NAN, vec![f64::NAN; n], vec![0.0; n])),
        atol: atol.clone(),
        evaluations: &evaluations,
    };
    let rhs = |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| {
        evaluations.set(evaluations.get() + 1);
        problem.rhs(t, x, y);
    };
    let jac =
        |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| jacobian.jac_mul(x, t, v, y);
    let builder = OdeBuilder::<M>::new()
        .t0(t0)
        .rtol(tol)
        .atol(atol.clone())
        .rhs_implicit(rhs, jac)
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(y0),
            n,
        );
    let (y, largest) = if extremes {
        let count = problem.root_count();
        let roots = |x: &[f64], _p: &[f64], t: f64, g: &mut [f64]| problem.roots(t, x, g);
        let ode = builder
            .root(roots, count)
            .build()
            .map_err(|e| e.to_string())?;
        match peer {
            Peer::DiffsolBdf => diffsol_steps(ode.bdf::<LS>(), t1)?,
            _ => diffsol_steps(ode.esdirk34::<LS>(), t1)?,
        }
    } else {
        let ode = builder.build().map_err(|e| e.to_string())?;
        match peer {
            Peer::DiffsolBdf => diffsol_steps(ode.bdf::<LS>(), t1)?,
            _ => diffsol_steps(ode.esdirk34::<LS>(), t1)?,
        }
    };
    Ok(Leg {
        y,
        largest,
        rhs: evaluations.get(),
    })
}

/// Steps a diffsol solver to `t1`; returns the state there and the largest |y0| at the roots
/// met on the way.
fn diffsol_steps<'a, Eqn, S>(
    solver: Result<S, diffsol::error::DiffsolError>,
    t1: f64,
) -> Result<(Vec<f64>, f64), String>
where
    Eqn: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    let mut solver = solver.map_err(|e| e.to_string())?;
    let t0 = solver.state().t;
    solver.set_stop_time(t1).map_err(|e| e.to_string())?;
    let mut largest = 0.0f64;
    loop {
        match solver.step().map_err(|e| e.to_string())? {
            OdeSolverStopReason::TstopReached => {
                return Ok((solver.state().y.clone_as_vec(), largest));
            }
            // A root at the start is the event the leg starts on.
            OdeSolverStopReason::RootFound(t_root, _) if t_root > t0 + 1e-12 * (t1 - t0) => {
                let y = solver
                    .interpolate(t_root)
                    .map_err(|e| e.to_string())?
                    .clone_as_vec();
                largest = largest.max(y[0].abs());
                if let Some(end) = stop_again(&mut solver, t1)? {
                    return Ok((end, largest));
                }
            }
            OdeSolverStopReason::RootFound(..) => {
                if let Some(end) = stop_again(&mut solver, t1)? {
                    return Ok((end, largest));
                }
            }
            OdeSolverStopReason::InternalTimestep => {}
        }
    }
}

/// The problem in units of the tolerance scales, for ode_solvers' one absolute tolerance:
/// atol = tol there is atol = tol x scale here, as the other peers are given.
struct Scaled<'a, P: Problem, const N: usize> {
    problem: &'a P,
    scale: [f64; N],
}

impl<P: Problem, const N: usize> System<f64, SVector<f64, N>> for Scaled<'_, P, N> {
    #[inline]
    fn system(&self, t: f64, y: &SVector<f64, N>, dy: &mut SVector<f64, N>) {
        let mut x = [0.0; N];
        for i in 0..N {
            x[i] = y[i] * self.scale[i];
        }
        let mut d = [0.0; N];
        self.problem.rhs(t, &x, &mut d);
        for i in 0..N {
            dy[i] = d[i] / self.scale[i];
        }
    }
}

fn explicit_leg<const N: usize, P: Problem>(
    peer: Peer,
    problem: &P,
    (t0, t1): (f64, f64),
    y0: &[f64],
    tol: f64,
    scale: &[f64],
    extremes: bool,
) -> Result<Leg, String> {
    let mut s = [0.0; N];
    s.copy_from_slice(scale);
    let system = Scaled { problem, scale: s };
    let y = SVector::<f64, N>::from_fn(|i, _| y0[i] / s[i]);
    // Every step's end (Sparse): the leg's end is the last one, and where u' changes sign the
    // extremes are found between two. (Dense output at a grid of dx, the other mode, writes
    // the leg's end extrapolated from the step before the last when the grid's last point is
    // the end.)
    let output = OutputType::Sparse;
    let span = t1 - t0;
    // The crate's defaults (Hairer's), with no limit on the number of steps and without the
    // stiffness test, which ends the run with an error (Dop853 ends scene L's that way at
    // rtol 3e-4 and below); ours warns once and goes on.
    let (xs, ys, evaluations) = if peer == Peer::TextbookDop853 {
        let mut start = [0.0; N];
        start.copy_from_slice(y0);
        let (xs, ys, evaluations) = crate::dop853::integrate(problem, (t0, t1), start, tol, scale)?;
        let scaled = ys
            .iter()
            .map(|y| SVector::<f64, N>::from_fn(|i, _| y[i] / s[i]))
            .collect::<Vec<_>>();
        (xs, scaled, evaluations)
    } else if peer == Peer::Dop853 {
        let mut solver = Dop853::from_param(
            system,
            t0,
            t1,
            span,
            y,
            tol,
            tol,
            0.9,
            0.0,
            0.333,
            6.0,
            span,
            0.0,
            u32::MAX,
            u32::MAX,
            output,
        );
        let stats = solver.integrate().map_err(|e| e.to_string())?;
        (
            solver.x_out().clone(),
            solver.y_out().clone(),
            u64::from(stats.num_eval),
        )
    } else {
        let mut solver = Dopri5::from_param(
            system,
            t0,
            t1,
            span,
            y,
            tol,
            tol,
            0.9,
            0.04,
            0.2,
            10.0,
            span,
            0.0,
            u32::MAX,
            u32::MAX,
            output,
        );
        let stats = solver.integrate().map_err(|e| e.to_string())?;
        (
            solver.x_out().clone(),
            solver.y_out().clone(),
            u64::from(stats.num_eval),
        )
    };
    let last = xs.len().checked_sub(1).ok_or("no output")?;
    if (xs[last] - t1).abs() > 1e-9 * span {
        return Err(format!("the output ends at {} instead of {t1}", xs[last]));
    }
    let unscaled = |k: usize| -> [f64; N] {
        let mut x = [0.0; N];
        for i in 0..N {
            x[i] = ys[k][i] * s[i];
        }
        x
    };
    let mut largest = 0.0f64;
    let mut rhs = evaluations;
    if extremes {
        // Where u' changes sign between two step ends: the extreme of the quintic through u,
        // u', u'' at both (u'' from the right-hand side there).
        for k in 0..last {
            let (a, b) = (unscaled(k), unscaled(k + 1));
            if a[1] * b[1] < 0.0 || b[1] == 0.0 {
                let (mut da, mut db) = ([0.0; N], [0.0; N]);
                problem.rhs(xs[k], &a, &mut da);
                problem.rhs(xs[k + 1], &b, &mut db);
                rhs += 2;
                let h = xs[k + 1] - xs[k];
                let u = quintic_extreme(
                    (a[0], h * a[1], h * h * da[1]),
                    (b[0], h * b[1], h * h * db[1]),
                );
                largest = largest.max(u.abs());
            }
        }
    }
    Ok(Leg {
        y: unscaled(last).to_vec(),
        largest,
        rhs,
    })
}

/// The value at the stationary point of the quintic p(s), s in [0, 1], with p, p', p'' given
/// at both ends (derivatives in s), where p' changes sign.
fn quintic_extreme((u0, d0, e0): (f64, f64, f64), (u1, d1, e1): (f64, f64, f64)) -> f64 {
    let c0 = u0;
    let c1 = d0;
    let c2 = 0.5 * e0;
    let a = u1 - c0 - c1 - c2;
    let b = d1 - c1 - 2.0 * c2;
    let c = e1 - 2.0 * c2;
    let c3 = 10.0 * a - 4.0 * b + 0.5 * c;
    let c4 = -15.0 * a + 7.0 * b - c;
    let c5 = 6.0 * a - 3.0 * b + 0.5 * c;
    let p = |s: f64| c0 + s * (c1 + s * (c2 + s * (c3 + s * (c4 + s * c5))));
    let dp = |s: f64| c1 + s * (2.0 * c2 + s * (3.0 * c3 + s * (4.0 * c4 + s * 5.0 * c5)));
    let (mut lo, mut hi) = (0.0, 1.0);
    let low_sign = dp(lo) > 0.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if (dp(mid) > 0.0) == low_sign {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    p(0.5 * (lo + hi))
}

/// Scene O's exact law run by an event-locating peer: from rest, every event located and the
/// integration restarted there in the new mode; the largest |u| over [t_read, t_end].
pub fn run_switch(
    peer: Peer,
    switch: &Switch,
    (t_read, t_end): (f64, f64),
    max_step: f64,
    tol: f64,
) -> Result<Outcome, String> {
    let scale = [1.0, 1.0];
    let mut t = 0.0;
    let mut y = vec![0.0, 0.0];
    switch.mode.set(switch.settle(0.0, 0.0));
    let mut largest = 0.0f64;
    let mut rhs = 0;
    // After an event at (t, u): the new mode, u' = 0.
    let event = |t: f64, u: f64, fired: usize| -> Mode {
        match fired {
            // Sliding stopped: stick, or turn back.
            0 => switch.settle(t, u),
            // Broke away upwards or downwards.
            1 => Mode(1.0),
            _ => Mode(-1.0),
        }
    };
    match peer {
        Peer::CvodeBdf | Peer::CvodeAdams => {
            let method = if peer == Peer::CvodeBdf {
                cvode::Method::Bdf
            } else {
                cvode::Method::Adams
            };
            let atol = [tol, tol];
            let mut solver = Cvode::new(method, switch, t, &y, tol, &atol, true)?;
            // While stuck the right-hand side is 0 and nothing holds CVODE's step: it grows
            // until a step spans the forcing's rise and fall through the breakaway force, and
            // the event is missed (the first breakaway, at t = 0.41 s, was). Steps of at most
            // an eighth of the forcing period, the coarsest event grid of ours.
            solver.set_max_step(max_step)?;
            let mut found = [0; 3];
            for target in [t_read, t_end] {
                loop {
                    let stop = solver.advance(target)?;
                    t = solver.t;
                    y.copy_from_slice(solver.y());
                    if t >= t_read {
                        largest = largest.max(y[0].abs());
                    }
                    if let Stop::Reached = stop {
                        break;
                    }
                    solver.root_info(&mut found);
                    let fired = found.iter().position(|&r| r != 0).unwrap_or(0);
                    switch.mode.set(event(t, y[0], fired));
                    y[1] = 0.0;
                    rhs += solver.rhs_evaluations();
                    solver.reinit(t, &y)?;
                }
            }
            rhs += solver.rhs_evaluations();
        }
        Peer::DiffsolBdf | Peer::DiffsolEsdirk34 => {
            for target in [t_read, t_end] {
                while t < target {
                    let fired = Cell::new(None);
                    let (t_stop, y_stop, evaluations) = unpanicked(|| {
                        diffsol_switch_leg(peer, switch, (t, target), &y, tol, &scale, &fired)
                    })?;
                    rhs += evaluations;
                    t = t_stop;
                    y = y_stop;
                    if t >= t_read {
                        largest = largest.max(y[0].abs());
                    }
                    if let Some(k) = fired.get() {
                        switch.mode.set(event(t, y[0], k));
                        y[1] = 0.0;
                    }
                }
            }
        }
        Peer::Dopri5 | Peer::Dop853 | Peer::TextbookDop853 => {
            return Err("no event location in ode_solvers or the textbook Dop853".into());
        }
    }
    Ok(Outcome {
        value: largest,
        rhs,
    })
}

/// One leg of the exact law with diffsol, from (t0, y0) to the first event (which root fired
/// goes to `fired`) or to t1.
fn diffsol_switch_leg(
    peer: Peer,
    switch: &Switch,
    (t0, t1): (f64, f64),
    y0: &[f64],
    tol: f64,
    scale: &[f64],
    fired: &Cell<Option<usize>>,
) -> Result<(f64, Vec<f64>, u64), String> {
    let n = 2;
    let evaluations = Cell::new(0u64);
    let atol: Vec<f64> = scale.iter().map(|s| tol * s).collect();
    let jacobian = Differences {
        problem: switch,
        cache: RefCell::new((f64::NAN, vec![f64::NAN; n], vec![0.0; n])),
        atol: atol.clone(),
        evaluations: &evaluations,
    };
    let rhs = |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| {
        evaluations.set(evaluations.get() + 1);
        switch.rhs(t, x, y);
    };
    let jac =
        |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| jacobian.jac_mul(x, t, v, y);
    let roots = |x: &[f64], _p: &[f64], t: f64, g: &mut [f64]| switch.roots(t, x, g);
    let ode = OdeBuilder::<M>::new()
        .t0(t0)
        .rtol(tol)
        .atol(atol.clone())
        .rhs_implicit(rhs, jac)
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(y0),
            n,
        )
        .root(roots, 3)
        .build()
        .map_err(|e| e.to_string())?;
    let (t, y, root) = match peer {
        Peer::DiffsolBdf => first_event(ode.bdf::<LS>(), t1),
        _ => first_event(ode.esdirk34::<LS>(), t1),
    }?;
    fired.set(root);
    Ok((t, y, evaluations.get()))
}

/// Steps a diffsol solver to `t1` or to the first root after its start, whichever comes
/// first; returns where it stopped, and which root function fired there.
fn first_event<'a, Eqn, S>(
    solver: Result<S, diffsol::error::DiffsolError>,
    t1: f64,
) -> Result<(f64, Vec<f64>, Option<usize>), String>
where
    Eqn: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    let mut solver = solver.map_err(|e| e.to_string())?;
    let t0 = solver.state().t;
    solver.set_stop_time(t1).map_err(|e| e.to_string())?;
    loop {
        match solver.step().map_err(|e| e.to_string())? {
            OdeSolverStopReason::TstopReached => {
                return Ok((t1, solver.state().y.clone_as_vec(), None));
            }
            OdeSolverStopReason::RootFound(t_root, k) if t_root > t0 + 1e-12 * (t1 - t0) => {
                let y = solver
                    .interpolate(t_root)
                    .map_err(|e| e.to_string())?
                    .clone_as_vec();
                return Ok((t_root, y, Some(k)));
            }
            OdeSolverStopReason::RootFound(..) => {
                if let Some(end) = stop_again(&mut solver, t1)? {
                    return Ok((t1, end, None));
                }
            }
            OdeSolverStopReason::InternalTimestep => {}
        }
    }
}

/// diffsol 0.18 returns from a step that finds a root before it shortens the next step to the
/// stop time, which that step then overshoots (and panics on, in bdf): the stop time is set
/// again after every root. Returns the state when the solver already stands on it.
fn stop_again<'a, Eqn, S>(solver: &mut S, t1: f64) -> Result<Option<Vec<f64>>, String>
where
    Eqn: diffsol::OdeEquations<T = f64> + 'a,
    S: OdeSolverMethod<'a, Eqn>,
{
    if solver.state().t >= t1 {
        let y = solver.interpolate(t1).map_err(|e| e.to_string())?;
        return Ok(Some(y.clone_as_vec()));
    }
    solver.set_stop_time(t1).map_err(|e| e.to_string())?;
    Ok(None)
}
