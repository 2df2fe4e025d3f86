//! The velocity and the normal force as inputs, moving linearly over a step when the master
//! gives their derivatives.

use super::*;
use crate::error::Kind;
use crate::models::longitudinal::table::{
    LAW, NORMAL_FORCE_SOURCE, SOLVER, TABLE, VELOCITY_SOURCE,
};

const F: f64 = 60_000.0;
const VA: f64 = 0.264;
const VC: f64 = 0.146;
const WEIGHT: f64 = 0.02 * 9.81;
const FC: f64 = 0.1 * WEIGHT;

fn values(law: &str, solver: &str) -> ValueSet {
    let mut v = ValueSet::start(&TABLE);
    v.set(vr::LAW, f64::from(LAW.value_of(law).unwrap()));
    v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
    v.set(vr::VC, VC);
    v
}

fn with_inputs(mut v: ValueSet, velocity: bool, load: bool) -> ValueSet {
    if velocity {
        v.set(
            vr::VELOCITY_SOURCE,
            f64::from(VELOCITY_SOURCE.value_of("input").unwrap()),
        );
    }
    if load {
        v.set(
            vr::NORMAL_FORCE_SOURCE,
            f64::from(NORMAL_FORCE_SOURCE.value_of("input").unwrap()),
        );
    }
    v
}

/// The paper's velocity, vc + va cos(2 pi f t), and its derivative.
fn paper_velocity(t: f64) -> (f64, f64) {
    let phase = TAU * F * t;
    (VC + VA * phase.cos(), -VA * TAU * F * phase.sin())
}

/// A master's run: `steps` communication steps of `h`, setting each input from `inputs(t)` (value
/// and derivative) at every communication point, the derivatives only when `derivatives`.
/// Returns the outputs after each step.
fn master_run(
    v: &ValueSet,
    (h, steps): (f64, usize),
    inputs: &dyn Fn(f64) -> [(u32, f64, f64); 2],
    derivatives: bool,
) -> Vec<ValueSet> {
    let mut v = v.clone();
    let mut sim = Longitudinal::new(&v, 0.0).unwrap();
    let mut trace = Vec::with_capacity(steps);
    for k in 0..steps {
        let t = k as f64 * h;
        for (reference, value, rate) in inputs(t) {
            v.set(reference, value);
            if derivatives {
                sim.set_input_derivative(reference, rate).unwrap();
            }
        }
        sim.do_step(h, &v).unwrap();
        let mut out = v.clone();
        for (reference, value, _) in inputs(t + h) {
            out.set(reference, value);
        }
        sim.write_outputs(&mut out);
        trace.push(out);
    }
    trace
}

fn paper_inputs(t: f64) -> [(u32, f64, f64); 2] {
    let (value, rate) = paper_velocity(t);
    [(vr::VR_IN, value, rate), (vr::FN_IN, WEIGHT, 0.0)]
}

/// Oracle: dopri5 at rtol 1e-12 under the same input. closed_form follows an input velocity
/// that moves linearly over each step (the distance slid is then quadratic), through its sign
/// changes, to its tolerance in every output.
#[test]
fn closed_form_follows_an_input_velocity() {
    let run = |solver: &str, tolerance: f64| {
        let mut v = with_inputs(values("dahl", solver), true, false);
        v.set(vr::TOLERANCE, tolerance);
        master_run(&v, (0.1 / F, 60), &paper_inputs, true)
    };
    let reference = run("dopri5", 1e-12);
    for tolerance in [1e-6, 1e-9] {
        let trace = run("closed_form", tolerance);
        for (out, want) in trace.iter().zip(&reference) {
            for (output, scale) in [(vr::FT, FC), (vr::FT_MEAN, FC), (vr::W_DISS, FC * VA / F)] {
                let error = (out.real(output) - want.real(output)).abs();
                assert!(
                    error < tolerance * scale,
                    "{tolerance}: output {output} off by {error:e}"
                );
            }
        }
    }
}

