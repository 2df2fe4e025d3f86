//! How a switch of a variable table becomes a Rust enum: read from its Integer once, with an
//! error for a number that names no item, and matched exhaustively. Each model declares its own
//! enums with `switch!` in its folder's `switches.rs` (the input scheme's, which every model
//! with inputs shares, is in src/models/input_scheme.rs).
//!
//! Each enum lists its items by name; a test (src/models/mod.rs) checks them against the table's
//! type, so renaming an item in one place and not the other fails the build's tests instead of
//! falling back to a default.

use crate::error::Error;
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

/// Declares a switch's enum: `Name = path::TO_ITS_TYPE { Variant = "item", ... }`, the variants
/// in the order of the type's items.
macro_rules! switch {
    ($(#[$doc:meta])* $name:ident = $table:path { $($variant:ident = $item:literal),+ $(,)? }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $name {
            $($variant),+
        }

        impl $crate::models::switch::Switch for $name {
            const TYPE: &'static $crate::variables::variable::EnumType = &$table;
            const ALL: &'static [Self] = &[$($name::$variant),+];

            fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $item),+
                }
            }
        }
    };
}

// Named by path from the models' folders (a macro_rules! is otherwise seen only below its
// definition in the module tree).
pub(crate) use switch;

/// A switch enum's type name and its items' names, in order: what the test that holds the enums to
/// the tables compares.
#[cfg(test)]
pub(crate) fn items<S: Switch>() -> (&'static str, Vec<&'static str>) {
    (S::TYPE.name, S::ALL.iter().map(|s| s.name()).collect())
}
