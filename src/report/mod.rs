//! What the CLI prints and draws: tables beside the papers' numbers, and the data of plots
//! (figure.rs), drawn by the Python package.

pub mod cases;
pub mod figure;
pub mod longitudinal;
pub mod oscillator;
pub mod progress;
// Runs the FMUs through the in-process driver, which exists where it does.
#[cfg(all(
    target_os = "linux",
    any(target_arch = "x86_64", target_arch = "aarch64")
))]
pub mod stability;
pub mod transverse;
pub mod trimmed;
pub mod work_precision;