/// Oracle: the prescribed velocity, which the input approximates by its values at the
/// communication points. Held, the input lags by half a step, an error of first order in FT;
/// moving at the derivatives given, of second: halving the step halves FT's error, or quarters
/// it.
#[test]
fn an_input_velocity_with_derivatives_converges_with_second_order() {
    let periods = 4;
    let mut prescribed = values("dahl", "dopri5");
    prescribed.set(vr::TOLERANCE, 1e-11);
    let v = with_inputs(prescribed.clone(), true, false);
    let error = |n: usize, derivatives: bool| {
        let (h, steps) = (1.0 / (F * n as f64), n * periods);
        let mut sim = Longitudinal::new(&prescribed, 0.0).unwrap();
        let mut out = prescribed.clone();
        let reference: Vec<f64> = (0..steps)
            .map(|_| {
                sim.do_step(h, &prescribed).unwrap();
                sim.write_outputs(&mut out);
                out.real(vr::FT)
            })
            .collect();
        let trace = master_run(&v, (h, steps), &paper_inputs, derivatives);
        trace
            .iter()
            .zip(&reference)
            .skip(steps - n)
            .map(|(out, want)| (out.real(vr::FT) - want).abs())
            .fold(0.0, f64::max)
    };
    let held = error(40, false) / error(80, false);
    let moving = error(40, true) / error(80, true);
    assert!((1.6..2.5).contains(&held), "held: error ratio {held}");
    assert!(
        (3.2..5.0).contains(&moving),
        "derivatives: error ratio {moving}"
    );
    assert!(error(80, true) < error(80, false) / 10.0);
}

/// Oracle: the weight. A normal-force input equal to m g is the same run, to round-off, for
/// every law and solver; twice m g doubles Coulomb's FT_mean and leaves its S.
#[test]
fn a_normal_force_equal_to_the_weight_is_the_weight() {
    for law in ["coulomb", "dahl", "lugre"] {
        for solver in ["exponential", "dopri5", "radau5"] {
            let weight = values(law, solver);
            let input = with_inputs(weight.clone(), false, true);
            let read = |v: &ValueSet| {
                let mut sim = Longitudinal::new(v, 0.0).unwrap();
                for _ in 0..6 {
                    sim.do_step(0.5 / F, v).unwrap();
                }
                let mut out = v.clone();
                sim.write_outputs(&mut out);
                (out.real(vr::FT_MEAN), out.real(vr::S), out.real(vr::W_DISS))
            };
            let (a, b) = (read(&weight), read(&input));
            assert!(
                (a.0 - b.0).abs() < 1e-14 * FC,
                "{law} {solver}: {a:?} {b:?}"
            );
            assert!((a.1 - b.1).abs() < 1e-11, "{law} {solver}: {a:?} {b:?}");
            assert!((a.2 - b.2).abs() <= 1e-12 * a.2.abs(), "{law} {solver}");
        }
    }
    let mut doubled = with_inputs(values("coulomb", "dopri5"), false, true);
    doubled.set(vr::FN_IN, 2.0 * WEIGHT);
    let mut sim = Longitudinal::new(&doubled, 0.0).unwrap();
    sim.do_step(1.0 / F, &doubled).unwrap();
    let mut out = doubled.clone();
    sim.write_outputs(&mut out);
    let exact = coulomb::mean_under_vibration(FC, VC, VA);
    assert!((out.real(vr::FT_MEAN) - 2.0 * exact).abs() < 1e-12 * FC);
    assert!((out.real(vr::S) - (1.0 - exact / FC) * 100.0).abs() < 1e-9);
}

