//! vd_in moving linearly over a step when the master gives its derivative (every solver).

use super::*;
use crate::models::transverse::table::{BODY, DRIVE_SOURCE, SOLVER, TABLE};
use crate::variables::declare::INPUT_SCHEME;

fn values(solver: &str, body: &str) -> ValueSet {
    let mut v = ValueSet::start(&TABLE);
    v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
    v.set(vr::BODY, f64::from(BODY.value_of(body).unwrap()));
    v.set(
        vr::DRIVE_SOURCE,
        f64::from(DRIVE_SOURCE.value_of("input").unwrap()),
    );
    v
}

const SOLVERS: [&str; 5] = ["dopri5", "rk4", "two_phase", "radau5", "exponential"];

/// Oracle: with the body held the drive stretch is the integral of vd, v0 h + a h^2/2 for a
/// ramp, and v0 h for the held step that follows (the derivative applied to one step only).
#[test]
fn a_held_body_stretches_the_drive_by_the_integral_of_the_ramp() {
    let (v0, a, h) = (5e-4, 0.3, 1e-3);
    for solver in SOLVERS {
        let mut v = values(solver, "held");
        v.set(vr::VD_IN, v0);
        let mut sim = Transverse::new(&v, 0.0).unwrap();
        sim.set_input_derivative(vr::VD_IN, a).unwrap();
        sim.do_step(h, &v).unwrap();
        let want = v0 * h + 0.5 * a * h * h;
        let fd = sim.drive_force();
        assert!(
            (fd - sim.p.kd * want).abs() < 1e-9 * sim.p.kd * want,
            "{solver}: Fd = {fd}, want {}",
            sim.p.kd * want
        );
        sim.do_step(h, &v).unwrap();
        let want = want + v0 * h;
        assert!(
            (sim.drive_force() - sim.p.kd * want).abs() < 1e-9 * sim.p.kd * want,
            "{solver}: the second step was not held"
        );
    }
}

/// Oracle: Fd's and x's difference quotients over a short step of a free, sliding body with
/// drive damping, vd_in moving at the rate the derivative says.
#[test]
fn fd_and_x_derivatives_match_their_difference_quotients() {
    let mut v = values("dopri5", "free");
    v.set(vr::HD, 50.0);
    v.set(vr::VA, 0.0);
    v.set(vr::VD_IN, 5e-4);
    let mut sim = Transverse::new(&v, 0.0).unwrap();
    for _ in 0..20 {
        sim.do_step(1e-4, &v).unwrap();
    }
    let a = 0.2;
    sim.set_input_derivative(vr::VD_IN, a).unwrap();
    let d_fd = sim.output_derivative(vr::FD, &v).unwrap();
    let d_x = sim.output_derivative(vr::X, &v).unwrap();
    let mut before = v.clone();
    sim.write_outputs(&mut before);
    let h = 1e-8;
    sim.do_step(h, &v).unwrap();
    let mut after = v.clone();
    after.set(vr::VD_IN, 5e-4 + a * h);
    sim.write_outputs(&mut after);
    let q_fd = (after.real(vr::FD) - before.real(vr::FD)) / h;
    let q_x = (after.real(vr::X) - before.real(vr::X)) / h;
    assert!((q_fd - d_fd).abs() < 1e-4 * d_fd.abs(), "{q_fd} vs {d_fd}");
    assert!((q_x - d_x).abs() < 1e-4 * d_x.abs(), "{q_x} vs {d_x}");
    assert!(sim.output_derivative(vr::KT, &v).is_err());
    assert!(sim.set_input_derivative(vr::FD, 1.0).is_err());
}

/// Oracle: every output's difference quotient over a 10 ns step against the mean of its
/// derivative at the step's two ends (the trapezoid rule: their gap is of order h^2), in the
/// vibrating slide of the paper's case: in the first period, where FFx_mean is the running
/// mean, and in the tenth, where it is held.
#[test]
fn every_output_derivative_matches_its_difference_quotient() {
    let mut v = values("dopri5", "free");
    v.set(vr::TOLERANCE, 1e-12);
    let mut sim = Transverse::new(&v, 0.0).unwrap();
    let outputs = TABLE
        .variables
        .iter()
        .filter(|var| var.causality == crate::variables::variable::Causality::Output);
    let outputs: Vec<_> = outputs.collect();
    let period = 1.0 / sim.p.f;
    for t in [0.37 * period, 9.37 * period] {
        sim.do_step(t - sim.time(), &v).unwrap();
        let h = 1e-8;
        let mut before = v.clone();
        sim.write_outputs(&mut before);
        let d0: Vec<f64> = outputs
            .iter()
            .map(|var| sim.output_derivative(var.value_reference, &v).unwrap())
            .collect();
        sim.do_step(h, &v).unwrap();
        let mut after = v.clone();
        sim.write_outputs(&mut after);
        for (var, d0) in outputs.iter().zip(d0) {
            let r = var.value_reference;
            let d1 = sim.output_derivative(r, &v).unwrap();
            let mean = 0.5 * (d0 + d1);
            let quotient = (after.real(r) - before.real(r)) / h;
            // The quotient's round-off: a few ulps of the output over h.
            let round_off = 8.0 * f64::EPSILON * after.real(r).abs() / h;
            assert!(
                (quotient - mean).abs() <= 1e-6 * mean.abs() + round_off,
                "{} at t = {t}: quotient {quotient}, derivative {mean}",
                var.name
            );
        }
    }
}

/// Oracle: with the body held the drive stretch is the integral of vd. Under vd_in = a t set at
/// every communication point with no derivative, `held` loses a h^2 / 2 a step, `extrapolated`
/// only the first step's (it knows one value there), and `corrected` makes that up over the
/// second step: the stretch is a t^2 / 2 from then on.
#[test]
fn input_schemes_stretch_the_drive_by_what_they_make_of_the_values() {
    let (a, h, steps) = (0.3, 1e-3, 6);
    for solver in SOLVERS {
        for (scheme, lost) in [
            ("held", steps as f64),
            ("extrapolated", 1.0),
            ("corrected", 0.0),
        ] {
            let mut v = values(solver, "held");
            v.set(
                vr::INPUT_SCHEME,
                f64::from(INPUT_SCHEME.value_of(scheme).unwrap()),
            );
            let mut sim = Transverse::new(&v, 0.0).unwrap();
            for k in 0..steps {
                v.set(vr::VD_IN, a * k as f64 * h);
                sim.do_step(h, &v).unwrap();
            }
            let t = steps as f64 * h;
            let want = sim.p.kd * (0.5 * a * t * t - lost * 0.5 * a * h * h);
            let fd = sim.drive_force();
            assert!(
                (fd - want).abs() < 1e-9 * want,
                "{solver}, {scheme}: Fd = {fd}, want {want}"
            );
        }
    }
}
