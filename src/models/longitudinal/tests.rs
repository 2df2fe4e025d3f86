use super::*;
use crate::error::{Failure, Kind};
use crate::models::longitudinal::table::{LAW, SOLVER, TABLE};

fn values(law: &str, vc: f64) -> ValueSet {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::LAW, f64::from(LAW.value_of(law).unwrap()));
    values.set(vr::VC, vc);
    values
}

/// Oracle: Leus & Gutowski (2008), Table 1, Dahl column (va = 0.264 m/s, kt = 0.056 N/um).
#[test]
fn dahl_reproduces_table_1() {
    for (vc, published) in [
        (0.324, 0.0196),
        (0.230, 0.0181),
        (0.146, 0.0109),
        (0.095, 0.0066),
    ] {
        let mean = steady_mean_force(&values("dahl", vc), 30).unwrap();
        assert!(
            (mean / published - 1.0).abs() < 0.01,
            "vc {vc}: {mean} vs {published}"
        );
    }
}

/// Oracle: the closed form FC (2/pi) asin(vc/va) (fraction of the period with vr < 0).
#[test]
fn coulomb_matches_closed_form() {
    // 0.264 = va: vr touches zero once a period without changing sign.
    for vc in [0.230, 0.146, -0.095, 0.4, 0.264] {
        let values = values("coulomb", vc);
        let mean = steady_mean_force(&values, 3).unwrap();
        let fc = 0.1 * 0.02 * 9.81;
        let exact = coulomb::mean_under_vibration(fc, vc, 0.264);
        assert!(
            (mean - exact).abs() < 1e-12 * fc,
            "vc {vc}: {mean} vs {exact}"
        );
    }
}

/// Halving the sub-step must cut the error about fourfold (second order).
#[test]
fn dahl_mean_converges_with_second_order() {
    let mean_at = |n: f64| {
        let mut values = values("dahl", 0.146);
        values.set(
            vr::SOLVER,
            f64::from(SOLVER.value_of("exponential").unwrap()),
        );
        values.set(vr::STEPS_PER_PERIOD, n);
        steady_mean_force(&values, 12).unwrap()
    };
    let reference = mean_at(64_000.0);
    let e1 = (mean_at(200.0) - reference).abs();
    let e2 = (mean_at(400.0) - reference).abs();
    let ratio = e1 / e2;
    assert!((3.5..4.5).contains(&ratio), "error ratio {ratio}");
}

