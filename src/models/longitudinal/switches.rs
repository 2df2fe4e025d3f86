//! Scene L's switches as Rust enums, one per switch type of its table (how they are read and
//! checked: src/models/switch.rs).

use super::table;
use crate::models::switch::switch;

switch!(
    /// Scene L's friction law.
    LongitudinalLaw = table::LAW { Coulomb = "coulomb", Dahl = "dahl", LuGre = "lugre" }
);
switch!(
    /// Where scene L's sliding velocity comes from.
    VelocitySource = table::VELOCITY_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Where scene L's normal force comes from.
    NormalForceSource = table::NORMAL_FORCE_SOURCE { Weight = "weight", Input = "input" }
);
switch!(
    /// Scene L's initial state.
    LongitudinalInitialState = table::INITIAL { Rest = "rest", Periodic = "periodic" }
);
switch!(
    /// Scene L's integration scheme.
    LongitudinalSolver = table::SOLVER {
        Exponential = "exponential",
        Rk4 = "rk4",
        Dopri5 = "dopri5",
        Radau5 = "radau5",
        ClosedForm = "closed_form",
        Auto = "auto",
    }
);

/// Every enum above, for the test that holds them to the switch types of the tables
/// (src/models/mod.rs).
#[cfg(test)]
pub(crate) fn enums() -> Vec<(&'static str, Vec<&'static str>)> {
    use crate::models::switch::items;
    vec![
        items::<LongitudinalLaw>(),
        items::<VelocitySource>(),
        items::<NormalForceSource>(),
        items::<LongitudinalInitialState>(),
        items::<LongitudinalSolver>(),
    ]
}

#[cfg(test)]
mod tests {
    use super::LongitudinalLaw;
    use crate::error::Kind;
    use crate::models::longitudinal::table::{vr, TABLE};
    use crate::models::switch::Switch;
    use crate::variables::values::ValueSet;

    /// A number that names no item is refused with the items it could have been.
    #[test]
    fn a_number_that_names_no_item_is_refused() {
        let mut values = ValueSet::start(&TABLE);
        for (number, read) in [(2.0, Some(LongitudinalLaw::Dahl)), (0.0, None), (4.0, None)] {
            values.set(vr::LAW, number);
            let law = LongitudinalLaw::read(&values, vr::LAW);
            assert_eq!(law.as_ref().ok().copied(), read);
            if let Err(error) = law {
                assert_eq!(error.kind, Kind::Value { name: "law" });
                assert_eq!(error.expected, "one of 1 coulomb, 2 dahl, 3 lugre");
            }
        }
    }
}
