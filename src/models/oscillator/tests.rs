use super::*;
use crate::error::{Failure, Kind};
use crate::models::oscillator::table::{FORCE_SOURCE, LAW, TABLE};
use std::f64::consts::TAU;

fn values(law: &str) -> ValueSet {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::LAW, f64::from(LAW.value_of(law).unwrap()));
    values
}

fn run(values: &ValueSet, step: f64, stop: f64) -> (Oscillator, Vec<Event>) {
    let mut sim = Oscillator::new(values, 0.0).unwrap();
    let mut log = Vec::new();
    let held = values.real(vr::P_IN);
    while sim.time() < stop - 1e-9 * step {
        let h = step.min(stop - sim.time());
        sim.step_logged(h, held, Some(&mut log)).unwrap();
    }
    (sim, log)
}

/// Oracle: without friction (h = 0) eq. 1 is a linear forced damped oscillator with a textbook
/// closed form (steady harmonic response plus the decaying free response).
#[test]
fn without_friction_every_law_is_the_linear_closed_form() {
    let (m, c, k, p, w): (f64, f64, f64, f64, f64) = (1.0, 0.1, 1.0, 4.0, 0.5);
    let stop: f64 = 10.0;
    let x = p / ((k - m * w * w).powi(2) + (c * w).powi(2)).sqrt();
    let phi = (c * w).atan2(k - m * w * w);
    let alpha = c / (2.0 * m);
    let wd = (k / m - alpha * alpha).sqrt();
    let a = x * phi.sin();
    let b = (-x * w * phi.cos() + alpha * a) / wd;
    let exact = x * (w * stop - phi).sin()
        + (-alpha * stop).exp() * (a * (wd * stop).cos() + b * (wd * stop).sin());
    for (law, tolerance) in [("exact", 1e-12), ("linear", 1e-7), ("trigonometric", 1e-7)] {
        let mut v = values(law);
        v.set(vr::H, 0.0);
        v.set(vr::W, w);
        let (sim, _) = run(&v, 0.1, stop);
        let u = sim.state().u;
        assert!((u - exact).abs() < tolerance, "{law}: {u} vs {exact}");
    }
}

/// Oracle: statics. With P below h the force never overcomes friction: the exact mass never
/// moves and H balances the excitation; the regularised laws creep by at most about D.
#[test]
fn stays_stuck_below_the_breakaway_force() {
    let mut v = values("exact");
    v.set(vr::P, 1.5);
    let (sim, log) = run(&v, 0.37, 30.0);
    assert!(log.is_empty(), "{log:?}");
    assert_eq!((sim.state().u, sim.state().v), (0.0, 0.0));
    let (friction, _, a) = sim.friction(0.0);
    assert!((friction - 1.5 * 30f64.sin()).abs() < 1e-12);
    assert_eq!(a, 0.0);
    for law in ["linear", "trigonometric_stiction"] {
        let mut v = values(law);
        v.set(vr::P, 1.5);
        v.set(vr::D, 1e-6);
        let (sim, _) = run(&v, 0.37, 30.0);
        assert!(sim.amplitude() < 1e-5, "{law}: {}", sim.amplitude());
    }
}

/// Oracle: the switch conditions themselves. A stick starts with |F - k u| <= hs; a slip starts
/// with |F - k u| = hs, the force on the side of the slip.
#[test]
fn events_satisfy_the_switch_conditions() {
    for (law, p, w, h) in [("exact", 1.0, 0.5, 0.5), ("exact_stiction", 3.0, 0.5, 1.0)] {
        let mut v = values(law);
        v.set(vr::P, p);
        v.set(vr::W, w);
        v.set(vr::H, h);
        v.set(vr::DA, v.real(vr::D));
        let hs = if law == "exact" { h } else { 2.0 * h };
        let (_, log) = run(&v, 0.3, 120.0);
        for e in &log {
            let f = p * (w * e.t).sin() - e.u;
            match e.mode {
                Mode::Stuck => assert!(f.abs() <= hs + 1e-12, "{law} t {}: {f}", e.t),
                Mode::Sliding(s) => {
                    // A slip starts at the breakaway force, or where a slide passes u' = 0
                    // with the force beyond it (then no stick in between).
                    assert!(s * f >= hs - 1e-9, "{law} t {}: {f}", e.t);
                }
            }
        }
        let sticks = log.iter().filter(|e| e.mode == Mode::Stuck).count();
        let breakaways = log
            .windows(2)
            .filter(|p| p[0].mode == Mode::Stuck)
            .map(|p| p[1])
            .collect::<Vec<_>>();
        for e in &breakaways {
            let f = p * (w * e.t).sin() - e.u;
            assert!(
                (f.abs() - hs).abs() < 1e-12,
                "{law} breakaway at {}: {f}",
                e.t
            );
        }
        assert!(sticks > 10, "{law}: {sticks} sticks");
    }
}

