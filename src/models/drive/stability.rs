//! The extremes DriveTrain is run at in the stability matrix (src/report/stability.rs): each a
//! parameter set, a communication step and a number of steps.

use crate::models::stability::{Cases, Extreme, Value::*};

/// DriveTrain at its defaults (10 ms mechanical, 0.2 ms electrical time constant) from rest;
/// every extreme runs through, the scheme being exact at any step.
const EXTREMES: &[Extreme] = &[
    ("paper", &[], 1e-4, 500),
    ("L 1e-9", &[("L", Real(1e-9))], 1e-4, 500),
    ("J 1e-12", &[("J", Real(1e-12))], 1e-4, 500),
    ("efficiency 1e-3", &[("efficiency", Real(1e-3))], 1e-4, 500),
    ("step 1e-8", &[], 1e-8, 2000),
    ("step 1 s", &[], 1.0, 20),
    ("1e6 s", &[], 1e4, 100),
];

pub const CASES: Cases = Cases {
    base: &[],
    extremes: EXTREMES,
    fixed_law: None,
};
