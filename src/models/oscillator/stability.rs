//! The extremes scene O is run at in the stability matrix (src/report/stability.rs): each a
//! parameter set, a communication step and a number of steps.

use crate::models::stability::{Cases, Extreme, Value::*};

const O_PERIOD: f64 = std::f64::consts::TAU;
/// Scene O, trigonometric law at the paper's values (w = 1 rad/s); 3 forcing periods.
const EXTREMES: &[Extreme] = &[
    ("paper", &[], O_PERIOD / 50.0, 150),
    ("D 1e-6", &[("D", Real(1e-6))], O_PERIOD / 50.0, 150),
    (
        "w 2 pi 1 Hz",
        &[("w", Real(std::f64::consts::TAU))],
        1.0 / 50.0,
        150,
    ),
    (
        "w 2 pi 100 kHz",
        &[("w", Real(std::f64::consts::TAU * 1e5))],
        1e-5 / 50.0,
        150,
    ),
    ("m 1e-6", &[("m", Real(1e-6))], O_PERIOD / 50.0, 50),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 20),
    (
        "1e4 periods",
        &[("steps_per_period", Integer(20)), ("rtol", Real(1e-4))],
        100.0 * O_PERIOD,
        100,
    ),
];

pub const CASES: Cases = Cases {
    base: &[],
    extremes: EXTREMES,
    fixed_law: Some(("law", "exact")),
};