/// Oracle: tests/reference/oscillator (scipy DOP853 at 1e-12, events, independent code).
#[test]
fn exact_matches_the_reference_solutions() {
    let cases = include_str!("../../../tests/reference/oscillator/cases.csv");
    let sticks = include_str!("../../../tests/reference/oscillator/stick_intervals.csv");
    let header: Vec<&str> = cases.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for row in cases.lines().skip(1) {
        let f: Vec<&str> = row.split(',').collect();
        let num = |name: &str| f[column(name)].parse::<f64>().unwrap();
        let mut v = values(f[column("law")]);
        let (h, hs) = (num("h"), num("hs"));
        for (vr, name) in [
            (vr::P, "P"),
            (vr::W, "w"),
            (vr::H, "h"),
            (vr::C, "c"),
            (vr::K, "k"),
            (vr::M, "m"),
        ] {
            v.set(vr, num(name));
        }
        // ha = h Da/D: Da = D (hs - h)/h gives the reference's breakaway force.
        if h > 0.0 {
            v.set(vr::DA, v.real(vr::D) * (hs - h) / h);
        }
        let (stop, amplitude) = (num("stop_time"), num("amplitude"));
        let (sim, log) = run(&v, stop / (num("periods") * 50.0), stop);
        let rel = (sim.amplitude() / amplitude - 1.0).abs();
        assert!(
            rel < 1e-9,
            "{}: amplitude {} vs {amplitude}",
            f[0],
            sim.amplitude()
        );
        assert!(
            (sim.state().u - num("u_end")).abs() < 1e-8 * amplitude,
            "{}",
            f[0]
        );
        for stick in sticks
            .lines()
            .skip(1)
            .filter(|l| l.starts_with(&format!("{},", f[0])))
        {
            let s: Vec<f64> = stick
                .split(',')
                .skip(1)
                .map(|x| x.parse().unwrap())
                .collect();
            let start = log
                .iter()
                .find(|e| e.mode == Mode::Stuck && (e.t - s[0]).abs() < 1e-3);
            let start = start.unwrap_or_else(|| panic!("{}: no stick at {}", f[0], s[0]));
            let end = log
                .iter()
                .find(|e| e.mode != Mode::Stuck && e.t > start.t)
                .unwrap();
            assert!(
                (start.t - s[0]).abs() < 1e-9,
                "{}: {} vs {}",
                f[0],
                start.t,
                s[0]
            );
            assert!(
                (end.t - s[1]).abs() < 1e-9,
                "{}: {} vs {}",
                f[0],
                end.t,
                s[1]
            );
        }
    }
}

/// Oracle: the exact law itself. Where the communication points fall must not matter: events
/// are located inside steps, so steps of 1/50 period, 1 s and 7.3 s give the same motion.
#[test]
fn exact_does_not_depend_on_the_communication_step() {
    let mut v = values("exact");
    v.set(vr::P, 1.0);
    v.set(vr::W, 0.5);
    v.set(vr::H, 0.5);
    let stop = 73.0;
    let (reference, _) = run(&v, TAU / 0.5 / 50.0, stop);
    for step in [1.0, 7.3] {
        let (sim, _) = run(&v, step, stop);
        assert!((sim.state().u - reference.state().u).abs() < 1e-11);
        assert!((sim.state().v - reference.state().v).abs() < 1e-11);
    }
}

