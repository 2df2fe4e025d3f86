//! DriveTrain's switches as Rust enums, one per switch type of its table (how they are read and
//! checked: src/models/switch.rs).

use super::table;
use crate::models::switch::switch;

switch!(
    /// Where the drive's armature voltage comes from.
    VoltageSource = table::VOLTAGE_SOURCE { Parameter = "parameter", Input = "input" }
);
switch!(
    /// The drive's integration scheme.
    DriveSolver = table::SOLVER { Exponential = "exponential" }
);

/// Every enum above, for the test that holds them to the switch types of the tables
/// (src/models/mod.rs).
#[cfg(test)]
pub(crate) fn enums() -> Vec<(&'static str, Vec<&'static str>)> {
    use crate::models::switch::items;
    vec![items::<VoltageSource>(), items::<DriveSolver>()]
}
