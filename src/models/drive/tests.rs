//! Oracle: the closed-form solution of the motor's two linear equations (Sylvester's formula for
//! the 2 x 2 exponential, an affine particular solution for a load ramp), independent of the
//! Pade matrix exponential the simulation uses.

use super::{Drive, Params};
use crate::models::drive::table::{vr, TABLE};
use crate::models::Simulation;
use crate::variables::values::ValueSet;

type M2 = [[f64; 2]; 2];

fn mat_vec(a: &M2, x: [f64; 2]) -> [f64; 2] {
    [
        a[0][0] * x[0] + a[0][1] * x[1],
        a[1][0] * x[0] + a[1][1] * x[1],
    ]
}

fn inverse(a: &M2) -> M2 {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [
        [a[1][1] / det, -a[0][1] / det],
        [-a[1][0] / det, a[0][0] / det],
    ]
}

/// e^{A t} by Sylvester's formula (distinct real eigenvalues, as at the defaults).
fn exp2(a: &M2, t: f64) -> M2 {
    let tr = a[0][0] + a[1][1];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let root = (tr * tr / 4.0 - det).sqrt();
    // The eigenvalue of larger magnitude from the formula, the other from their product det: a
    // stiff motor (tiny L) would lose the slow one to cancellation in tr/2 + root.
    let fast = tr / 2.0 - root.copysign(-tr);
    let (l1, l2) = (det / fast, fast);
    let (e1, e2) = ((l1 * t).exp(), (l2 * t).exp());
    let mut out = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            let id = if i == j { 1.0 } else { 0.0 };
            out[i][j] = (e1 * (a[i][j] - l2 * id) - e2 * (a[i][j] - l1 * id)) / (l1 - l2);
        }
    }
    out
}

/// (i, omega, x_nut) at `t` from rest under V and the load F0 + rate t.
fn closed_form(p: &Params, voltage: f64, f0: f64, rate: f64, t: f64) -> [f64; 3] {
    let a = [
        [-p.resistance / p.inductance, -p.ke / p.inductance],
        [p.kt / p.j_eff, -p.b / p.j_eff],
    ];
    let load = -p.r / (p.efficiency * p.j_eff);
    let c0 = [voltage / p.inductance, load * f0];
    let c1 = [0.0, load * rate];
    let inv = inverse(&a);
    let slope = mat_vec(&inv, [-c1[0], -c1[1]]);
    let offset = mat_vec(&inv, [slope[0] - c0[0], slope[1] - c0[1]]);
    let e = exp2(&a, t);
    let start = [-offset[0], -offset[1]];
    let free = mat_vec(&e, start);
    // x = r * integral of omega: the particular part plus A^{-1}(e^{At} - I) applied to start.
    let e_minus_i = [[e[0][0] - 1.0, e[0][1]], [e[1][0], e[1][1] - 1.0]];
    let free_integral = mat_vec(&inv, mat_vec(&e_minus_i, start));
    [
        offset[0] + slope[0] * t + free[0],
        offset[1] + slope[1] * t + free[1],
        p.r * (offset[1] * t + 0.5 * slope[1] * t * t + free_integral[1]),
    ]
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale
}

#[test]
fn steps_are_exact_for_held_and_ramped_loads() {
    let mut values = ValueSet::start(&TABLE);
    let (f0, rate) = (0.9, 30.0);
    for (ramp, h) in [(0.0, 1e-3), (rate, 1e-3), (rate, 7e-3)] {
        values.set(vr::F_LOAD, f0);
        let mut drive = Drive::new(&values, 0.0).unwrap();
        let voltage = drive.p.voltage.unwrap();
        let mut t = 0.0;
        for _ in 0..12 {
            // The master's part: the input at the step's start, and its rate over the step.
            values.set(vr::F_LOAD, f0 + ramp * t);
            drive.set_input_derivative(vr::F_LOAD, ramp).unwrap();
            drive.do_step(h, &values).unwrap();
            t += h;
        }
        let want = closed_form(&drive.p, voltage, f0, ramp, t);
        drive.write_outputs(&mut values);
        let got = [
            values.real(vr::CURRENT),
            values.real(vr::OMEGA),
            values.real(vr::X_NUT),
        ];
        for k in 0..3 {
            assert!(
                close(got[k], want[k], want[k].abs()),
                "ramp {ramp}, h {h}: {got:?} vs {want:?}"
            );
        }
        assert!(close(
            values.real(vr::V_NUT),
            drive.p.r * want[1],
            want[1].abs() * drive.p.r
        ));
    }
}