/// Oracle: `exact`. As D -> 0 the regularised laws converge to the switch model; at D = 1e-6
/// (slope h/D = 1.6e6) the default solver stays stable and lands within 1e-6 of it.
#[test]
fn regularised_laws_converge_to_exact_when_stiff() {
    let stop = 20.0 * TAU;
    let (exact, _) = run(&values("exact"), TAU / 50.0, stop);
    for law in ["linear", "trigonometric"] {
        let mut v = values(law);
        v.set(vr::D, 1e-6);
        let (sim, _) = run(&v, TAU / 50.0, stop);
        let rel = (sim.amplitude() / exact.amplitude() - 1.0).abs();
        assert!(
            rel < 1e-6,
            "{law}: {} vs {}",
            sim.amplitude(),
            exact.amplitude()
        );
    }
    let (exact, _) = run(&values("exact_stiction"), TAU / 50.0, stop);
    for law in ["linear_stiction", "trigonometric_stiction"] {
        let mut v = values(law);
        v.set(vr::D, 1e-6);
        v.set(vr::DA, 1e-6);
        let (sim, _) = run(&v, TAU / 50.0, stop);
        let rel = (sim.amplitude() / exact.amplitude() - 1.0).abs();
        assert!(
            rel < 1e-5,
            "{law}: {} vs {}",
            sim.amplitude(),
            exact.amplitude()
        );
    }
}

/// Oracle: determinism. Restoring a saved state replays the same motion bit for bit.
/// Full and variants alike.
#[test]
fn save_and_restore_replay_the_motion() {
    let cases = [
        ("exact", Scope::full()),
        ("trigonometric", Scope::full()),
        ("trigonometric", motion_scope()),
    ];
    for (law, scope) in cases {
        let v = values(law);
        let mut sim = Oscillator::with_scope(&v, 0.0, &scope).unwrap();
        sim.do_step(3.0, &v).unwrap();
        let saved = sim.save();
        sim.do_step(2.0, &v).unwrap();
        let after = sim.save();
        sim.restore(&saved).unwrap();
        sim.do_step(2.0, &v).unwrap();
        assert_eq!(sim.save(), after, "{law}");
        assert!(sim.restore(&[1.0, 2.0]).is_err());
    }
}

/// Oracle: the input path equals the prescribed one when the input is the same force, held
/// over steps short enough (zero-order hold error ~ step).
#[test]
fn input_force_follows_the_input() {
    let mut prescribed = Oscillator::new(&values("exact"), 0.0).unwrap();
    let mut v = values("exact");
    v.set(
        vr::FORCE_SOURCE,
        f64::from(FORCE_SOURCE.value_of("input").unwrap()),
    );
    let mut input = Oscillator::new(&v, 0.0).unwrap();
    let step = 1e-3;
    for i in 0..10_000 {
        let t = (f64::from(i) + 0.5) * step;
        prescribed.step_logged(step, 0.0, None).unwrap();
        input.step_logged(step, 4.0 * t.sin(), None).unwrap();
    }
    let (a, b) = (prescribed.state().u, input.state().u);
    assert!((a - b).abs() < 1e-5 * a.abs().max(1.0), "{a} vs {b}");
}

#[test]
fn bad_parameters_are_refused_with_the_expected_range() {
    for (vr, x, name) in [
        (vr::M, 0.0, "m"),
        (vr::W, 0.0, "w"),
        (vr::D, 0.0, "D"),
        (vr::C, -1.0, "c"),
        (vr::H, f64::NAN, "h"),
        (vr::DA, -0.1, "Da"),
    ] {
        let mut v = values("linear");
        v.set(vr, x);
        let err = Oscillator::new(&v, 0.0).unwrap_err();
        assert_eq!(err.kind, Kind::Value { name }, "{err}");
    }
    let mut sim = Oscillator::new(&values("exact"), 0.0).unwrap();
    assert!(sim.step_logged(0.0, 0.0, None).is_err());
}

/// The steady amplitude of `law` over 20 periods by radau5 at rtol = atol = 1e-12: the
/// regularised laws' reference.
fn tight_amplitude(law: &str) -> f64 {
    let mut reference = with_solver(law, "radau5");
    reference.set(vr::RTOL, 1e-12);
    reference.set(vr::ATOL, 1e-12);
    steady_amplitude(&reference, 20).unwrap()
}

fn with_solver(law: &str, solver: &str) -> ValueSet {
    let mut v = values(law);
    v.set(
        vr::SOLVER,
        f64::from(
            crate::models::oscillator::table::SOLVER
                .value_of(solver)
                .unwrap(),
        ),
    );
    v
}

