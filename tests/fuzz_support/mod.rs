//! What the call fuzzers over both FMI boundaries share (tests/fuzz_calls.rs for FMI 2.0,
//! tests/fuzz_calls_fmi3.rs for FMI 3.0): the deterministic PRNG, the values, value references,
//! step sizes and corrupted serialized states they pass, and the runner that spreads sequences
//! over the cores, counts panics and reports hung calls; in its modules, how a sequence is laid
//! out (sequence.rs), its FMU-state calls (fmu_states.rs) and the promises checked after each
//! call (checks.rs).
//!
//! A deterministic PRNG (splitmix64) makes every sequence reproducible:
//! `FUZZ_SEED` (default 0x5EED), `FUZZ_SEQUENCES` (default per fuzzer), `FUZZ_ONLY=<n>` reruns
//! sequence n alone and prints its calls.

pub mod checks;
pub mod fmu_states;
pub mod sequence;

use friction_fmu::variables::values::check_value;
use friction_fmu::variables::variable::{Kind, ModelTable, Variable};
use std::cell::Cell;
use std::io::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

pub struct Rng(pub u64);

impl Rng {
    /// splitmix64: tiny, fast, and good enough to spread choices evenly.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    pub fn chance(&mut self, percent: u64) -> bool {
        self.next() % 100 < percent
    }

    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.below(items.len())]
    }
}

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

/// The FMU's checksum of serialized states (FNV-1a 64), recomputed so that corrupted bytes get
/// past it and reach the structural checks behind it.
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

pub fn mutate(rng: &mut Rng, pool: &[Vec<u8>]) -> (Vec<u8>, String) {
    let mut note = String::new();
    let mut bytes = if pool.is_empty() || rng.chance(5) {
        (0..rng.below(200)).map(|_| rng.next() as u8).collect()
    } else {
        pool[rng.below(pool.len())].clone()
    };
    match rng.below(8) {
        0 | 1 => {}
        2 => bytes.truncate(rng.below(bytes.len() + 1)),
        3 => {
            if !bytes.is_empty() {
                let i = rng.below(bytes.len());
                bytes[i] ^= 1 << rng.below(8);
            }
        }
        4 => bytes.extend((0..rng.below(16)).map(|_| rng.next() as u8)),
        _ => {
            // Overwrite an 8-byte number in the body with a special value, then fix the checksum.
            // One whole number: the serialized state is the magic word, its length, the GUID's
            // length and text, then 8-byte numbers, then the checksum.
            let guid_length = bytes
                .get(16..20)
                .map_or(0, |b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize);
            let first = 20 + guid_length;
            if bytes.len() >= first + 16 {
                let body = bytes.len() - 8;
                let at = first + 8 * rng.below((body - first) / 8);
                // Values the FMU must refuse, or harmless ones: an accepted 1e12 Hz or a
                // 1e-300 kg would make the next doStep endless (see MAX_STEPS_PER_CALL).
                let value = rng.pick(&[
                    f64::NAN,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    -1.0,
                    0.0,
                    -0.0,
                    1.0,
                    2.0,
                    3.5,
                    6.0,
                ]);
                bytes[at..at + 8].copy_from_slice(&value.to_le_bytes());
                note = format!(", {value} at byte {at}, checksum fixed");
                let sum = fnv1a(&bytes[..body]);
                bytes[body..].copy_from_slice(&sum.to_le_bytes());
            }
        }
    }
    (bytes, note)
}

pub static PANICS: AtomicUsize = AtomicUsize::new(0);
pub static PANIC_MESSAGES: Mutex<Vec<String>> = Mutex::new(Vec::new());

thread_local! {
    /// Whether this thread runs sequences: panics elsewhere (another test of the same binary
    /// failing) are not the fuzzer's to count.
    static FUZZING: Cell<bool> = const { Cell::new(false) };
}

/// Counts every panic on the threads that run sequences, also those the FMU catches at its C
/// boundary (still a bug there).
pub fn count_panics() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !FUZZING.with(Cell::get) {
                return default(info);
            }
            PANICS.fetch_add(1, Ordering::SeqCst);
            let mut messages = PANIC_MESSAGES.lock().unwrap_or_else(|e| e.into_inner());
            if messages.len() < 5 {
                messages.push(info.to_string());
            }
            default(info);
        }));
    });
}

pub fn env_number(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(text) => {
            let text = text.trim();
            let parsed = match text.strip_prefix("0x") {
                Some(hex) => u64::from_str_radix(hex, 16),
                None => text.parse(),
            };
            parsed.unwrap_or_else(|_| panic!("{name}={text}: expected a number"))
        }
        Err(_) => default,
    }
}

