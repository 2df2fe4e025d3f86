//! Scene O's switches as Rust enums, one per switch type of its table (how they are read and
//! checked: src/models/switch.rs).

use super::table;
use crate::models::switch::switch;

switch!(
    /// Scene O's friction law.
    OscillatorLaw = table::LAW {
        Linear = "linear",
        Trigonometric = "trigonometric",
        LinearStiction = "linear_stiction",
        TrigonometricStiction = "trigonometric_stiction",
        Exact = "exact",
        ExactStiction = "exact_stiction",
    }
);
switch!(
    /// Where scene O's external force comes from.
    ForceSource = table::FORCE_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Scene O's integration scheme.
    OscillatorSolver = table::SOLVER {
        Radau5 = "radau5",
        Dopri5 = "dopri5",
        Rk4 = "rk4",
        Piecewise = "piecewise",
    }
);
switch!(
    /// Scene O's initial state.
    OscillatorInitialState = table::INITIAL { Given = "given", Periodic = "periodic" }
);

/// Every enum above, for the test that holds them to the switch types of the tables
/// (src/models/mod.rs).
#[cfg(test)]
pub(crate) fn enums() -> Vec<(&'static str, Vec<&'static str>)> {
    use crate::models::switch::items;
    vec![
        items::<OscillatorLaw>(),
        items::<ForceSource>(),
        items::<OscillatorSolver>(),
        items::<OscillatorInitialState>(),
    ]
}