/// Oracle: radau5 at rtol = atol = 1e-12. Kink-aware dopri5, piecewise (closed form outside the
/// band) and rk4 (1024 steps a period) must reach the same steady amplitude for every
/// regularised law, including the stiction laws whose H has three kinks on each side; rk4 steps
/// across the kinks, so it is held to less.
#[test]
fn explicit_solvers_match_a_tight_radau_reference() {
    for law in [
        "linear",
        "trigonometric",
        "linear_stiction",
        "trigonometric_stiction",
    ] {
        let exact = tight_amplitude(law);
        let mut dopri = with_solver(law, "dopri5");
        dopri.set(vr::RTOL, 1e-10);
        dopri.set(vr::ATOL, 1e-10);
        let mut piecewise = with_solver(law, "piecewise");
        piecewise.set(vr::RTOL, 1e-10);
        piecewise.set(vr::ATOL, 1e-10);
        let mut rk4 = with_solver(law, "rk4");
        rk4.set(vr::STEPS_PER_PERIOD, 1024.0);
        for (name, v, tolerance) in [
            ("dopri5", dopri, 1e-8),
            ("piecewise", piecewise, 1e-8),
            ("rk4", rk4, 1e-5),
        ] {
            let amplitude = steady_amplitude(&v, 20).unwrap();
            assert!(
                (amplitude / exact - 1.0).abs() < tolerance,
                "{law} {name}: {amplitude} vs {exact}"
            );
        }
    }
}

/// Oracle: the order of RK4 on the smooth trigonometric law with D wide enough that every step
/// stays on one side of the kinks at |u'| = D only by chance: the error still falls by at least
/// ~8 per halving of the step (the kinks cost at most one order).
#[test]
fn rk4_converges_on_the_paper_case() {
    let exact = tight_amplitude("trigonometric");
    let error = |n: f64| {
        let mut v = with_solver("trigonometric", "rk4");
        v.set(vr::STEPS_PER_PERIOD, n);
        (steady_amplitude(&v, 20).unwrap() / exact - 1.0).abs()
    };
    let ratio = error(200.0) / error(400.0);
    assert!(ratio > 7.0, "error ratio {ratio}");
}

/// Regression: a motion that sticks in the transition band (forcing 0.001 N against h = 100 N,
/// slope C = h/D = 125 N.s/m) made rk4 at 128 steps a period gain energy at every step, with
/// W_diss at 3e4 J after 20 periods and every step reported as done. The slope now sets the
/// stability bound: the step is refused, and 1024 steps a period, within the bound, run.
#[test]
fn rk4_refuses_a_step_the_friction_slope_makes_unstable() {
    let mut v = with_solver("linear", "rk4");
    v.set(vr::H, 100.0);
    v.set(vr::P, 0.001);
    let period = std::f64::consts::TAU / v.real(vr::W);
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    let refused = sim.do_step(period, &v).unwrap_err();
    assert_eq!(
        refused.kind,
        Kind::Step {
            solver: "rk4",
            failure: Failure::BeyondStability
        },
        "{refused}"
    );
    v.set(vr::STEPS_PER_PERIOD, 1024.0);
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    for _ in 0..20 {
        sim.do_step(period, &v).unwrap();
    }
    // The forcing's work is at most P times the path, a few 1e-6 m here.
    let mut out = v.clone();
    sim.write_outputs(&mut out);
    assert!(out.real(vr::W_DISS) < 1e-6, "{}", out.real(vr::W_DISS));
}

/// u_amplitude and W_diss hidden: only the motion read.
fn motion_scope() -> Scope {
    Scope::hiding(vec![vr::U_AMPLITUDE, vr::W_DISS, vr::H_OUT, vr::C_OUT])
}

/// (u, u', u'') after each of `steps` communication steps of 1/50 forcing period.
fn motion(v: &ValueSet, scope: &Scope, steps: u32) -> Vec<[f64; 3]> {
    let mut sim = Oscillator::with_scope(v, 0.0, scope).unwrap();
    let h = std::f64::consts::TAU / v.real(vr::W) / 50.0;
    let mut out = v.clone();
    (0..steps)
        .map(|_| {
            sim.do_step(h, v).unwrap();
            sim.write_outputs(&mut out);
            [out.real(vr::U), out.real(vr::V), out.real(vr::A)]
        })
        .collect()
}