/// A sequence that has not finished after this long is reported as hung, and the process ends
/// (a hung FMU call cannot be interrupted, and a stalled CI job says nothing).
pub const HANG_SECONDS: u64 = 60;

/// One sequence of calls: (seed, index, verbose) to the first broken promise, if any.
pub type Sequence = fn(u64, u64, bool) -> Result<(), String>;

/// Runs `count` sequences from `seed` on every core; returns the failures (sequence, message).
pub fn fuzz(sequence: Sequence, seed: u64, count: u64) -> Vec<(u64, String)> {
    count_panics();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let failures = Mutex::new(Vec::new());
    // Per thread: the sequence it runs and when it started it (seconds since `started`).
    let running: Vec<(AtomicU64, AtomicU64)> = (0..threads)
        .map(|_| (AtomicU64::new(u64::MAX), AtomicU64::new(0)))
        .collect();
    let done = AtomicBool::new(false);
    let started = Instant::now();
    std::thread::scope(|scope| {
        let (running, done) = (&running, &done);
        scope.spawn(move || {
            while !done.load(Ordering::SeqCst) {
                std::thread::sleep(Duration::from_millis(200));
                let now = started.elapsed().as_secs();
                for (index, since) in running {
                    let index = index.load(Ordering::SeqCst);
                    if index != u64::MAX && now > since.load(Ordering::SeqCst) + HANG_SECONDS {
                        // Straight to stderr: the test harness captures eprintln!.
                        let _ = writeln!(
                            std::io::stderr(),
                            "fuzz: sequence {index} has run for over {HANG_SECONDS} s: a hung call \
                             (rerun it with FUZZ_SEED={seed:#x} FUZZ_ONLY={index} -- --nocapture)"
                        );
                        std::process::exit(101);
                    }
                }
            }
        });
        let workers: Vec<_> = (0..threads)
            .map(|thread| {
                let failures = &failures;
                let (slot_index, slot_since) = &running[thread as usize];
                scope.spawn(move || {
                    FUZZING.with(|f| f.set(true));
                    let mut index = thread;
                    while index < count {
                        slot_since.store(started.elapsed().as_secs(), Ordering::SeqCst);
                        slot_index.store(index, Ordering::SeqCst);
                        let outcome =
                            catch_unwind(AssertUnwindSafe(|| sequence(seed, index, false)));
                        slot_index.store(u64::MAX, Ordering::SeqCst);
                        let failure = match outcome {
                            Ok(Ok(())) => None,
                            Ok(Err(message)) => Some(message),
                            Err(_) => Some("panicked (see the panic message above)".to_string()),
                        };
                        if let Some(message) = failure {
                            let mut failures = failures.lock().unwrap_or_else(|e| e.into_inner());
                            failures.push((index, message));
                            if failures.len() >= 10 {
                                return;
                            }
                        }
                        index += threads;
                    }
                })
            })
            .collect();
        for worker in workers {
            let _ = worker.join();
        }
        done.store(true, Ordering::SeqCst);
    });
    failures.into_inner().unwrap_or_else(|e| e.into_inner())
}

/// The fuzz test: `FUZZ_ONLY` reruns one sequence verbosely, else `FUZZ_SEQUENCES` (default
/// `default_count`) run on every core; fails with the failing sequences and any panic.
pub fn run(sequence: Sequence, default_count: u64) {
    let seed = env_number("FUZZ_SEED", 0x5EED);
    if let Ok(only) = std::env::var("FUZZ_ONLY") {
        let index = env_number("FUZZ_ONLY", 0);
        println!("FUZZ_ONLY={only}");
        let result = sequence(seed, index, true);
        assert_eq!(result, Ok(()));
        return;
    }
    let count = env_number("FUZZ_SEQUENCES", default_count);
    let started = Instant::now();
    let mut failures = fuzz(sequence, seed, count);
    failures.sort();
    println!(
        "{count} sequences (seed {seed:#x}) in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let panics = PANICS.load(Ordering::SeqCst);
    let panic_messages = PANIC_MESSAGES.lock().map(|m| m.clone()).unwrap_or_default();
    assert!(
        failures.is_empty() && panics == 0,
        "{} failing sequences (rerun one with FUZZ_SEED={seed:#x} FUZZ_ONLY=<n> -- --nocapture), \
         {panics} panics {panic_messages:?}:\n{}",
        failures.len(),
        failures
            .iter()
            .map(|(i, m)| format!("  sequence {i}: {m}"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}
