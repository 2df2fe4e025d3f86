//! The extremes scene L is run at in the stability matrix (src/report/stability.rs): each a
//! parameter set, a communication step and a number of steps.

use crate::models::stability::{Cases, Extreme, Value::*};

const L_PERIOD: f64 = 1.0 / 60e3;
/// Scene L, Dahl at Table 1's vc = 0.146 m/s unless the case says otherwise; 3 periods.
const EXTREMES: &[Extreme] = &[
    ("paper", &[], L_PERIOD / 20.0, 60),
    ("kt x1e3", &[("kt", Real(5.6e7))], L_PERIOD / 20.0, 60),
    (
        "lugre vs 1e-9",
        &[("law", Item("lugre")), ("vs", Real(1e-9))],
        L_PERIOD / 20.0,
        60,
    ),
    ("f 1 Hz", &[("f", Real(1.0))], 0.05, 60),
    ("f 100 kHz", &[("f", Real(1e5))], 1e-5 / 20.0, 60),
    ("va 0", &[("va", Real(0.0))], L_PERIOD / 20.0, 60),
    ("va 100 vc", &[("vc", Real(0.00264))], L_PERIOD / 20.0, 60),
    ("vc 0", &[("vc", Real(0.0))], L_PERIOD / 20.0, 60),
    ("vc < 0", &[("vc", Real(-0.146))], L_PERIOD / 20.0, 60),
    // Below alpha 1 the bristle saturates in finite time, where the rate is not Lipschitz.
    (
        "dahl alpha 0.3",
        &[("law", Item("dahl")), ("alpha", Real(0.3))],
        L_PERIOD / 20.0,
        60,
    ),
    ("m 1e-6", &[("m", Real(1e-6))], L_PERIOD / 20.0, 60),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 2),
    // Only where a period costs a few steps whatever the stiffness (`cases` in
    // src/report/stability.rs).
    (
        "1e6 periods",
        &[("f", Real(1.0)), ("steps_per_period", Integer(8))],
        1e4,
        100,
    ),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(64)), ("tolerance", Real(1e-4))],
        100.0 * L_PERIOD,
        100,
    ),
];

pub const CASES: Cases = Cases {
    base: &[("law", Item("dahl")), ("vc", Real(0.146))],
    extremes: EXTREMES,
    fixed_law: Some(("law", "coulomb")),
};