/// Oracle: the full model. Without the amplitude the turning points are not searched (that
/// search integrates probes from copies of the solver, never the run itself) and without W_diss
/// the friction work is not integrated (it has no say in the error control): the motion is the
/// same arithmetic, equal to round-off (1e-12 of its scale) for every solver. The exact core,
/// in closed form, only no longer restarts its phase at each period's end: round-off too.
#[test]
fn trimmed_model_without_amplitude_and_work_matches_the_full_one() {
    for (law, solver) in [
        ("trigonometric", "radau5"),
        ("trigonometric", "dopri5"),
        ("trigonometric", "rk4"),
        ("exact", "radau5"),
    ] {
        let v = with_solver(law, solver);
        let full = motion(&v, &Scope::full(), 500);
        let trimmed = motion(&v, &motion_scope(), 500);
        let scale = full.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in full.iter().zip(&trimmed) {
            for (x, y) in a.iter().zip(b) {
                assert!((x - y).abs() <= 1e-12 * scale, "{law} {solver}: {x} vs {y}");
            }
        }
    }
    let trimmed = Oscillator::with_scope(&values("linear"), 0.0, &motion_scope()).unwrap();
    assert!(!trimmed.tracks_amplitude);
}

/// Oracle: the step budget. With m = 1e-9 kg the velocity decays in m/c = 1e-9 s, and looking
/// for its sign changes on that grid over a step of 2 pi/100 s would take about 1e9 grid steps:
/// each step either completes or is refused within the budget, naming the grid.
#[test]
fn exact_with_a_grid_too_fine_for_the_step_is_refused_not_endless() {
    let mut v = values("exact");
    v.set(vr::M, 1e-9);
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    let step = TAU / 100.0;
    let mut refused = None;
    for _ in 0..20 {
        if let Err(message) = sim.step_logged(step, 0.0, None) {
            refused = Some(message);
            break;
        }
    }
    let error = refused.expect("a step of about 1e9 grid steps was taken");
    assert_eq!(
        error.kind,
        Kind::Step {
            solver: "exact",
            failure: Failure::TooManySteps
        },
        "{error}"
    );
}

/// Oracle: the exact switch model with stiction. With a transition band of 1e-9 m/s (D = Da)
/// the trigonometric stiction law is the switch model to within the band's width, and radau5,
/// which ends its steps on the band's edges as dopri5 does, resolves it: the amplitude and the
/// dissipated work after 30 periods agree (stepping across the edges, they were 1.4e-6 and 2e-3
/// off).
#[test]
fn radau5_resolves_a_narrow_stiction_band() {
    let run = |law: &str| {
        let mut v = with_solver(law, "radau5");
        v.set(vr::D, 1e-9);
        v.set(vr::DA, 1e-9);
        let mut sim = Oscillator::new(&v, 0.0).unwrap();
        for _ in 0..480 {
            sim.step_logged(TAU / 16.0, 0.0, None).unwrap();
        }
        let mut out = v.clone();
        sim.write_outputs(&mut out);
        (out.real(vr::U_AMPLITUDE), out.real(vr::W_DISS))
    };
    let (amplitude, work) = run("exact_stiction");
    let (a, w) = run("trigonometric_stiction");
    assert!((a / amplitude - 1.0).abs() < 1e-7, "{a} vs {amplitude}");
    assert!((w / work - 1.0).abs() < 1e-5, "{w} vs {work}");
}

/// linear_stiction's band below 1e-8 m/s is not resolved to the tolerance (its anti-damped
/// falling branch): the first step says so, once; a wider band says nothing.
#[test]
fn an_unresolved_linear_stiction_band_is_said_once() {
    for (d, warned) in [(1e-9, true), (1e-6, false)] {
        let mut v = with_solver("linear_stiction", "radau5");
        v.set(vr::D, d);
        v.set(vr::DA, d);
        let mut sim = Oscillator::new(&v, 0.0).unwrap();
        sim.step_logged(TAU / 16.0, 0.0, None).unwrap();
        let first = sim.take_warning();
        assert_eq!(first.is_some(), warned, "{first:?}");
        if warned {
            assert!(first.unwrap().contains("not accurate to the tolerance"));
            sim.step_logged(TAU / 16.0, 0.0, None).unwrap();
            assert!(sim.take_warning().is_none());
        }
    }
}

