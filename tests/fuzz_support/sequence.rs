//! How a sequence of either standard is laid out: its PRNG, the models of its first two
//! instances, the calls planned to bring them to the stepping phases before the random ones, and
//! the arguments both standards' calls draw alike (an experiment's times, a step's communication
//! point, debug-logging categories).

use super::rng::Rng;
use super::values::SPECIAL;
use friction_fmu::models::MODELS;
use friction_fmu::variables::variable::ModelTable;

/// The PRNG of sequence `index` from `seed`: each sequence can be rerun alone (FUZZ_ONLY).
pub fn rng_of(seed: u64, index: u64) -> Rng {
    Rng(seed ^ index.wrapping_mul(0xD6E8_FEB8_6659_FD93))
}

/// A model at random.
pub fn any_model(rng: &mut Rng) -> &'static ModelTable {
    MODELS[rng.below(MODELS.len())].table
}

/// The first instance's model, and the instances of a sequence (None where one was refused).
pub type Slots<S> = (&'static ModelTable, Vec<Option<S>>);

/// The first two instances, "fuzz0" and "fuzz1", mostly of one model: `instantiate` returns
/// Err("") when the FMU rightly refused (the slot stays empty), Err(why) for a broken promise.
pub fn first_two<S>(
    rng: &mut Rng,
    mut instantiate: impl FnMut(&mut Rng, &'static ModelTable, &str) -> Result<S, String>,
) -> Result<Slots<S>, String> {
    let first = any_model(rng);
    let second = if rng.chance(70) {
        first
    } else {
        any_model(rng)
    };
    let mut slots = Vec::new();
    for (k, table) in [first, second].into_iter().enumerate() {
        match instantiate(rng, table, &format!("fuzz{k}")) {
            Ok(slot) => slots.push(Some(slot)),
            Err(e) if e.is_empty() => slots.push(None),
            Err(e) => return Err(e),
        }
    }
    Ok((first, slots))
}

/// A new instance "again" of a model at random for slot `k`: beside the slot's instance where that
/// was `freed` and there are fewer than four (the freed handle is kept, so later calls test that it
/// stays dead, also when the new instance takes the freed memory), else in its place. Returns the
/// instance it replaced; Err(why) for a broken promise, a rightful refusal changes nothing.
pub fn reinstantiate<S>(
    rng: &mut Rng,
    slots: &mut Vec<Option<S>>,
    k: usize,
    freed: impl Fn(&S) -> bool,
    mut instantiate: impl FnMut(&mut Rng, &'static ModelTable, &str) -> Result<S, String>,
) -> Result<Option<S>, String> {
    let table = any_model(rng);
    let keep = slots[k].as_ref().is_some_and(freed) && slots.len() < 4;
    match instantiate(rng, table, "again") {
        Ok(slot) if keep => {
            slots.push(Some(slot));
            Ok(None)
        }
        Ok(slot) => Ok(slots[k].replace(slot)),
        Err(e) if e.is_empty() => Ok(None),
        Err(e) => Err(e),
    }
}

/// The calls of a sequence: planned ones first, then random ones.
pub struct Calls<Op> {
    planned: Vec<(usize, Op)>,
    /// How many calls the sequence makes, planned ones included.
    pub count: usize,
}

impl<Op: Copy> Calls<Op> {
    /// Most sequences first bring their `slots` instances to the stepping phases (with up to three
    /// parameters set by `set` on the way, then the calls `initialize`), so that the random calls
    /// after that reach them often; half also `seed_bytes` (serialized states to corrupt). Then up
    /// to 60 random calls.
    pub fn new(
        rng: &mut Rng,
        slots: usize,
        mut set: impl FnMut(&mut Rng) -> Op,
        initialize: &[Op],
        seed_bytes: Op,
    ) -> Calls<Op> {
        let mut planned = Vec::new();
        for k in 0..slots {
            if rng.chance(75) {
                planned.extend((0..rng.below(4)).map(|_| (k, set(rng))));
                planned.extend(initialize.iter().map(|&op| (k, op)));
            }
            if rng.chance(50) {
                planned.push((k, seed_bytes));
            }
        }
        let count = planned.len() + 1 + rng.below(60);
        Calls { planned, count }
    }

    /// Call `call`: (the slot it is made on, what it does), planned or else one of `ops` on any
    /// of `slots`.
    pub fn get(&self, call: usize, rng: &mut Rng, slots: usize, ops: &[Op]) -> (usize, Op) {
        match self.planned.get(call) {
            Some(&planned) => planned,
            None => (rng.below(slots), rng.pick(ops)),
        }
    }
}

/// An experiment's tolerance, start and stop time: mostly sane, sometimes anything in SPECIAL.
pub struct Experiment {
    pub tolerance: Option<f64>,
    pub start: f64,
    pub stop: Option<f64>,
}

impl Experiment {
    /// The experiment of `table`, from 0, with its stop time or none.
    pub fn valid(rng: &mut Rng, table: &ModelTable) -> Experiment {
        Experiment {
            tolerance: None,
            start: 0.0,
            stop: rng.chance(50).then_some(table.default_experiment.stop_time),
        }
    }

    pub fn random(rng: &mut Rng, table: &ModelTable) -> Experiment {
        let tolerance = rng.chance(50).then(|| rng.pick(SPECIAL).abs());
        let start = if rng.chance(70) {
            0.0
        } else {
            rng.pick(SPECIAL)
        };
        let stop = rng.chance(40).then(|| {
            if rng.chance(70) {
                start + table.default_experiment.stop_time
            } else {
                rng.pick(SPECIAL)
            }
        });
        Experiment {
            tolerance,
            start,
            stop,
        }
    }

    /// The arguments as a report shows them.
    pub fn describe(&self) -> String {
        let Experiment {
            tolerance,
            start,
            stop,
        } = self;
        format!("({tolerance:?}, {start}, {stop:?})")
    }
}

/// The communication point of a step of `h` from an instance believed to be at `time`: mostly
/// that time, sometimes off it (ahead, behind, not finite, or off by a rounding error).
pub fn communication_point(rng: &mut Rng, time: f64, h: f64) -> f64 {
    if rng.chance(85) {
        time
    } else {
        rng.pick(&[
            time + 1e-3,
            time - h,
            f64::NAN,
            f64::INFINITY,
            0.0,
            -1.0,
            time * (1.0 + 1e-15),
        ])
    }
}

/// Up to two debug-logging categories, known or not.
pub fn debug_categories(rng: &mut Rng) -> Vec<&'static str> {
    let n = rng.below(3);
    (0..n)
        .map(|_| rng.pick(&["logCalls", "logStatusError", "logStatusWarning", "nope", ""]))
        .collect()
}