/// Oracle: W_diss = FC times the distance slid, the integral of |vr|, in closed form between
/// vr's zeros. Coulomb's force keeps its level over each sub-step, so its work is exact at
/// any steps_per_period (the midpoint rule left 2.2e-2 of it off at 4, 3.0e-7 at 2000, at
/// vc = 0.146 m/s).
#[test]
fn coulomb_work_is_exact_on_any_grid() {
    let (fc, va, f) = (0.1 * 0.02 * 9.81, 0.264, 60e3);
    let slid = |vc: f64, t: f64| vc * t + va / (TAU * f) * (TAU * f * t).sin();
    let exact = |vc: f64, stop: f64| {
        // vr's zeros, in turns: where cos = -vc/va.
        let mut cuts = vec![0.0, stop];
        if vc.abs() < va {
            let p = (-vc / va).acos() / TAU;
            for k in 0..(stop * f).ceil() as i32 {
                for turn in [f64::from(k) + p, f64::from(k + 1) - p] {
                    if turn / f < stop {
                        cuts.push(turn / f);
                    }
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        fc * cuts
            .windows(2)
            .map(|w| (slid(vc, w[1]) - slid(vc, w[0])).abs())
            .sum::<f64>()
    };
    for vc in [0.146, -0.095, 0.264, 0.4] {
        for n in [4.0, 2000.0] {
            let mut v = values("coulomb", vc);
            v.set(vr::STEPS_PER_PERIOD, n);
            let mut sim = Longitudinal::new(&v, 0.0).unwrap();
            // 12 periods in calls that end off the grid and off the period.
            let stop = 2e-4;
            for _ in 0..70 {
                sim.do_step(stop / 70.0, &v).unwrap();
            }
            let want = exact(vc, stop);
            let got = sim.dissipated_energy();
            assert!(
                (got - want).abs() < 1e-13 * want,
                "vc {vc}, n {n}: {got} vs {want} ({:.1e})",
                got / want - 1.0
            );
        }
    }
}

/// W_diss counts from 0 at the start: a periodic start's bristle holds the orbit's energy
/// there, which is stored, not dissipated. Counted against the work it made W_diss negative,
/// and a Dahl or LuGre run calling 64 times a period was refused as creating energy at its
/// first call, and at kt = 1e-3 the shooting itself fell back (the exponential solver told to
/// use the exponential solver). Oracles: the work a period of the converged transient from
/// rest dissipates (the energy stored returns to its value each period); at kt = 1e-3, where
/// that transient takes millions of periods, the orbit's second period.
#[test]
fn a_periodic_start_dissipates_from_zero() {
    use crate::models::longitudinal::table::INITIAL;
    for (law, kt) in [("lugre", None), ("dahl", None), ("dahl", Some(1e-3))] {
        let mut v = values(law, 0.146);
        if let Some(kt) = kt {
            v.set(vr::KT, kt);
        }
        let period = 1.0 / v.real(vr::F);
        let mut rest = Longitudinal::new(&v, 0.0).unwrap();
        for _ in 0..400 * 64 {
            rest.do_step(period / 64.0, &v).unwrap();
        }
        let before = rest.dissipated_energy();
        for _ in 0..64 {
            rest.do_step(period / 64.0, &v).unwrap();
        }
        let per_period = rest.dissipated_energy() - before;
        v.set(
            vr::INITIAL,
            f64::from(INITIAL.value_of("periodic").unwrap()),
        );
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        assert_eq!(sim.take_warning(), None, "{law} {kt:?}");
        assert_eq!(sim.dissipated_energy(), 0.0, "{law} {kt:?}");
        for k in 0..64 {
            sim.do_step(period / 64.0, &v)
                .unwrap_or_else(|e| panic!("{law} {kt:?}, call {k}: {e}"));
        }
        let first = sim.dissipated_energy();
        for _ in 0..64 {
            sim.do_step(period / 64.0, &v).unwrap();
        }
        let second = sim.dissipated_energy() - first;
        let want = if kt.is_some() { second } else { per_period };
        assert!(
            (first / want - 1.0).abs() < 1e-6,
            "{law} {kt:?}: {first} vs {want}"
        );
    }
}

/// LuGre's damping force sigma1 z' adds sigma1 f (z(T) - z(0)) to a period's FT_mean: 0 on
/// the orbit, but in the first period after a periodic start it multiplies the shooting's
/// residual in z by sigma1 f, which must then close to FT_mean's tolerance, not z's (radau5
/// at sigma1 = 1e4 was 1.1e-4 of FT_mean off with one call a period, where the steps are
/// the shooting's own). Oracle: the transient from rest after 100 periods (the bristle
/// settles within one). The adaptive solvers hold z to the tolerance over that gain, so
/// 64 calls a period, whose steps are not the shooting's, meet it too (dopri5 was 2.0e-6 of
/// FT_mean off at sigma1 = 1e3); the exponential solver's grid error it cannot close, and
/// says so.
#[test]
fn a_periodic_start_closes_the_lugre_damping_term() {
    use crate::models::longitudinal::table::INITIAL;
    let fc = 0.1 * 0.02 * 9.81;
    for solver in ["exponential", "dopri5", "radau5"] {
        for sigma1 in [0.0, 1e3, 1e4] {
            let mut v = values("lugre", 0.146);
            v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
            v.set(vr::SIGMA1, sigma1);
            let steady = steady_mean_force(&v, 100).unwrap();
            v.set(
                vr::INITIAL,
                f64::from(INITIAL.value_of("periodic").unwrap()),
            );
            let mut sim = Longitudinal::new(&v, 0.0).unwrap();
            let said = sim.take_warning();
            assert_eq!(
                said.is_some(),
                sigma1 > 0.0 && solver == "exponential",
                "{solver}, sigma1 {sigma1}: {said:?}"
            );
            if let Some(said) = said {
                assert!(said.contains("first period"), "{said}");
            }
            let mut calls_64 = sim.clone();
            sim.do_step(1.0 / sim.f, &v).unwrap();
            for _ in 0..64 {
                calls_64.do_step(1.0 / sim.f / 64.0, &v).unwrap();
            }
            // The grid's error in z times sigma1 f/sigma0, which the warning says.
            let firsts = if solver == "exponential" {
                vec![sim.mean_force()]
            } else {
                vec![sim.mean_force(), calls_64.mean_force()]
            };
            for first in firsts {
                assert!(
                    (first - steady).abs() < 3e-8 * fc,
                    "{solver}, sigma1 {sigma1}: {first} vs {steady} ({:.1e} of FC)",
                    (first - steady) / fc
                );
            }
        }
    }
}

/// A Dahl bristle with alpha < 1 that starts within the solver's slack of saturation is
/// saturated from the start: no solver can step there (dopri5 spent 2e6 steps on a sub-step
/// of 5e-324 s, and the periodic start fell back saying so). Oracle: the transient from rest
/// after 200 periods.
#[test]
fn a_bristle_saturated_at_a_step_start_is_held() {
    use crate::models::longitudinal::table::INITIAL;
    let fc = 0.1 * 0.02 * 9.81;
    for solver in ["dopri5", "radau5"] {
        let mut v = values("dahl", 0.146);
        v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
        v.set(vr::ALPHA, 0.3);
        let steady = steady_mean_force(&v, 200).unwrap();
        v.set(
            vr::INITIAL,
            f64::from(INITIAL.value_of("periodic").unwrap()),
        );
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        assert_eq!(sim.take_warning(), None, "{solver}");
        sim.do_step(1.0 / sim.f, &v).unwrap();
        let first = sim.mean_force();
        assert!(
            (first - steady).abs() < 1e-8 * fc,
            "{solver}: {first} vs {steady}"
        );
    }
}

/// The solvers count time from the communication step's start: a message of theirs says
/// so, and where that start is ("the step fell to 6.7e-21 s at t = 0e0" was all a step
/// from 1e-5 s said).
#[test]
fn a_solver_message_says_where_its_time_starts() {
    for solver in ["dopri5", "radau5"] {
        let mut v = values("lugre", 0.146);
        v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
        v.set(vr::VELOCITY_SOURCE, 2.0);
        v.set(vr::KT, 1e15);
        v.set(vr::TOLERANCE, 1e-14);
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        sim.do_step(1e-5, &v).unwrap();
        v.set(vr::VR_IN, 1e3);
        let said = sim.do_step(1e-5, &v).unwrap_err().found;
        assert!(
            said.contains("at t = 0e0")
                && said.ends_with(
                    "(the solver's times count from the communication step's start, t = 0.00001 s)"
                ),
            "{solver}: {said}"
        );
    }
}

/// Coulomb with W_diss hidden (law and bristle parameters fixed, only FT_mean and S read).
fn coulomb_scope() -> Scope {
    Scope::hiding(vec![
        vr::LAW,
        vr::KT,
        vr::ALPHA,
        vr::FT,
        vr::Z,
        vr::VR,
        vr::W_DISS,
    ])
}

/// `(FT_mean, S)` after each of `periods` periods.
fn mean_trace(values: &ValueSet, scope: &Scope, periods: u32) -> Vec<(f64, f64)> {
    let mut sim = Longitudinal::with_scope(values, 0.0, scope).unwrap();
    let mut out = values.clone();
    (0..periods)
        .map(|_| {
            sim.do_step(1.0 / sim.f, values).unwrap();
            sim.write_outputs(&mut out);
            (out.real(vr::FT_MEAN), out.real(vr::S))
        })
        .collect()
}

/// Oracle: the full model, and the closed form. With W_diss hidden Coulomb's closed form
/// runs over the sign changes of vr instead of the 1/n grid: the same integral summed in
/// fewer pieces, equal to round-off (1e-13 FC; 1e-11 in S, a percentage).
#[test]
fn trimmed_coulomb_matches_the_full_model() {
    let fc = 0.1 * 0.02 * 9.81;
    for vc in [0.230, 0.146, -0.095, 0.4, 0.264] {
        let v = values("coulomb", vc);
        let full = mean_trace(&v, &Scope::full(), 4);
        let trimmed = mean_trace(&v, &coulomb_scope(), 4);
        for ((a, sa), (b, sb)) in full.iter().zip(&trimmed) {
            assert!((a - b).abs() < 1e-13 * fc, "vc {vc}: {a} vs {b}");
            assert!((sa - sb).abs() < 1e-11, "vc {vc}: S {sa} vs {sb}");
        }
        let exact = coulomb::mean_under_vibration(fc, vc, 0.264);
        assert!((trimmed[3].0 - exact).abs() < 1e-13 * fc, "vc {vc}");
    }
    // The trimmed model takes a handful of sub-steps a period, not steps_per_period.
    let mut sim =
        Longitudinal::with_scope(&values("coulomb", 0.146), 0.0, &coulomb_scope()).unwrap();
    sim.do_step(1.0 / sim.f, &values("coulomb", 0.146)).unwrap();
    assert!(sim.work.steps <= 4, "{} sub-steps", sim.work.steps);
}

/// save/restore of the trimmed Coulomb model continues it exactly.
#[test]
fn trimmed_coulomb_restore_continues_identically() {
    let v = values("coulomb", 0.146);
    let h = 0.37 / 60_000.0;
    let mut a = Longitudinal::with_scope(&v, 0.0, &coulomb_scope()).unwrap();
    a.do_step(h, &v).unwrap();
    let saved = a.save();
    a.do_step(h, &v).unwrap();
    let mut b = Longitudinal::with_scope(&v, 0.0, &coulomb_scope()).unwrap();
    b.restore(&saved).unwrap();
    b.do_step(h, &v).unwrap();
    assert_eq!(a.mean_force(), b.mean_force());
    assert_eq!(a.time(), b.time());
}

/// `(FT, FT_mean)` after each of 30 communication steps of 0.37 period under `scope`.
fn force_trace(values: &ValueSet, scope: &Scope) -> (Vec<(f64, f64)>, Longitudinal) {
    let mut sim = Longitudinal::with_scope(values, 0.0, scope).unwrap();
    let mut out = values.clone();
    let trace = (0..30)
        .map(|_| {
            sim.do_step(0.37 / sim.f, values).unwrap();
            sim.write_outputs(&mut out);
            (out.real(vr::FT), out.real(vr::FT_MEAN))
        })
        .collect();
    (trace, sim)
}

/// Oracle: the full model, and for FT the full model at rtol 1e-12. The general solvers
/// leave out the work w when W_diss is hidden (it has no say in their error control: the
/// same steps, FT_mean equal to round-off), and the force integral q and the period cuts
/// when FT_mean and S are hidden too: then the steps differ, and FT must be as close to the
/// tight run as the full model's (within twice its error, itself below 1e-6 FC at rtol
/// 1e-8). rk4 keeps w for the passivity check (and its grid holds the period ends).
#[test]
fn trimmed_general_solvers_match_the_full_model() {
    let fc = 0.1 * 0.02 * 9.81;
    let mean_read = Scope::hiding(vec![vr::FT, vr::Z, vr::VR, vr::W_DISS]);
    let trace_read = Scope::hiding(vec![vr::FT_MEAN, vr::S, vr::W_DISS]);
    for law in ["dahl", "lugre"] {
        for solver in ["dopri5", "radau5", "rk4"] {
            let mut v = values(law, 0.146);
            v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
            let (full, _) = force_trace(&v, &Scope::full());
            let (mean, a) = force_trace(&v, &mean_read);
            let (trace, b) = force_trace(&v, &trace_read);
            let fixed = solver == "rk4";
            assert_eq!((a.ode_dim, b.ode_dim), if fixed { (3, 3) } else { (2, 1) });
            for ((_, m), (_, m2)) in full.iter().zip(&mean) {
                assert!((m - m2).abs() <= 1e-13 * fc, "{law} {solver}: {m} vs {m2}");
            }
            let mut tight = v.clone();
            tight.set(vr::TOLERANCE, 1e-12);
            let (reference, _) = force_trace(&tight, &Scope::full());
            let error = |t: &[(f64, f64)]| {
                t.iter()
                    .zip(&reference)
                    .map(|((f, _), (r, _))| (f - r).abs())
                    .fold(0.0, f64::max)
            };
            let (e_full, e_trimmed) = (error(&full), error(&trace));
            assert!(e_full < 1e-6 * fc, "{law} {solver}: full {e_full:e} N");
            assert!(
                e_trimmed <= 2.0 * e_full + 1e-12 * fc,
                "{law} {solver}: trimmed {e_trimmed:e} N, full {e_full:e} N"
            );
        }
    }
}

/// save/restore of a simulation without q and w continues it exactly.
#[test]
fn trimmed_general_solver_restore_continues_identically() {
    let mut v = values("dahl", 0.146);
    v.set(vr::SOLVER, f64::from(SOLVER.value_of("radau5").unwrap()));
    let scope = Scope::hiding(vec![vr::FT_MEAN, vr::S, vr::W_DISS]);
    let h = 0.37 / 60_000.0;
    let mut a = Longitudinal::with_scope(&v, 0.0, &scope).unwrap();
    a.do_step(h, &v).unwrap();
    let saved = a.save();
    a.do_step(h, &v).unwrap();
    let mut b = Longitudinal::with_scope(&v, 0.0, &scope).unwrap();
    b.restore(&saved).unwrap();
    b.do_step(h, &v).unwrap();
    assert_eq!(a.friction_force(), b.friction_force());
    assert_eq!(a.z(), b.z());
}

fn with_solver(solver: &str, knob: f64) -> ValueSet {
    let mut values = values("dahl", 0.146);
    values.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
    if knob >= 1.0 {
        values.set(vr::STEPS_PER_PERIOD, knob);
    } else {
        values.set(vr::TOLERANCE, knob);
    }
    values
}

/// Oracle: the exponential scheme at 64000 steps a period (second order, so within about
/// 1e-9 of the limit). rk4 must show fourth order: halving its step cuts the error by ~16.
#[test]
fn rk4_converges_with_fourth_order() {
    let reference = steady_mean_force(&with_solver("exponential", 64_000.0), 12).unwrap();
    let error =
        |n: f64| (steady_mean_force(&with_solver("rk4", n), 12).unwrap() / reference - 1.0).abs();
    let ratio = error(50.0) / error(100.0);
    assert!((13.0..19.0).contains(&ratio), "error ratio {ratio}");
}

/// Oracle: the exponential scheme at 64000 steps a period; the adaptive solvers meet it to
/// about their tolerance, and their error falls as the tolerance does.
#[test]
fn adaptive_solvers_meet_the_fine_exponential_reference() {
    let reference = steady_mean_force(&with_solver("exponential", 64_000.0), 12).unwrap();
    for solver in ["dopri5", "radau5"] {
        let error = |tol: f64| {
            (steady_mean_force(&with_solver(solver, tol), 12).unwrap() / reference - 1.0).abs()
        };
        let (loose, tight) = (error(1e-5), error(1e-8));
        assert!(tight < 1e-7, "{solver}: error {tight} at 1e-8");
        assert!(
            tight < loose / 10.0,
            "{solver}: {loose} at 1e-5, {tight} at 1e-8"
        );
    }
}

/// Dahl with alpha < 1 saturates after a finite sliding distance, where the rate's slope is
/// unbounded. The adaptive solvers stop within their tolerance of that corner and hold the
/// bristle from there (what they did before: docs/performance.md, "Measurements behind the
/// code"). Oracle: the exponential scheme
/// (exact bristle update, second order) at 16 000 steps a period, with a Richardson
/// correction from 4 000, within about 1e-10 of the limit.
#[test]
fn dahl_below_alpha_one_saturates_without_stalling_the_adaptive_solvers() {
    for alpha in [0.3, 0.6] {
        let with_alpha = |solver: &str, knob: f64| {
            let mut v = with_solver(solver, knob);
            v.set(vr::ALPHA, alpha);
            v
        };
        let mean = |v: &ValueSet| steady_mean_force(v, 10).unwrap();
        let (coarse, fine) = (
            mean(&with_alpha("exponential", 4_000.0)),
            mean(&with_alpha("exponential", 16_000.0)),
        );
        let reference = fine + (fine - coarse) / 15.0;
        for solver in ["dopri5", "radau5"] {
            for tol in [1e-6, 1e-8] {
                let v = with_alpha(solver, tol);
                let mut sim = Longitudinal::new(&v, 0.0).unwrap();
                for _ in 0..10 {
                    sim.do_step(1.0 / sim.f, &v).unwrap();
                }
                let error = (sim.mean_force() / reference - 1.0).abs();
                assert!(
                    error < 10.0 * tol,
                    "alpha {alpha}, {solver} at {tol}: error {error}"
                );
                let rhs = sim.work.rhs_evaluations;
                assert!(rhs < 40_000, "alpha {alpha}, {solver} at {tol}: {rhs} RHS");
            }
        }
    }
}

/// A contact barely deflected (va 0.13 um/s: z about 1e-5 of FC/kt) holds energies below
/// what the adaptive solvers resolve. Their round-off there is not read as the contact
/// creating energy (it was, at rtol 1e-3), while an unstable fixed step still is.
#[test]
fn a_barely_deflected_contact_is_not_taken_for_an_unstable_one() {
    for solver in ["dopri5", "radau5"] {
        for tol in [1e-3, 1e-4, 5e-6, 1e-6] {
            let mut v = values("dahl", 0.0);
            v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
            v.set(vr::VA, 1.3e-7);
            v.set(vr::F, 1557.0);
            v.set(vr::KT, 3250.0);
            v.set(vr::ALPHA, 2.24);
            v.set(vr::TOLERANCE, tol);
            let mut sim = Longitudinal::new(&v, 0.0).unwrap();
            for k in 0..40 {
                sim.do_step(0.25 / 1557.0, &v)
                    .unwrap_or_else(|e| panic!("{solver} at rtol {tol}, step {k}: {e}"));
            }
        }
    }
    let mut v = values("dahl", 0.0);
    v.set(vr::SOLVER, f64::from(SOLVER.value_of("rk4").unwrap()));
    v.set(vr::STEPS_PER_PERIOD, 4.0);
    v.set(vr::KT, 1e9);
    let mut sim = Longitudinal::new(&v, 0.0).unwrap();
    let refused = (0..10).find_map(|_| sim.do_step(1e-4, &v).err());
    assert!(
        refused
            .as_ref()
            .is_some_and(|e| e.failure() == Some(Failure::CreatedEnergy)),
        "rk4 far beyond its stability bound: {refused:?}"
    );
}

/// Oracle: the same run from t = 0. Within a step the phase and the solvers' time count from
/// the step's start, so a run started a whole number of periods far from 0 is the same run
/// but for where the master's clock (a double) puts the communication points, and with them
/// the period over which FT_mean is taken: it differs by no more than that resolution allows
/// (ulp(t) f of a period, times the force's swing over its mean), and the simulation asks for
/// the warning that says so once that resolution passes the tolerance.
#[test]
fn a_run_started_far_from_zero_is_the_run_started_at_zero() {
    let trace_from = |v: &ValueSet, t0: f64| {
        let mut sim = Longitudinal::new(v, t0).unwrap();
        let mut out = v.clone();
        for _ in 0..20 {
            sim.do_step(1.0 / sim.f, v).unwrap();
        }
        sim.write_outputs(&mut out);
        (out.real(vr::FT_MEAN), out.real(vr::S))
    };
    for (law, solver) in [
        ("dahl", "dopri5"),
        ("dahl", "radau5"),
        ("dahl", "exponential"),
        ("dahl", "closed_form"),
        ("lugre", "dopri5"),
        ("coulomb", "dopri5"),
    ] {
        let mut v = values(law, 0.146);
        v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
        let (mean, s) = trace_from(&v, 0.0);
        let fc = 0.1 * 0.02 * 9.81;
        // 60 kHz: 6e9 and 6e10 periods.
        for t0 in [1e5, 1e6] {
            let (far_mean, far_s) = trace_from(&v, t0);
            let error = (far_mean / mean - 1.0).abs();
            let resolution = f64::EPSILON * t0 * 60e3;
            assert!(
                error < 4.0 * resolution * fc / mean,
                "{law} {solver} from {t0}: FT_mean {far_mean} vs {mean} ({error:.1e}), S {far_s} vs {s}"
            );
            let sim = Longitudinal::new(&v, t0).unwrap();
            let reading = sim.reading_period().unwrap();
            assert!(crate::models::clock_warning(t0, reading).is_some());
            assert!(crate::models::clock_warning(1e-3, reading).is_none());
        }
    }
}

/// Oracle: dopri5 at rtol 1e-12. With m = 1e6 kg, FC = 1e5 N and FC/kt = 17 m, while the
/// contact slides 7 um a period and FT_mean is 1.3 N: tolerances on the scale of saturation
/// let every adaptive solver drift by rtol FC / FT_mean (1.2e-4 for radau5 at 1e-8); on the
/// scale of the distance slid in a period they meet their tolerance.
#[test]
fn a_heavy_body_is_solved_to_the_tolerance_of_the_forces_it_meets() {
    let with = |solver: &str, tol: f64| {
        let mut v = values("dahl", 0.146);
        v.set(vr::M, 1e6);
        v.set(vr::SOLVER, f64::from(SOLVER.value_of(solver).unwrap()));
        v.set(vr::TOLERANCE, tol);
        steady_mean_force(&v, 10).unwrap()
    };
    let reference = with("dopri5", 1e-12);
    for solver in ["dopri5", "radau5", "closed_form"] {
        for tol in [1e-8, 1e-10] {
            let error = (with(solver, tol) / reference - 1.0).abs();
            assert!(error < 10.0 * tol, "{solver} at {tol}: {error:.1e}");
        }
    }
}

/// Oracle: dopri5 at rtol 1e-12. closed_form's bristle is exact, so its FT_mean meets the
/// tolerance asked, from fewer evaluations than dopri5 takes to the same tolerance; a saved
/// state replays to the same bits.
#[test]
fn closed_form_meets_the_tolerance_from_few_evaluations() {
    let reference = steady_mean_force(&with_solver("dopri5", 1e-12), 12).unwrap();
    let run = |solver: &str, tol: f64| {
        let v = with_solver(solver, tol);
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        for _ in 0..12 {
            sim.do_step(1.0 / sim.f, &v).unwrap();
        }
        (sim.mean_force(), sim.work.rhs_evaluations)
    };
    for tol in [1e-4, 1e-6, 1e-10] {
        let (mean, evaluations) = run("closed_form", tol);
        let error = (mean / reference - 1.0).abs();
        assert!(error < tol, "closed_form at {tol}: error {error:.1e}");
        let (_, dopri5) = run("dopri5", tol);
        assert!(
            evaluations < dopri5,
            "at {tol}: {evaluations} evaluations, dopri5 {dopri5}"
        );
    }
    let v = with_solver("closed_form", 1e-8);
    let h = 0.37 / 60_000.0;
    let mut a = Longitudinal::new(&v, 0.0).unwrap();
    a.do_step(h, &v).unwrap();
    let saved = a.save();
    a.do_step(h, &v).unwrap();
    let mut b = Longitudinal::new(&v, 0.0).unwrap();
    b.restore(&saved).unwrap();
    b.do_step(h, &v).unwrap();
    assert_eq!(a.mean_force().to_bits(), b.mean_force().to_bits());
    assert_eq!(a.z().to_bits(), b.z().to_bits());
}

/// Once a period has completed, closed_form takes calls that end inside a sub-step in
/// closed form and leaves the force integral to the sub-step's end: a hundred calls a period
/// read what one call a period reads (FT_mean to the tolerance, z and W_diss to round-off)
/// for about the same evaluations, and a state saved between the calls replays to the bit.
#[test]
fn short_closed_form_calls_leave_the_force_integral_to_the_cut() {
    let v = with_solver("closed_form", 1e-8);
    // The simulation after 6 periods, and its evaluations over the last 5.
    let run = |calls: u32| {
        let mut sim = Longitudinal::new(&v, 0.0).unwrap();
        let h = 1.0 / (sim.f * f64::from(calls));
        let mut first = 0;
        for i in 0..6 * calls {
            sim.do_step(h, &v).unwrap();
            if i + 1 == calls {
                first = sim.work.rhs_evaluations;
            }
        }
        let later = sim.work.rhs_evaluations - first;
        (sim, later)
    };
    let ((long, e_long), (short, e_short)) = (run(1), run(100));
    assert!((short.mean_force() / long.mean_force() - 1.0).abs() < 1e-8);
    assert!((short.z() - long.z()).abs() < 1e-12 * long.fc / 5.6e4);
    let (w_short, w_long) = (short.dissipated_energy(), long.dissipated_energy());
    assert!((w_short / w_long - 1.0).abs() < 1e-12, "{w_short} {w_long}");
    // One closed form a call (its distance slid) beside the sub-steps' quadratures.
    assert!(e_short < e_long + 2 * 5 * 100, "{e_short} against {e_long}");

    let (mut a, _) = run(100);
    let h = 1.0 / (a.f * 100.0);
    a.do_step(h, &v).unwrap();
    assert!(a.pending.is_some());
    let saved = a.save();
    let mut b = Longitudinal::new(&v, 0.0).unwrap();
    b.restore(&saved).unwrap();
    for _ in 0..150 {
        a.do_step(h, &v).unwrap();
        b.do_step(h, &v).unwrap();
    }
    assert_eq!(a.save(), b.save());
}

/// closed_form refuses what has no closed form, saying what it expected.
#[test]
fn closed_form_refuses_laws_without_a_closed_form() {
    let mut lugre = with_solver("closed_form", 1e-8);
    lugre.set(vr::LAW, f64::from(LAW.value_of("lugre").unwrap()));
    let mut power = with_solver("closed_form", 1e-8);
    power.set(vr::ALPHA, 0.5);
    let mut loaded = with_solver("closed_form", 1e-8);
    loaded.set(
        vr::NORMAL_FORCE_SOURCE,
        f64::from(table::NORMAL_FORCE_SOURCE.value_of("input").unwrap()),
    );
    for (case, v) in [
        ("lugre", lugre),
        ("alpha 0.5", power),
        ("normal force input", loaded),
    ] {
        let refused = Longitudinal::new(&v, 0.0).err();
        assert!(
            refused
                .as_ref()
                .is_some_and(|e| e.kind == Kind::Combination),
            "{case}: {refused:?}"
        );
    }
}