/// Oracles: without friction the closed-form steady amplitude p / |k - m w^2 + i c w|; with it,
/// the transient after 200 forcing periods (it decays by about half a period). With `initial =
/// periodic` the first period's u_amplitude is the steady one, for every law; an input force has
/// no period to find and is refused.
#[test]
fn a_periodic_start_is_steady_from_the_first_period() {
    use crate::models::oscillator::table::INITIAL;
    let periodic = f64::from(INITIAL.value_of("periodic").unwrap());
    let amplitude_after = |v: &ValueSet, periods: u32| {
        let mut sim = Oscillator::new(v, 0.0).unwrap();
        let period = sim.amplitude.period;
        for _ in 0..periods {
            sim.do_step(period, v).unwrap();
        }
        assert_eq!(sim.unresolved, None);
        sim.amplitude.last
    };
    let laws = [
        "linear",
        "trigonometric",
        "linear_stiction",
        "trigonometric_stiction",
        "exact",
        "exact_stiction",
    ];
    for law in laws {
        let mut v = values(law);
        v.set(vr::RTOL, 1e-10);
        v.set(vr::H, 0.0);
        let (m, c, k, p, w) = ["m", "c", "k", "P", "w"]
            .map(|n| v.real(TABLE.by_name(n).unwrap().value_reference))
            .into();
        let exact = p / ((k - m * w * w).powi(2) + (c * w).powi(2)).sqrt();
        v.set(vr::INITIAL, periodic);
        let first = amplitude_after(&v, 1);
        assert!(
            (first / exact - 1.0).abs() < 1e-8,
            "{law}, h = 0: {first} vs {exact}"
        );

        let mut v = values(law);
        v.set(vr::RTOL, 1e-10);
        let steady = amplitude_after(&v, 200);
        v.set(vr::INITIAL, periodic);
        let first = amplitude_after(&v, 1);
        assert!(
            (first / steady - 1.0).abs() < 1e-7,
            "{law}: {first} vs {steady}"
        );
    }
    let mut v = values("exact");
    v.set(vr::INITIAL, periodic);
    v.set(
        vr::FORCE_SOURCE,
        f64::from(FORCE_SOURCE.value_of("input").unwrap()),
    );
    let refused = Oscillator::new(&v, 0.0).unwrap_err();
    assert_eq!(refused.kind, Kind::Combination, "{refused}");
}

/// With k = 0 nothing holds the body where it is: every orbit shifted in u is an orbit too (a
/// Floquet multiplier of 1), and which one the motion settles on only the transient from
/// (u0, v0) knows. The periodic start says so and runs that transient: the same motion as a
/// start from (u0, v0), not an orbit at an offset Newton's method picked (u = -5.85e8 m).
#[test]
fn a_periodic_start_without_a_spring_says_so_and_runs_the_transient() {
    use crate::models::oscillator::table::INITIAL;
    for law in ["trigonometric", "exact"] {
        let mut v = values(law);
        v.set(vr::K, 0.0);
        let mut from_rest = Oscillator::new(&v, 0.0).unwrap();
        v.set(
            vr::INITIAL,
            f64::from(INITIAL.value_of("periodic").unwrap()),
        );
        let mut sim = Oscillator::new(&v, 0.0).unwrap();
        let said = sim.take_warning().unwrap_or_default();
        assert!(
            said.contains("k = 0") && said.contains("goes through the transient"),
            "{law}: {said}"
        );
        let period = sim.amplitude.period;
        for _ in 0..5 {
            sim.do_step(period, &v).unwrap();
            from_rest.do_step(period, &v).unwrap();
        }
        assert_eq!(sim.state(), from_rest.state(), "{law}");
        assert!(sim.amplitude.last < 20.0, "{law}: {}", sim.amplitude.last);
    }
}

/// A call that ends inside a step taken ahead is answered by `read_inside` (which the FMU asks
/// first, saving no rollback for it) exactly as by `do_step`: the same state to the bit, and
/// most short calls answered so.
#[test]
fn read_inside_answers_as_a_step_would() {
    let v = values("trigonometric");
    let mut stepped = Oscillator::new(&v, 0.0).unwrap();
    let mut read = Oscillator::new(&v, 0.0).unwrap();
    let mut answered = 0;
    for _ in 0..20_000 {
        stepped.do_step(1e-4, &v).unwrap();
        if read.read_inside(1e-4) {
            answered += 1;
        } else {
            read.do_step(1e-4, &v).unwrap();
        }
        assert_eq!(read.save(), stepped.save());
    }
    assert!(answered > 15_000, "{answered} of 20000 calls read inside");
}

