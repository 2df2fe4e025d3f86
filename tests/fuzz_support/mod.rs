//! What the call fuzzers over both FMI boundaries share (tests/fuzz_calls.rs for FMI 2.0,
//! tests/fuzz_calls_fmi3.rs for FMI 3.0), a module each: the deterministic PRNG (rng.rs), the
//! values, value references and step sizes they pass (values.rs), corrupted serialized states
//! (serialized.rs), how a sequence is laid out (sequence.rs), its FMU-state calls
//! (fmu_states.rs), the promises checked after each call (checks.rs), and the runner that spreads
//! sequences over the cores, counts panics and reports hung calls (runner.rs).
//!
//! A deterministic PRNG (splitmix64) makes every sequence reproducible:
//! `FUZZ_SEED` (default 0x5EED), `FUZZ_SEQUENCES` (default per fuzzer), `FUZZ_ONLY=<n>` reruns
//! sequence n alone and prints its calls.

pub mod checks;
pub mod fmu_states;
pub mod rng;
pub mod runner;
pub mod sequence;
pub mod serialized;
pub mod values;
