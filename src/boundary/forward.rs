//! The macro both standards' export macros ([`crate::export_fmi2`], [`crate::export_fmi3`]) use
//! for the functions that only forward their C arguments to the standard's `exports`: each
//! signature is said once, in the standard's own type names.

/// Defines, in a module `$module` that sees the types of `$ffi`, each `fn` given as an exported
/// C function of that name and signature that calls the function of the same name in
/// `$exports` with its arguments.
#[doc(hidden)]
#[macro_export]
macro_rules! forward_exports {
    (
        $module:ident, [$($exports:tt)*], [$($ffi:tt)*];
        $(fn $name:ident($($arg:ident: $ty:ty),* $(,)?) $(-> $ret:ty)?;)*
    ) => {
        #[allow(non_snake_case, clippy::too_many_arguments)]
        mod $module {
            use $($ffi)*::*;
            use $($exports)* as exports;
            $(
                #[no_mangle]
                pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
                    exports::$name($($arg),*)
                }
            )*
        }
    };
}
