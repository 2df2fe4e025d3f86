//! The arguments the fuzzers pass: values of every variable kind (special floats, the ranges'
//! ends, starts), value references known and unknown, and step sizes, kept near the defaults
//! where the FMU would accept them (see `MAX_STEPS_PER_CALL`).

use super::rng::Rng;
use friction_fmu::variables::values::check_value;
use friction_fmu::variables::variable::{Kind, ModelTable, Variable};

/// The longest step the fuzzer takes, in default steps of the model.
///
/// Parameters such as a vibration frequency of 1e12 Hz or a velocity of 1e12 m/s are accepted
/// and ask for millions of integration steps: the FMU stops such a doStep at its work limit
/// (src/solve/mod.rs) with a Discard, after about a second (tests/python/test_work_limit.py).
/// A second per call is too slow for 1e5 sequences, and the fuzzer hunts crashes, not slow
/// steps, so it keeps steps and accepted parameter values near the defaults (see `tame`).
pub const MAX_STEPS_PER_CALL: f64 = 20.0;

/// A value the FMU accepts for `var` is replaced by one within 10x of the variable's nominal
/// value (its start, or 1 if that is 0), keeping the sign; values the FMU refuses (NaN, inf,
/// out of range, not an item) are kept, as refusing them is what is being tested.
pub fn tame(rng: &mut Rng, table: &ModelTable, var: &Variable, value: f64) -> f64 {
    if check_value(table, var, value).is_err() || value == 0.0 {
        return value;
    }
    let start = match var.kind {
        Kind::Real { start, .. } => start,
        Kind::Integer { start, .. } => f64::from(start),
        Kind::Switch { .. } => return value,
    };
    let nominal = if start == 0.0 { 1.0 } else { start.abs() };
    let tamed = value.signum() * nominal * 10f64.powf(rng.unit() * 2.0 - 1.0);
    let tamed = match var.kind {
        Kind::Integer { .. } => tamed.round(),
        _ => tamed,
    };
    // Still inside the range (e.g. a tolerance whose maximum is near its default).
    if check_value(table, var, tamed).is_ok() {
        tamed
    } else {
        start
    }
}

pub const SPECIAL: &[f64] = &[
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    -1.0,
    1.0,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    1e-300,
    f64::MIN_POSITIVE,
    5e-324,
    1e-12,
];

pub fn real_value(rng: &mut Rng, table: &ModelTable, var: Option<&Variable>) -> f64 {
    let Some(var) = var else {
        return rng.pick(SPECIAL);
    };
    let (start, min, max) = match var.kind {
        Kind::Real {
            start, min, max, ..
        } => (start, min, max),
        _ => (0.0, f64::NEG_INFINITY, f64::INFINITY),
    };
    let nominal = if start == 0.0 { 1.0 } else { start };
    let value = match rng.below(6) {
        0 | 1 => rng.pick(SPECIAL),
        2 => min,
        3 => max,
        4 => start,
        _ => nominal * (rng.unit() * 4.0 - 1.0),
    };
    tame(rng, table, var, value)
}

pub fn integer_value(rng: &mut Rng, table: &ModelTable, var: Option<&Variable>) -> i32 {
    let special = [0, -1, 1, 2, 3, 4, 7, i32::MIN, i32::MAX];
    let Some(var) = var else {
        return rng.pick(&special);
    };
    let value = match var.kind {
        Kind::Integer { start, min, max } => match rng.below(4) {
            0 => rng.pick(&special),
            1 => min,
            2 => max,
            _ => start,
        },
        Kind::Switch { type_name, start } => {
            let items = table.enum_type(type_name).map_or(0, |e| e.items.len()) as i32;
            match rng.below(4) {
                0 => rng.pick(&special),
                1 => items + 1,
                2 => start,
                _ => 1 + rng.below(items.max(1) as usize) as i32,
            }
        }
        Kind::Real { .. } => rng.pick(&special),
    };
    tame(rng, table, var, f64::from(value)) as i32
}

/// Value references: mostly the model's own, sometimes unknown ones.
pub fn value_references(rng: &mut Rng, table: &ModelTable) -> Vec<u32> {
    let n = rng.pick(&[0, 1, 1, 1, 2, 3, 5]);
    (0..n)
        .map(|_| {
            if rng.chance(85) {
                table.variables[rng.below(table.variables.len())].value_reference
            } else {
                let random = rng.next() as u32;
                rng.pick(&[0, 5, 9, 99, 1000, u32::MAX, random])
            }
        })
        .collect()
}

pub fn step_size(rng: &mut Rng, table: &ModelTable) -> f64 {
    let h = table.default_experiment.step_size;
    let step = rng.pick(&[
        0.0,
        -0.0,
        -h,
        -1.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e-300,
        1e-12,
        1.0,
        h,
        h,
        h,
        h * 0.37,
        // Far shorter than the solvers' steps: TransverseFriction reads steps taken ahead.
        h * 0.1,
        h * 3.0,
    ]);
    if step.is_finite() && step > MAX_STEPS_PER_CALL * h {
        MAX_STEPS_PER_CALL * h
    } else {
        step
    }
}