/// A micro-motor (rotor inertia 1e-12 kg m^2) over long steps: its system matrix spans 1e-3 to
/// 1e10 per second, so its exponential must be balanced. Oracle: the steady state A y + c = 0,
/// which the transient, decaying at R/2L = 2500/s, has reached within e^-500 by the end of the
/// shortest step below; the nut has then moved r (omega_ss t + (A^-1 y_ss)_omega) from rest.
#[test]
fn a_micro_motor_reaches_its_steady_state_over_long_steps() {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::J, 1e-12);
    values.set(vr::M_NUT, 0.0);
    values.set(vr::F_LOAD, 0.9);
    for h in [0.2, 1.0, 30.0] {
        let mut drive = Drive::new(&values, 0.0).unwrap();
        let p = drive.p;
        drive.do_step(h, &values).unwrap();
        drive.write_outputs(&mut values);
        let a = [
            [-p.resistance / p.inductance, -p.ke / p.inductance],
            [p.kt / p.j_eff, -p.b / p.j_eff],
        ];
        let c = [
            p.voltage.unwrap() / p.inductance,
            -p.r * 0.9 / (p.efficiency * p.j_eff),
        ];
        let inv = inverse(&a);
        let steady = mat_vec(&inv, [-c[0], -c[1]]);
        let transient_area = mat_vec(&inv, [steady[0], steady[1]]);
        let x = p.r * (steady[1] * h + transient_area[1]);
        let got = [
            values.real(vr::CURRENT),
            values.real(vr::OMEGA),
            values.real(vr::X_NUT),
        ];
        let want = [steady[0], steady[1], x];
        for k in 0..3 {
            // Round-off: unbalanced, some 30 squarings left errors of 5e-9.
            assert!(
                (got[k] - want[k]).abs() < 1e-12 * want[k].abs(),
                "h {h}: {got:?} vs {want:?}"
            );
        }
    }
}

/// A derivative applies to one step: the next step without one holds the input again.
#[test]
fn an_input_derivative_applies_to_the_next_step_only() {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::F_LOAD, 1.0);
    let mut with = Drive::new(&values, 0.0).unwrap();
    let mut held = with.clone();
    with.set_input_derivative(vr::F_LOAD, 0.0).unwrap();
    with.do_step(1e-3, &values).unwrap();
    held.do_step(1e-3, &values).unwrap();
    assert_eq!(with.save(), held.save());
    with.set_input_derivative(vr::F_LOAD, 100.0).unwrap();
    with.do_step(1e-3, &values).unwrap();
    held.do_step(1e-3, &values).unwrap();
    assert!(
        held.save()[2] > with.save()[2] + 1e-9,
        "a rising load slows the motor"
    );
    let gap = held.save()[2] - with.save()[2];
    // Both hold the load now: the gap changes only by the system's own relaxation.
    with.do_step(1e-6, &values).unwrap();
    held.do_step(1e-6, &values).unwrap();
    assert!(((held.save()[2] - with.save()[2]) - gap).abs() < 1e-3 * gap.abs());
}

