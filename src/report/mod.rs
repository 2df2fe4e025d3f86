//! What the CLI prints and draws: tables beside the papers' numbers, and plots.

pub mod cases;
pub mod longitudinal;
pub mod oscillator;
pub mod progress;
pub mod svg;
pub mod transverse;
pub mod work_precision;
