//! Scene T's switches as Rust enums, one per switch type of its table (how they are read and
//! checked: src/models/switch.rs).

use super::table;
use crate::models::switch::switch;

switch!(
    /// Scene T's slip law.
    SlipLaw = table::SLIP_LAW { Split = "split", Total = "total" }
);
switch!(
    /// Scene T's integration scheme.
    TransverseSolver = table::SOLVER {
        Dopri5 = "dopri5",
        Rk4 = "rk4",
        TwoPhase = "two_phase",
        Radau5 = "radau5",
        Exponential = "exponential",
        Dop853 = "dop853",
    }
);
switch!(
    /// Where scene T's drive velocity comes from.
    DriveSource = table::DRIVE_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Whether scene T's body moves.
    Body = table::BODY { Free = "free", Held = "held" }
);
switch!(
    /// Scene T's initial state.
    InitialState = table::INITIAL {
        Rest = "rest",
        Sliding = "sliding",
        Periodic = "periodic",
    }
);

/// Every enum above, for the test that holds them to the switch types of the tables
/// (src/models/mod.rs).
#[cfg(test)]
pub(crate) fn enums() -> Vec<(&'static str, Vec<&'static str>)> {
    use crate::models::switch::items;
    vec![
        items::<SlipLaw>(),
        items::<TransverseSolver>(),
        items::<DriveSource>(),
        items::<Body>(),
        items::<InitialState>(),
    ]
}