/// Oracle: the state equations themselves (d/dt r omega = r omega', d/dt x = r omega), at a
/// state away from rest, and refusal for what has none.
#[test]
fn output_derivatives_are_the_state_equations() {
    let mut values = ValueSet::start(&TABLE);
    values.set(vr::F_LOAD, 0.5);
    let mut drive = Drive::new(&values, 0.0).unwrap();
    drive.do_step(2e-3, &values).unwrap();
    let h = 1e-7;
    let before = drive.clone();
    let mut after = drive.clone();
    after.do_step(h, &values).unwrap();
    let mut a = values.clone();
    let mut b = values.clone();
    before.write_outputs(&mut a);
    after.write_outputs(&mut b);
    for out in [vr::V_NUT, vr::X_NUT, vr::CURRENT, vr::OMEGA] {
        let slope = (b.real(out) - a.real(out)) / h;
        let exact = before.output_derivative(out, &values).unwrap();
        assert!(
            (slope - exact).abs() < 1e-3 * exact.abs(),
            "{out}: {slope} vs {exact}"
        );
    }
    assert!(before.output_derivative(vr::R, &values).is_err());
    assert!(drive.set_input_derivative(vr::V_NUT, 1.0).is_err());
}

/// With F_load = a t set at every communication point and no derivative, `extrapolated` holds
/// the first step (one value known) and then moves the load along the same line the master's
/// derivative a would: the two runs meet to round-off.
#[test]
fn an_extrapolated_load_ramp_is_the_ramp_the_derivative_gives() {
    let (a, h) = (50.0, 1e-4);
    let mut values = ValueSet::start(&TABLE);
    values.set(
        vr::INPUT_SCHEME,
        f64::from(
            crate::variables::declare::INPUT_SCHEME
                .value_of("extrapolated")
                .unwrap(),
        ),
    );
    let mut extrapolated = Drive::new(&values, 0.0).unwrap();
    let mut derivative = Drive::new(&ValueSet::start(&TABLE), 0.0).unwrap();
    for k in 0..20 {
        let t = k as f64 * h;
        values.set(vr::F_LOAD, a * t);
        if k > 0 {
            derivative.set_input_derivative(vr::F_LOAD, a).unwrap();
        }
        extrapolated.do_step(h, &values).unwrap();
        derivative.do_step(h, &values).unwrap();
    }
    let (x, y) = (extrapolated.save(), derivative.save());
    for k in 1..4 {
        assert!((x[k] - y[k]).abs() <= 1e-12 * y[k].abs(), "{x:?} {y:?}");
    }
}

/// A motor whose armature time constant L/R is far below a step, and far below the mechanical
/// one (L = 1e-15 H, 2e-16 s against 10 ms; L = J = 1e-30): its exponential spans some 30
/// binades, and the slow mode, a part in 1e13 of the matrix's norm, must still come out exact.
/// Oracle: the closed form (Sylvester's formula with the slow eigenvalue det / fast, free of
/// cancellation) at 0.1 s from rest.
#[test]
fn a_stiff_motor_is_exact_at_any_step() {
    for (inductance, inertia) in [(1e-15, 2e-7), (1e-30, 1e-30), (1e-9, 2e-7)] {
        for h in [1e-4f64, 1e-2] {
            let mut values = ValueSet::start(&TABLE);
            values.set(vr::L, inductance);
            values.set(vr::J, inertia);
            let mut drive = Drive::new(&values, 0.0).unwrap();
            let steps = (0.1 / h).round() as usize;
            for _ in 0..steps {
                drive.do_step(h, &values).unwrap();
            }
            let t = steps as f64 * h;
            let want = closed_form(&drive.p, drive.p.voltage.unwrap(), 0.0, 0.0, t);
            drive.write_outputs(&mut values);
            let got = [
                values.real(vr::CURRENT),
                values.real(vr::OMEGA),
                values.real(vr::X_NUT),
            ];
            // Round-off: i = (V - ke omega) / R cancels to 1/200 of V / R, and 1000 steps add up
            // (2.8e-12 at worst; the squarings of exp itself left i 26 % off at L = 1e-15).
            for k in 0..3 {
                assert!(
                    (got[k] - want[k]).abs() <= 1e-10 * want[k].abs(),
                    "L {inductance}, J {inertia}, h {h}: {got:?} vs {want:?}"
                );
            }
        }
    }
}
