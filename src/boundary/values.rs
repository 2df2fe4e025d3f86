//! The getters' and setters' shared bodies: C arrays in, the instance's f64 values out and back.

use super::args::{slice, slice_mut};
use crate::instance::calls::{Call, Dialect};
use crate::instance::{handles, Status};
use crate::variables::variable::Kind;

pub fn is_real(kind: &Kind) -> bool {
    matches!(kind, Kind::Real { .. })
}

/// The Integers and the switches, which both standards' descriptions declare as integers
/// (docs/interoperability.md says why not as Enumerations).
pub fn is_integer_or_switch(kind: &Kind) -> bool {
    matches!(kind, Kind::Integer { .. } | Kind::Switch { .. })
}

/// For the types no variable of these FMUs has.
pub fn is_none(_: &Kind) -> bool {
    false
}

/// Which variables a getter or setter reaches, and its type's name for messages.
#[derive(Clone, Copy)]
pub struct Access {
    pub call: Call,
    pub accepts: fn(&Kind) -> bool,
    pub type_name: &'static str,
}

pub const fn access(call: Call, accepts: fn(&Kind) -> bool, type_name: &'static str) -> Access {
    Access {
        call,
        accepts,
        type_name,
    }
}

/// Reads `nvr` values into the C array `value`, each converted by `convert`.
///
/// # Safety
/// `vr` and `value` are NULL or arrays of `nvr` elements.
pub unsafe fn get_values<T>(
    handle: usize,
    dialect: &'static Dialect,
    access: Access,
    vr: *const u32,
    nvr: usize,
    value: *mut T,
    convert: fn(f64) -> T,
) -> Status {
    let Access {
        call,
        accepts,
        type_name,
    } = access;
    handles::with_instance(handle, dialect, |instance| {
        let (Some(vrs), Some(out)) = (slice(vr, nvr), slice_mut(value, nvr)) else {
            return instance.null_argument(call, "vr or value");
        };
        instance.get(
            call,
            vrs,
            &mut |i, x| out[i] = convert(x),
            accepts,
            type_name,
        )
    })
}

/// Writes `nvr` values from the C array `value`, each converted by `convert`.
///
/// # Safety
/// `vr` and `value` are NULL or arrays of `nvr` elements.
pub unsafe fn set_values<T: Copy>(
    handle: usize,
    dialect: &'static Dialect,
    access: Access,
    vr: *const u32,
    nvr: usize,
    value: *const T,
    convert: fn(T) -> f64,
) -> Status {
    let Access {
        call,
        accepts,
        type_name,
    } = access;
    handles::with_instance(handle, dialect, |instance| {
        let function = instance.function(call);
        let (Some(vrs), Some(values)) = (slice(vr, nvr), slice(value, nvr)) else {
            return instance.null_argument(call, "vr or value");
        };
        instance.trace(|| format!("{function}(vr = {vrs:?})"));
        instance.set(call, vrs, &|i| convert(values[i]), accepts, type_name)
    })
}
