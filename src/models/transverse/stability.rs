//! The extremes scene T is run at in the stability matrix (src/report/stability.rs): each a
//! parameter set, a communication step and a number of steps.

use crate::models::stability::{Cases, Extreme, Value::*};

const T_PERIOD: f64 = 1.0 / 3000.0;
/// Scene T at the paper's values (vd 0.5 mm/s, va 2 mm/s, 3 kHz) starting in steady sliding;
/// 4 periods.
const EXTREMES: &[Extreme] = &[
    ("paper", &[], T_PERIOD / 20.0, 80),
    ("kt x1e3", &[("kt", Real(6.286e10))], T_PERIOD / 20.0, 80),
    ("vs 1e-9", &[("vs", Real(1e-9))], T_PERIOD / 20.0, 80),
    ("f 1 Hz", &[("f", Real(1.0))], 1e-3, 10),
    ("f 100 kHz", &[("f", Real(1e5))], 1e-5 / 20.0, 80),
    ("va 0", &[("va", Real(0.0))], T_PERIOD / 20.0, 80),
    ("va 100 vd", &[("vd", Real(2e-5))], T_PERIOD / 20.0, 80),
    ("vd 0", &[("vd", Real(0.0))], T_PERIOD / 20.0, 80),
    // The body moves along y alone, so the bristle passes through zero where the slip reverses.
    (
        "vd 0, zeta 0.4, hv 1",
        &[("vd", Real(0.0)), ("zeta", Real(0.4)), ("hv", Real(1.0))],
        T_PERIOD / 20.0,
        80,
    ),
    ("vd < 0", &[("vd", Real(-5e-4))], T_PERIOD / 20.0, 80),
    ("eta 0", &[("eta", Real(0.0))], T_PERIOD / 20.0, 80),
    ("eta 1", &[("eta", Real(1.0))], T_PERIOD / 20.0, 80),
    // One period: dopri5 warns of the stiffness within it and then grinds on.
    ("m 1e-6", &[("m", Real(1e-6))], T_PERIOD / 20.0, 20),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 2),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(20)), ("tolerance", Real(1e-4))],
        100.0 * T_PERIOD,
        100,
    ),
];

pub const CASES: Cases = Cases {
    base: &[("initial", Item("sliding"))],
    extremes: EXTREMES,
    fixed_law: None,
};
