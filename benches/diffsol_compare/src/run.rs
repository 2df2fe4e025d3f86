//! One run of one solver over a case: the states at every restart point and the right-hand-side
//! evaluations it took. Every solver starts afresh at each restart point, as an FMU's doStep does.

use crate::cases::Case;
use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason, Vector};
use friction_fmu::solve::radau::Radau5;
use friction_fmu::solve::switching::MAX_SWITCHES;
use friction_fmu::solve::{Integrator, Work, MAX_DIM};
use std::cell::{Cell, RefCell};

pub struct Run {
    /// States at each grid point.
    pub states: Vec<Vec<f64>>,
    pub rhs_evaluations: u64,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Our radau5 with no memory across restarts (initial step guessed each time).
    Radau5Cold,
    /// Our radau5 carrying its next step size across restarts, as the models do.
    Radau5Warm,
    /// Our radau5 (h carried) ending its steps on the kinks, as scene T runs it.
    Radau5Kinks,
    Bdf,
    TrBdf2,
    Esdirk34,
    /// diffsol's bdf with the kinks as root functions, restarted at each root found.
    BdfKinks,
    /// Our radau5 (h carried) and diffsol's bdf with absolute tolerances 100 times looser:
    /// bdf stops on "step size too small" at tight rtol with atol = rtol times scene T's scales.
    Radau5LooseAtol,
    BdfLooseAtol,
}

/// The absolute-tolerance factor of the *LooseAtol methods.
const LOOSE: f64 = 100.0;

impl Method {
    pub fn name(self) -> &'static str {
        match self {
            Method::Radau5Cold => "radau5 (cold restart)",
            Method::Radau5Warm => "radau5 (h carried)",
            Method::Radau5Kinks => "radau5 (h carried, kinks located)",
            Method::Bdf => "diffsol bdf",
            Method::BdfKinks => "diffsol bdf (restart at kink roots)",
            Method::Radau5LooseAtol => "radau5 (h carried, atol x100)",
            Method::BdfLooseAtol => "diffsol bdf (atol x100)",
            Method::TrBdf2 => "diffsol tr_bdf2",
            Method::Esdirk34 => "diffsol esdirk34",
        }
    }
}

pub fn run(case: &Case, method: Method, rtol: f64, atol: f64) -> Result<Run, String> {
    match method {
        Method::Radau5Cold => radau(case, rtol, atol, false, false),
        Method::Radau5Warm => radau(case, rtol, atol, true, false),
        Method::Radau5Kinks => radau(case, rtol, atol, true, true),
        Method::Radau5LooseAtol => radau(case, rtol, atol * LOOSE, true, false),
        Method::BdfLooseAtol => diffsol_run(case, Method::Bdf, rtol, atol * LOOSE),
        _ => diffsol_run(case, method, rtol, atol),
    }
}

fn radau(case: &Case, rtol: f64, atol: f64, warm: bool, kinks: bool) -> Result<Run, String> {
    let n = case.y0.len();
    let mut solver = Radau5::new(rtol, atol, f64::INFINITY);
    solver.atol_scale[..n].copy_from_slice(&case.scale);
    let mut work = Work::default();
    let mut y = [0.0; MAX_DIM];
    y[..n].copy_from_slice(&case.y0);
    let mut t = case.t0;
    let mut states = Vec::with_capacity(case.grid.len());
    for &t1 in &case.grid {
        if !warm {
            solver.h_next = 0.0;
        }
        match (&case.switching, kinks) {
            (Some(sw), true) => {
                solver.integrate_switched(sw.as_ref(), t, t1, &mut y[..n], &mut work)?
            }
            (None, true) => return Err("no kinks in this case".into()),
            _ => solver.integrate(case.ode.as_ref(), t, t1, &mut y[..n], &mut work)?,
        }
        states.push(y[..n].to_vec());
        t = t1;
    }
    Ok(Run {
        states,
        rhs_evaluations: work.rhs_evaluations,
    })
}

type M = NalgebraMat<f64>;
type LS = NalgebraLU<f64>;

