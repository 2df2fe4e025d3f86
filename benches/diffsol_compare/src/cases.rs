//! The three test problems: the same equations for every solver, with the restart grid (the
//! communication points where a co-simulation step ends and the integrator starts afresh).

use friction_fmu::friction::lugre2d::SlipLaw;
use friction_fmu::friction::regularized::Regularized;
use friction_fmu::models::oscillator::{Equations, Forced};
use friction_fmu::models::transverse::table::{vr, TABLE};
use friction_fmu::models::transverse::{
    tolerance_scales, Clocked, Transverse, COUPLED, DIM, LAMBDA, Q, VX, VY, W, X, Y, ZX, ZY,
};
use friction_fmu::models::Simulation;
use friction_fmu::solve::switching::{Switching, MAX_SWITCHES};
use friction_fmu::solve::Ode;
use friction_fmu::variables::values::ValueSet;
use std::f64::consts::PI;

pub struct Case {
    pub name: String,
    pub ode: Box<dyn Ode>,
    /// The same equations with their kinks as switching functions, where located kinks apply.
    pub switching: Option<Box<dyn Switching>>,
    pub y0: Vec<f64>,
    pub t0: f64,
    /// Restart points after t0; the last is the end of the run.
    pub grid: Vec<f64>,
    /// Absolute tolerance of each state is atol * scale (both solvers get the same vector).
    pub scale: Vec<f64>,
    /// Closed-form solution, where there is one.
    pub exact: Option<fn(f64) -> Vec<f64>>,
}

fn grid(t0: f64, step: f64, count: usize) -> Vec<f64> {
    (1..=count).map(|i| t0 + i as f64 * step).collect()
}

/// y' = -1000 (y - cos t) - sin t, y(0) = 2: y = cos t + e^(-1000 t) (Prothero-Robinson type,
/// eigenvalue -1000, with a stiff transient at the start).
struct Linear;
impl Ode for Linear {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        dydt[0] = -1000.0 * (y[0] - t.cos()) - t.sin();
    }
}

pub fn linear() -> Case {
    Case {
        name: "linear stiff y'=-1000(y-cos t)-sin t, y(0)=2, 0..10 s, restart every 0.01 s (1000)"
            .into(),
        ode: Box::new(Linear),
        y0: vec![2.0],
        t0: 0.0,
        grid: grid(0.0, 0.01, 1000),
        scale: vec![1.0],
        switching: None,
        exact: Some(|t| vec![t.cos() + (-1000.0 * t).exp()]),
    }
}

/// Scene O with the trigonometric law at a small D (slope h/D = 1.6e4 at D = 1e-4), paper values
/// otherwise; the default experiment (0..120 pi, communication step pi/50, 6000 restarts).
pub fn oscillator(d: f64) -> Case {
    let equations = Equations {
        plant: Forced {
            m: 1.0,
            c: 0.1,
            k: 1.0,
            w: 1.0,
            p: 4.0,
            input: false,
        },
        held: 0.0,
        law: Regularized::Trigonometric { h: 1.6, d },
        with_work: true,
    };
    Case {
        name: format!(
            "scene O, trigonometric, D = {d:e}: (u, u', W), 0..120 pi, restart every pi/50 (6000)"
        ),
        ode: Box::new(equations),
        switching: None,
        y0: vec![0.0, 0.0, 0.0],
        t0: 0.0,
        grid: grid(0.0, PI / 50.0, 6000),
        scale: vec![1.0, 1.0, 1.0],
        exact: None,
    }
}

/// Scene T's ODE (paper T, continuous-time limit) for a prescribed drive velocity `vd`,
/// built on the simulation's public `Clocked::contact` and `Params::drive_force`; the simulation's
/// own `Equations` is private, so it is restated here and checked against the simulation in `main`.
pub struct TransverseOde {
    pub p: Clocked,
    pub vd: f64,
}

impl Ode for TransverseOde {
    fn dim(&self) -> usize {
        DIM
    }
    fn coupled(&self) -> usize {
        COUPLED
    }
    fn rhs(&self, t: f64, y: &[f64], dydt: &mut [f64]) {
        let p = &self.p;
        let c = p.contact(t, y);
        let fd = p.drive_force(y, self.vd);
        dydt[X] = y[VX];
        dydt[VX] = (fd - c.ffx()) / p.m;
        dydt[Y] = y[VY];
        dydt[VY] = c.ffy() / p.m;
        dydt[LAMBDA] = self.vd - y[VX];
        dydt[ZX] = c.zdot.x;
        dydt[ZY] = c.zdot.y;
        dydt[Q] = c.ffx();
        dydt[W] = c.ff * (c.v1 + c.v2);
    }
}

/// The kinks of the slip law (the simulation's `Switching`): the edges of the Stribeck band
/// |v1 + v2| < 4 vs, and v1 + v2 = 0 (total) or v1 = 0, v2 = 0 (split).
impl Switching for TransverseOde {
    fn switches(&self, t: f64, y: &[f64], out: &mut [f64; MAX_SWITCHES]) -> usize {
        let c = self.p.contact(t, y);
        let vr = c.v1 + c.v2;
        let band = 4.0 * self.p.law.vs;
        out[0] = vr - band;
        out[1] = vr + band;
        match self.p.slip {
            SlipLaw::Split => {
                out[2] = c.v1;
                out[3] = c.v2;
                4
            }
            SlipLaw::Total => {
                out[2] = vr;
                3
            }
        }
    }
}

/// The simulation's parameter set: defaults, kt x `kt_factor`, slip law `total`, solver radau5 at
/// `tolerance`, from rest or from steady sliding.
pub fn transverse_values(kt_factor: f64, tolerance: f64, sliding: bool) -> ValueSet {
    let mut values = ValueSet::start(&TABLE);
    if sliding {
        values.set(vr::INITIAL, 2.0);
    }
    values.set(vr::KT, values.real(vr::KT) * kt_factor);
    values.set(vr::SLIP_LAW, 2.0); // total
    values.set(vr::SOLVER, 4.0); // radau5
    values.set(vr::TOLERANCE, tolerance);
    values
}

/// Scene T at kt x `kt_factor`, restarting at every vibration period over `periods`.
pub fn transverse(kt_factor: f64, periods: usize, sliding: bool) -> Case {
    let values = transverse_values(kt_factor, 1e-10, sliding);
    let sim = Transverse::new(&values, 0.0).expect("scene T parameters");
    let p = sim.p;
    let vd = values.real(vr::VD);
    // The simulation's absolute-tolerance scales, with a finite one for the work.
    let speed = vd.abs() + p.va + p.law.vs;
    let mut scale = tolerance_scales(&p, vd).to_vec();
    scale[W] = sim.fc * speed / p.f;
    Case {
        name: format!(
            "scene T, slip law total, kt x {kt_factor}: 9 states, from {}, restart every period 1/{} s ({periods})",
            if sliding { "steady sliding" } else { "rest" },
            p.f
        ),
        ode: Box::new(TransverseOde { p, vd }),
        switching: Some(Box::new(TransverseOde { p, vd })),
        // The simulation's saved state is [t, vd, vd', y..].
        y0: sim.save()[3..3 + DIM].to_vec(),
        t0: 0.0,
        grid: grid(0.0, 1.0 / p.f, periods),
        scale,
        exact: None,
    }
}