/// Dahl (alpha 1) under a normal force FN(t) = m g (1 + 0.5 sin(2 pi f t / 7)) given at 50
/// communication points a period with its derivative, so FN is piecewise linear.
/// Oracle: the ODE dz/dt = vr (1 - kt z sgn(vr) / (mu FN(t))) written out here and integrated
/// by classical Runge-Kutta at 40 000 steps a period (its error is far below the tolerances
/// checked), with the same piecewise-linear FN.
#[test]
fn dahl_under_a_moving_normal_force_meets_an_independent_integration() {
    let n = 50;
    let h = 1.0 / (F * n as f64);
    let load = |t: f64| {
        let w = TAU * F / 7.0;
        (
            WEIGHT * (1.0 + 0.5 * (w * t).sin()),
            WEIGHT * 0.5 * w * (w * t).cos(),
        )
    };
    let steps = 4 * n;
    let kt = 5.6e4;
    let reference: Vec<f64> = {
        let fine = 800;
        let dt = h / fine as f64;
        let mut z = 0.0_f64;
        let mut out = Vec::new();
        for k in 0..steps {
            let t0 = k as f64 * h;
            let (fn0, rate) = load(t0);
            let rhs = |t: f64, z: f64| {
                let v = paper_velocity(t).0;
                let fc = 0.1 * (fn0 + rate * (t - t0));
                v * (1.0 - kt * z * v.signum() / fc)
            };
            for j in 0..fine {
                let t = t0 + j as f64 * dt;
                let k1 = rhs(t, z);
                let k2 = rhs(t + dt / 2.0, z + dt / 2.0 * k1);
                let k3 = rhs(t + dt / 2.0, z + dt / 2.0 * k2);
                let k4 = rhs(t + dt, z + dt * k3);
                z += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            }
            out.push(kt * z);
        }
        out
    };
    let inputs = |t: f64| {
        let (value, rate) = load(t);
        [(vr::FN_IN, value, rate), (vr::VR_IN, 0.0, 0.0)]
    };
    for (solver, tolerance) in [("dopri5", 1e-6), ("radau5", 1e-6), ("exponential", 1e-5)] {
        let mut v = with_inputs(values("dahl", solver), false, true);
        v.set(vr::TOLERANCE, 1e-10);
        v.set(vr::STEPS_PER_PERIOD, 4000.0);
        let trace = master_run(&v, (h, steps), &inputs, true);
        let error = trace
            .iter()
            .zip(&reference)
            .map(|(out, want)| (out.real(vr::FT) - want).abs())
            .fold(0.0, f64::max);
        assert!(error < tolerance * FC, "{solver}: FT off by {error:e} N");
    }
}

/// Oracle: centred differences of the outputs over two short steps with the same rates. Every
/// output's derivative agrees with them to the difference's own error, for every law, with both
/// inputs moving, within the first period (where FT_mean and S move too).
#[test]
fn output_derivatives_are_differences_of_the_outputs() {
    let outputs = [vr::FT, vr::Z, vr::VR, vr::FT_MEAN, vr::S, vr::W_DISS];
    for law in ["coulomb", "dahl", "lugre"] {
        let mut v = with_inputs(values(law, "dopri5"), true, true);
        v.set(vr::TOLERANCE, 1e-12);
        v.set(vr::SIGMA1, 1e-3);
        let (t, dt) = (0.3 / F, 1e-4 / F);
        let (a, b) = (300.0, 40.0 * WEIGHT);
        let inputs_at = |v: &mut ValueSet, time: f64| {
            v.set(vr::VR_IN, 0.1 + a * (time - t));
            v.set(vr::FN_IN, WEIGHT + b * (time - t));
        };
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        inputs_at(&mut v, 0.0);
        sim.do_step(t - dt, &v).unwrap();
        let outputs_at = |sim: &Longitudinal, time: f64| {
            let mut out = v.clone();
            inputs_at(&mut out, time);
            sim.write_outputs(&mut out);
            out
        };
        let moving_step = |sim: &mut Longitudinal, from: f64| {
            let mut at = v.clone();
            inputs_at(&mut at, from);
            sim.set_input_derivative(vr::VR_IN, a).unwrap();
            sim.set_input_derivative(vr::FN_IN, b).unwrap();
            sim.do_step(dt, &at).unwrap();
        };
        let before = outputs_at(&sim, t - dt);
        moving_step(&mut sim, t - dt);
        sim.set_input_derivative(vr::VR_IN, a).unwrap();
        sim.set_input_derivative(vr::FN_IN, b).unwrap();
        let mut now = v.clone();
        inputs_at(&mut now, t);
        let rates: Vec<f64> = outputs
            .iter()
            .map(|&r| sim.output_derivative(r, &now).unwrap())
            .collect();
        moving_step(&mut sim, t);
        let after = outputs_at(&sim, t + dt);
        for (&r, rate) in outputs.iter().zip(&rates) {
            let difference = (after.real(r) - before.real(r)) / (2.0 * dt);
            let scale = difference.abs().max(rate.abs()).max(1e-30);
            assert!(
                (difference - rate).abs() < 1e-5 * scale,
                "{law}, output {r}: derivative {rate:e}, difference {difference:e}"
            );
        }
    }
}