/// Runs a diffsol solver from a freshly made solver state at every restart point.
fn diffsol_run(case: &Case, method: Method, rtol: f64, atol: f64) -> Result<Run, String> {
    let n = case.y0.len();
    let ode = case.ode.as_ref();
    let evaluations = Cell::new(0u64);
    let start = RefCell::new(case.y0.clone());
    // Forward-difference J v (the same increments as radau5's Jacobian), reusing f(t, x) of the
    // last call at the same point so a dense Jacobian costs n + 1 evaluations, as in radau5.
    let cache: RefCell<(f64, Vec<f64>, Vec<f64>)> =
        RefCell::new((f64::NAN, vec![f64::NAN; n], vec![0.0; n]));
    let scale = case.scale.clone();
    let rhs = |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| {
        evaluations.set(evaluations.get() + 1);
        ode.rhs(t, x, y);
    };
    let jac = |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| {
        let mut c = cache.borrow_mut();
        if !(c.0 == t && c.1 == x) {
            c.0 = t;
            c.1.copy_from_slice(x);
            ode.rhs(t, x, &mut c.2);
            evaluations.set(evaluations.get() + 1);
        }
        let mut delta = f64::INFINITY;
        let mut norm = 0.0f64;
        for i in 0..n {
            if v[i] != 0.0 {
                let d = (f64::EPSILON * x[i].abs().max(atol * scale[i]).max(1e-12)).sqrt();
                delta = delta.min(d / v[i].abs());
                norm = norm.max(v[i].abs());
            }
        }
        if norm == 0.0 {
            y.fill(0.0);
            return;
        }
        let mut xp = [0.0; 16];
        for i in 0..n {
            xp[i] = x[i] + delta * v[i];
        }
        ode.rhs(t, &xp[..n], y);
        evaluations.set(evaluations.get() + 1);
        for (yi, fi) in y.iter_mut().zip(&c.2) {
            *yi = (*yi - fi) / delta;
        }
    };
    let builder = OdeBuilder::<M>::new()
        .rtol(rtol)
        .atol(case.scale.iter().map(|s| atol * s).collect::<Vec<_>>())
        .rhs_implicit(rhs, jac)
        .init(
            |_p: &[f64], _t: f64, y: &mut [f64]| y.copy_from_slice(&start.borrow()),
            n,
        );
    let mut states = Vec::with_capacity(case.grid.len());
    // The same restart loop for both problem types (with and without root functions).
    macro_rules! restarts {
        ($problem:expr) => {{
            let mut problem = $problem.map_err(|e| e.to_string())?;
            let mut t = case.t0;
            for &t1 in &case.grid {
                // Restart at every root found on the way to t1, as at a kink.
                while t < t1 {
                    problem.t0 = t;
                    let (t_end, y) = match method {
                        Method::Bdf | Method::BdfKinks => advance(problem.bdf::<LS>(), t1)?,
                        Method::TrBdf2 => advance(problem.tr_bdf2::<LS>(), t1)?,
                        Method::Esdirk34 => advance(problem.esdirk34::<LS>(), t1)?,
                        _ => unreachable!("radau5 runs elsewhere"),
                    };
                    start.borrow_mut().copy_from_slice(&y);
                    t = t_end;
                }
                states.push(start.borrow().clone());
            }
        }};
    }
    match (&case.switching, method) {
        (Some(sw), Method::BdfKinks) => {
            let mut probe = [0.0; MAX_SWITCHES];
            let count = sw.switches(case.t0, &case.y0, &mut probe);
            let roots = |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| {
                let mut out = [0.0; MAX_SWITCHES];
                sw.switches(t, x, &mut out);
                y.copy_from_slice(&out[..count]);
            };
            restarts!(builder.root(roots, count).build())
        }
        (None, Method::BdfKinks) => return Err("no kinks in this case".into()),
        _ => restarts!(builder.build()),
    }
    Ok(Run {
        states,
        rhs_evaluations: evaluations.get(),
    })
}

/// Steps a fresh solver to t1, or to the first root of its root functions found on the way (not
/// one right at its start, where the last restart left it on a kink); returns where it stopped
/// and the state there.
fn advance<'a, Eqn, S>(
    solver: Result<S, diffsol::error::DiffsolError>,
    t1: f64,
) -> Result<(f64, Vec<f64>), String>
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
                return Ok((t1, solver.state().y.clone_as_vec()));
            }
            OdeSolverStopReason::RootFound(t_root, _) if t_root > t0 + 1e-9 * (t1 - t0) => {
                let y = solver.interpolate(t_root).map_err(|e| e.to_string())?;
                return Ok((t_root, y.clone_as_vec()));
            }
            OdeSolverStopReason::InternalTimestep | OdeSolverStopReason::RootFound(..) => {}
        }
    }
}