/// Communication steps far shorter than radau5's: the calls that end inside a step taken ahead
/// read its polynomial, so a hundred calls of 1e-4 s cost about one step, and every point read
/// that way is within the tolerance of a run at rtol 1e-12 (calling every 0.1 s), as a run at
/// the same tolerance calling every 0.1 s is. The amplitude agrees too.
#[test]
fn short_communication_steps_read_a_step_taken_ahead() {
    let v = values("trigonometric");
    let mut tight = v.clone();
    tight.set(vr::RTOL, 1e-12);
    tight.set(vr::ATOL, 1e-12);
    let stop = 2.0 * TAU;
    let mut reference = Oscillator::new(&tight, 0.0).unwrap();
    let mut stepped = Oscillator::new(&v, 0.0).unwrap();
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    let (h, per_point) = (1e-4, 1000);
    let (mut worst, mut worst_stepped): (f64, f64) = (0.0, 0.0);
    let mut calls = 0;
    let off = |a: State, b: State| {
        assert!((a.t - b.t).abs() < 1e-9, "{} {}", a.t, b.t);
        // In units of the tolerance, atol + rtol |y| (1e-9 each).
        [(a.u, b.u), (a.v, b.v), (a.dissipated, b.dissipated)]
            .iter()
            .map(|(x, y)| (x - y).abs() / (1e-9 + 1e-9 * y.abs()))
            .fold(0.0_f64, f64::max)
    };
    while reference.time() + 0.1 < stop {
        reference.do_step(0.1, &tight).unwrap();
        stepped.do_step(0.1, &v).unwrap();
        for _ in 0..per_point {
            sim.do_step(h, &v).unwrap();
            calls += 1;
        }
        worst = worst.max(off(sim.state(), reference.state()));
        worst_stepped = worst_stepped.max(off(stepped.state(), reference.state()));
    }
    assert!(
        worst < 1.0 && worst_stepped < 1.0,
        "{worst} {worst_stepped}"
    );
    assert!(sim.amplitude.completed == 1 && reference.amplitude.completed == 1);
    assert!(
        (sim.amplitude() - reference.amplitude()).abs() < 1e-8,
        "{} {}",
        sim.amplitude(),
        reference.amplitude()
    );
    assert!(
        sim.work.steps * 50 < calls,
        "{} steps for {calls} calls",
        sim.work.steps
    );
}

/// During the first period u_amplitude is max |u| so far, and the calls that read a step taken
/// ahead must count the part of it they have read (they left it 7.5e-2 m below |u| at 1e-4 s
/// steps). Oracle: dopri5 at rtol = atol = 1e-12, which takes no step ahead, read every 1/16 s;
/// and max |u| so far is never below |u| now.
#[test]
fn the_amplitude_so_far_counts_what_is_read_from_a_step_taken_ahead() {
    let v = values("trigonometric");
    let mut reference = with_solver("trigonometric", "dopri5");
    reference.set(vr::RTOL, 1e-12);
    reference.set(vr::ATOL, 1e-12);
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    let mut oracle = Oscillator::new(&reference, 0.0).unwrap();
    let (h, per_point) = (1e-4, 625);
    let mut read_ahead = 0;
    let mut worst: f64 = 0.0;
    for i in 1..=60_000 {
        sim.do_step(h, &v).unwrap();
        read_ahead += usize::from(sim.ahead.is_some());
        if sim.amplitude.completed > 0 {
            break;
        }
        assert!(
            sim.amplitude() >= sim.state.u.abs(),
            "t = {}: u_amplitude {} below |u| = {}",
            sim.time(),
            sim.amplitude(),
            sim.state.u.abs()
        );
        if i % per_point == 0 {
            oracle.do_step(h * per_point as f64, &reference).unwrap();
            worst = worst.max((sim.amplitude() - oracle.amplitude()).abs());
        }
    }
    assert!(read_ahead > 10_000, "{read_ahead} calls read a step ahead");
    // The tolerance asked, atol + rtol |u| (1e-9 each), at |u| up to 10 m.
    assert!(worst < 1.1e-8, "u_amplitude so far {worst:e} m off");
}