/// A normal force that would reach zero within the step is refused before the step, and the
/// simulation is where it was.
#[test]
fn a_normal_force_that_reaches_zero_in_the_step_is_refused() {
    let v = with_inputs(values("dahl", "dopri5"), false, true);
    let mut sim = Longitudinal::new(&v, 0.0).unwrap();
    sim.set_input_derivative(vr::FN_IN, -WEIGHT * F).unwrap();
    let refused = sim.do_step(2.0 / F, &v).unwrap_err();
    assert_eq!(refused.kind, Kind::Value { name: "FN_in" }, "{refused}");
    assert_eq!(sim.time(), 0.0);
    let mut v = v.clone();
    v.set(vr::FN_IN, 0.0);
    assert!(sim.do_step(1e-6, &v).is_err());
}

/// Dahl below alpha 1 and a moving normal force: the adaptive solvers are refused at build
/// time with a message; the fixed-step ones run.
#[test]
fn dahl_below_alpha_one_under_a_normal_force_input_needs_a_fixed_step() {
    for solver in ["dopri5", "radau5"] {
        let mut v = with_inputs(values("dahl", solver), false, true);
        v.set(vr::ALPHA, 0.5);
        let refused = Longitudinal::new(&v, 0.0).unwrap_err();
        assert_eq!(refused.kind, Kind::Combination, "{refused}");
    }
    let mut v = with_inputs(values("dahl", "exponential"), false, true);
    v.set(vr::ALPHA, 0.5);
    assert!(Longitudinal::new(&v, 0.0).is_ok());
}

/// A saved state holds the inputs and the derivatives set for the coming step: the restored
/// simulation takes the same step.
#[test]
fn a_restored_state_keeps_the_derivatives_set_for_the_step() {
    let v = with_inputs(values("lugre", "radau5"), true, true);
    let mut v = v.clone();
    v.set(vr::VR_IN, 0.05);
    let mut a = Longitudinal::new(&v, 0.0).unwrap();
    a.do_step(0.4 / F, &v).unwrap();
    a.set_input_derivative(vr::VR_IN, -500.0).unwrap();
    a.set_input_derivative(vr::FN_IN, 10.0).unwrap();
    let saved = a.save();
    assert_eq!(saved.len(), 18 + 2 * crate::models::input_scheme::SAVED);
    a.do_step(0.4 / F, &v).unwrap();
    let mut b = Longitudinal::new(&v, 0.0).unwrap();
    b.restore(&saved).unwrap();
    b.do_step(0.4 / F, &v).unwrap();
    assert_eq!(a.save(), b.save());
    assert_ne!(a.save()[1], {
        let mut c = Longitudinal::new(&v, 0.0).unwrap();
        c.restore(&saved).unwrap();
        c.inputs[0].lapse();
        c.do_step(0.4 / F, &v).unwrap();
        c.save()[1]
    });
}

