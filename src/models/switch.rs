//! The models' switches as Rust enums: one per switch type of the variable tables, read from
//! its Integer once, with an error for a number that names no item, and matched exhaustively.
//!
//! Each enum lists its items by name; a test checks them against the table's type, so renaming
//! an item in one place and not the other fails the build's tests instead of falling back to a
//! default.

use crate::error::Error;
use crate::models::{
    drive::table as drive, longitudinal::table as longitudinal, oscillator::table as oscillator,
    transverse::table as transverse,
};
use crate::variables::declare;
use crate::variables::values::ValueSet;
use crate::variables::variable::EnumType;

/// A switch's enum: its variants in the order of the table's items (numbered from 1).
pub trait Switch: Copy + Sized + 'static {
    /// The switch type in the variable table.
    const TYPE: &'static EnumType;
    /// Every variant, in item order.
    const ALL: &'static [Self];

    /// The item's name, as the table spells it.
    fn name(self) -> &'static str;

    /// The switch's current value in `values`.
    fn read(values: &ValueSet, value_reference: u32) -> Result<Self, Error> {
        let number = values.integer(value_reference);
        let variable = values
            .table
            .variable(value_reference)
            .map_or("switch", |v| v.name);
        usize::try_from(number)
            .ok()
            .and_then(|k| k.checked_sub(1))
            .and_then(|k| Self::ALL.get(k).copied())
            .ok_or_else(|| {
                Error::value_found(
                    variable,
                    format!("{variable} = {number} names no item"),
                    format!("one of {}", Self::TYPE.listing()),
                )
            })
    }
}

macro_rules! switch {
    ($(#[$doc:meta])* $name:ident = $table:path { $($variant:ident = $item:literal),+ $(,)? }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $name {
            $($variant),+
        }

        impl Switch for $name {
            const TYPE: &'static EnumType = &$table;
            const ALL: &'static [Self] = &[$($name::$variant),+];

            fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $item),+
                }
            }
        }
    };
}

switch!(
    /// Scene L's friction law.
    LongitudinalLaw = longitudinal::LAW { Coulomb = "coulomb", Dahl = "dahl", LuGre = "lugre" }
);
switch!(
    /// Where scene L's sliding velocity comes from.
    VelocitySource = longitudinal::VELOCITY_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Where scene L's normal force comes from.
    NormalForceSource = longitudinal::NORMAL_FORCE_SOURCE { Weight = "weight", Input = "input" }
);
switch!(
    /// Scene L's initial state.
    LongitudinalInitialState = longitudinal::INITIAL { Rest = "rest", Periodic = "periodic" }
);
switch!(
    /// Scene L's integration scheme.
    LongitudinalSolver = longitudinal::SOLVER {
        Exponential = "exponential",
        Rk4 = "rk4",
        Dopri5 = "dopri5",
        Radau5 = "radau5",
        ClosedForm = "closed_form",
        Auto = "auto",
    }
);
switch!(
    /// Scene T's slip law.
    SlipLaw = transverse::SLIP_LAW { Split = "split", Total = "total" }
);
switch!(
    /// Scene T's integration scheme.
    TransverseSolver = transverse::SOLVER {
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
    DriveSource = transverse::DRIVE_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Whether scene T's body moves.
    Body = transverse::BODY { Free = "free", Held = "held" }
);
switch!(
    /// Scene T's initial state.
    InitialState = transverse::INITIAL {
        Rest = "rest",
        Sliding = "sliding",
        Periodic = "periodic",
    }
);
switch!(
    /// Scene O's friction law.
    OscillatorLaw = oscillator::LAW {
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
    ForceSource = oscillator::FORCE_SOURCE { Prescribed = "prescribed", Input = "input" }
);
switch!(
    /// Scene O's integration scheme.
    OscillatorSolver = oscillator::SOLVER {
        Radau5 = "radau5",
        Dopri5 = "dopri5",
        Rk4 = "rk4",
        Piecewise = "piecewise",
    }
);
switch!(
    /// Scene O's initial state.
    OscillatorInitialState = oscillator::INITIAL { Given = "given", Periodic = "periodic" }
);
switch!(
    /// Where the drive's armature voltage comes from.
    VoltageSource = drive::VOLTAGE_SOURCE { Parameter = "parameter", Input = "input" }
);
switch!(
    /// The drive's integration scheme.
    DriveSolver = drive::SOLVER { Exponential = "exponential" }
);
switch!(
    /// How an input moves over a step the master gives no derivative for (every model with
    /// inputs).
    InputScheme = declare::INPUT_SCHEME {
        Held = "held",
        Extrapolated = "extrapolated",
        Corrected = "corrected",
    }
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Kind;
    use crate::models::longitudinal::table::{vr, TABLE};
    use crate::models::MODELS;

    fn names<S: Switch>() -> (&'static str, Vec<&'static str>) {
        (S::TYPE.name, S::ALL.iter().map(|s| s.name()).collect())
    }

    /// Every switch type of every table has its enum, with the table's items in its order.
    #[test]
    fn every_switch_type_has_an_enum_with_its_items() {
        let enums = [
            names::<LongitudinalLaw>(),
            names::<VelocitySource>(),
            names::<NormalForceSource>(),
            names::<LongitudinalInitialState>(),
            names::<LongitudinalSolver>(),
            names::<SlipLaw>(),
            names::<TransverseSolver>(),
            names::<DriveSource>(),
            names::<Body>(),
            names::<InitialState>(),
            names::<OscillatorLaw>(),
            names::<ForceSource>(),
            names::<OscillatorSolver>(),
            names::<OscillatorInitialState>(),
            names::<VoltageSource>(),
            names::<DriveSolver>(),
            names::<InputScheme>(),
        ];
        // A type several tables share (InputScheme) is the same const in each.
        let mut types: Vec<&EnumType> = MODELS.iter().flat_map(|m| m.table.enum_types).collect();
        types.sort_by_key(|t| t.name);
        types.dedup_by_key(|t| t.name);
        assert_eq!(enums.len(), types.len());
        for enum_type in types {
            let items: Vec<&str> = enum_type.items.iter().map(|(name, _)| *name).collect();
            let found = enums.iter().find(|(name, _)| *name == enum_type.name);
            assert_eq!(
                found.map(|(_, variants)| variants),
                Some(&items),
                "{}",
                enum_type.name
            );
        }
    }

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