/// A state saved while a step taken ahead is being read holds that step: restored, the run
/// goes on to the same bits.
#[test]
fn a_state_saved_inside_a_step_taken_ahead_replays_the_motion() {
    let v = values("trigonometric");
    let mut sim = Oscillator::new(&v, 0.0).unwrap();
    for _ in 0..3000 {
        sim.do_step(1e-3, &v).unwrap();
    }
    assert!(sim.ahead.is_some());
    let saved = sim.save();
    for _ in 0..3000 {
        sim.do_step(1e-3, &v).unwrap();
    }
    let after = sim.save();
    let mut other = Oscillator::new(&v, 0.0).unwrap();
    other.restore(&saved).unwrap();
    for _ in 0..3000 {
        other.do_step(1e-3, &v).unwrap();
    }
    assert_eq!(other.save(), after);
}

/// Oracle: radau5 at rtol = atol = 1e-12. piecewise takes the motion outside the band in closed
/// form: on the paper's trigonometric case it meets the tolerance asked from fewer right-hand
/// sides than dopri5 takes to the same tolerance (and few a period), through short
/// communication steps and a saved state replayed to the same bits; and the friction work it
/// sums is dopri5's.
#[test]
fn piecewise_meets_the_tolerance_from_fewer_evaluations() {
    let exact = tight_amplitude("trigonometric");
    let run = |solver: &str, tol: f64, calls: u32| {
        let mut v = with_solver("trigonometric", solver);
        v.set(vr::RTOL, tol);
        v.set(vr::ATOL, tol);
        v.set(vr::STEPS_PER_PERIOD, 8.0);
        let mut sim = Oscillator::new(&v, 0.0).unwrap();
        let h = sim.amplitude.period / f64::from(calls);
        for _ in 0..20 * calls {
            sim.do_step(h, &v).unwrap();
        }
        let mut out = v.clone();
        sim.write_outputs(&mut out);
        (
            sim.amplitude(),
            out.real(vr::W_DISS),
            sim.work.rhs_evaluations,
        )
    };
    for tol in [1e-3, 1e-5, 1e-8] {
        let (amplitude, work, evaluations) = run("piecewise", tol, 1);
        let error = (amplitude / exact - 1.0).abs();
        assert!(error < tol, "at {tol}: {amplitude} vs {exact}");
        if tol == 1e-3 {
            // A period costs two linear phases, each a few chunks of the search and Newton's
            // steps to round-off, and two band crossings of a step or two of dopri5 each.
            assert!(evaluations < 20 * 70, "at {tol}: {evaluations}");
        }
        let (_, dopri5_work, dopri5) = run("dopri5", tol, 1);
        assert!(
            evaluations < dopri5,
            "at {tol}: {evaluations} against {dopri5}"
        );
        assert!(
            (work / dopri5_work - 1.0).abs() < 10.0 * tol,
            "{work} {dopri5_work}"
        );
        let (short, _, _) = run("piecewise", tol, 100);
        assert!(
            (short / exact - 1.0).abs() < tol,
            "at {tol}, short calls: {short}"
        );
    }
    let v = with_solver("trigonometric", "piecewise");
    let mut a = Oscillator::new(&v, 0.0).unwrap();
    a.do_step(2.3, &v).unwrap();
    let saved = a.save();
    a.do_step(1.9, &v).unwrap();
    let mut b = Oscillator::new(&v, 0.0).unwrap();
    b.restore(&saved).unwrap();
    b.do_step(1.9, &v).unwrap();
    assert_eq!(a.state().u.to_bits(), b.state().u.to_bits());
    assert_eq!(a.amplitude().to_bits(), b.amplitude().to_bits());
}

/// Oracle: Hairer's stiffness test. At D = 1e-6 the law's slope h/D is 1.6e6, so inside the
/// band dopri5's steps are held by its stability: the warning says so, naming the solver the
/// user chose (`piecewise`, whose dopri5 it is), and at the paper's D = 0.8 nothing is said.
#[test]
fn piecewise_on_a_narrow_band_says_it_is_stiff() {
    for (d, stiff) in [(1e-6, true), (0.8, false)] {
        let mut v = with_solver("trigonometric", "piecewise");
        v.set(vr::D, d);
        let mut sim = Oscillator::new(&v, 0.0).unwrap();
        let mut warning = None;
        for _ in 0..16 {
            sim.step_logged(TAU / 4.0, 0.0, None).unwrap();
            warning = warning.or(sim.take_warning());
        }
        assert_eq!(warning.is_some(), stiff, "D {d}: {warning:?}");
        if let Some(warning) = warning {
            assert!(
                warning.starts_with("solver piecewise (its dopri5"),
                "{warning}"
            );
        }
    }
}