/// Oracle: the transient after 40 periods (the bristle forgets its start within a few). With
/// `initial = periodic` the first period's FT_mean is that steady value, for every law and
/// solver; a run with an input velocity has no period to find and is refused.
#[test]
fn a_periodic_start_is_steady_from_the_first_period() {
    use crate::models::longitudinal::table::INITIAL;
    for law in ["coulomb", "dahl", "lugre"] {
        for solver in ["dopri5", "radau5", "exponential", "rk4", "closed_form"] {
            if law == "lugre" && solver == "closed_form" {
                continue;
            }
            let mut v = values(law, solver);
            v.set(vr::TOLERANCE, 1e-10);
            let steady = steady_mean_force(&v, 40).unwrap();
            let transient = steady_mean_force(&v, 1).unwrap();
            v.set(
                vr::INITIAL,
                f64::from(INITIAL.value_of("periodic").unwrap()),
            );
            let mut sim = Longitudinal::new(&v, 0.0).unwrap();
            assert_eq!(sim.notice, None, "{law} {solver}");
            sim.do_step(1.0 / F, &v).unwrap();
            let error = (sim.mean_force() / steady - 1.0).abs();
            assert!(
                error < 1e-9,
                "{law} {solver}: {error:e} after one period (from rest: {:e})",
                (transient / steady - 1.0).abs()
            );
        }
    }
    let mut v = with_inputs(values("dahl", "dopri5"), true, false);
    v.set(
        vr::INITIAL,
        f64::from(
            crate::models::longitudinal::table::INITIAL
                .value_of("periodic")
                .unwrap(),
        ),
    );
    let refused = Longitudinal::new(&v, 0.0).unwrap_err();
    assert_eq!(refused.kind, Kind::Combination, "{refused}");
}

/// Oracle: Coulomb's work is mu FN times the slip. With vr_in = v0 + a t (FN the weight), or
/// vr_in = v0 and FN_in = W + b t, set at every communication point without derivatives, W_diss
/// is mu times the integral of what the scheme made of the moving input: `held` misses every
/// step's rise, `extrapolated` only the first step's (it knows one value there), and `corrected`
/// makes that up over the second step, so from then on it is the master's line's integral.
#[test]
fn input_schemes_slide_by_what_they_make_of_the_values() {
    let (v0, h, steps) = (0.1, 2e-4, 8);
    let t = steps as f64 * h;
    let mu = FC / WEIGHT;
    for (a, b) in [(40.0, 0.0), (0.0, 5.0)] {
        let dissipated = |scheme: &str| {
            let mut v = with_inputs(values("coulomb", "exponential"), true, b != 0.0);
            v.set(
                vr::INPUT_SCHEME,
                f64::from(
                    crate::variables::declare::INPUT_SCHEME
                        .value_of(scheme)
                        .unwrap(),
                ),
            );
            let mut sim = Longitudinal::new(&v, 0.0).unwrap();
            for k in 0..steps {
                let t = k as f64 * h;
                v.set(vr::VR_IN, v0 + a * t);
                v.set(vr::FN_IN, WEIGHT + b * t);
                sim.do_step(h, &v).unwrap();
            }
            sim.dissipated_energy()
        };
        let exact = mu * (v0 * WEIGHT * t + (v0 * b + a * WEIGHT) * t * t / 2.0);
        let first_step = mu * (v0 * b + a * WEIGHT) * h * h / 2.0;
        for (scheme, lost) in [
            ("held", steps as f64 * first_step),
            ("extrapolated", first_step),
            ("corrected", 0.0),
        ] {
            let got = dissipated(scheme);
            assert!(
                (got - (exact - lost)).abs() < 1e-9 * exact,
                "a = {a}, b = {b}, {scheme}: W_diss = {got}, want {}",
                exact - lost
            );
        }
    }
}
