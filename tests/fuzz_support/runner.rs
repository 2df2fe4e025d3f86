//! The runner of a fuzz test: spreads its sequences over the cores, counts panics, reports hung
//! calls and the failing sequences, and reads `FUZZ_SEED`, `FUZZ_SEQUENCES` and `FUZZ_ONLY`.

use std::cell::Cell;
use std::io::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

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
