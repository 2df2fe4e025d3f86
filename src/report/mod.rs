//! What the CLI prints and draws: tables beside the papers' numbers, and plots.

pub mod longitudinal;
pub mod oscillator;
pub mod svg;
pub mod transverse;
