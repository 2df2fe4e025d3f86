//! The macro that exports the FMI 2.0 functions of a library that carries what a
//! [`crate::instance::library::Binary`] says.

/// Exports the 34 FMI 2.0 common and co-simulation functions with their C names, for the
/// library described by `$binary` (a `&'static Binary`, [`crate::instance::library::Binary`]);
/// each forwards to [`super::exports`], fmi2Instantiate with `$binary`, the others through
/// [`crate::forward_exports`].
#[macro_export]
macro_rules! export_fmi2 {
    ($binary:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Instantiate(
            instance_name: $crate::fmi2::ffi::FmiString,
            fmu_type: ::std::ffi::c_int,
            fmu_guid: $crate::fmi2::ffi::FmiString,
            fmu_resource_location: $crate::fmi2::ffi::FmiString,
            functions: *const $crate::fmi2::ffi::CallbackFunctions,
            visible: $crate::fmi2::ffi::Boolean,
            logging_on: $crate::fmi2::ffi::Boolean,
        ) -> $crate::fmi2::ffi::Component {
            $crate::fmi2::exports::instantiate(
                $binary,
                instance_name,
                fmu_type,
                fmu_guid,
                fmu_resource_location,
                functions,
                visible,
                logging_on,
            )
        }
        $crate::forward_exports! {
            fmi2_forwarded, [$crate::fmi2::exports], [$crate::fmi2::ffi];
            fn fmi2GetTypesPlatform() -> FmiString;
            fn fmi2GetVersion() -> FmiString;
            fn fmi2FreeInstance(c: Component);
            fn fmi2SetDebugLogging(
                c: Component,
                logging_on: Boolean,
                n_categories: usize,
                categories: *const FmiString,
            ) -> Status;
            fn fmi2SetupExperiment(
                c: Component,
                tolerance_defined: Boolean,
                tolerance: Real,
                start_time: Real,
                stop_time_defined: Boolean,
                stop_time: Real,
            ) -> Status;
            fn fmi2EnterInitializationMode(c: Component) -> Status;
            fn fmi2ExitInitializationMode(c: Component) -> Status;
            fn fmi2Terminate(c: Component) -> Status;
            fn fmi2Reset(c: Component) -> Status;
            fn fmi2GetReal(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut Real,
            ) -> Status;
            fn fmi2GetInteger(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut Integer,
            ) -> Status;
            fn fmi2GetBoolean(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut Boolean,
            ) -> Status;
            fn fmi2GetString(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut FmiString,
            ) -> Status;
            fn fmi2SetReal(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *const Real,
            ) -> Status;
            fn fmi2SetInteger(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *const Integer,
            ) -> Status;
            fn fmi2SetBoolean(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *const Boolean,
            ) -> Status;
            fn fmi2SetString(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                value: *const FmiString,
            ) -> Status;
            fn fmi2GetFMUstate(c: Component, state: *mut FmuState) -> Status;
            fn fmi2SetFMUstate(c: Component, state: FmuState) -> Status;
            fn fmi2FreeFMUstate(c: Component, state: *mut FmuState) -> Status;
            fn fmi2SerializedFMUstateSize(
                c: Component,
                state: FmuState,
                size: *mut usize,
            ) -> Status;
            fn fmi2SerializeFMUstate(
                c: Component,
                state: FmuState,
                bytes: *mut Byte,
                size: usize,
            ) -> Status;
            fn fmi2DeSerializeFMUstate(
                c: Component,
                bytes: *const Byte,
                size: usize,
                state: *mut FmuState,
            ) -> Status;
            fn fmi2GetDirectionalDerivative(
                c: Component,
                unknown: *const ValueReference,
                n_unknown: usize,
                known: *const ValueReference,
                n_known: usize,
                dv_known: *const Real,
                dv_unknown: *mut Real,
            ) -> Status;
            fn fmi2SetRealInputDerivatives(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                order: *const Integer,
                value: *const Real,
            ) -> Status;
            fn fmi2GetRealOutputDerivatives(
                c: Component,
                vr: *const ValueReference,
                nvr: usize,
                order: *const Integer,
                value: *mut Real,
            ) -> Status;
            fn fmi2DoStep(
                c: Component,
                current_communication_point: Real,
                communication_step_size: Real,
                no_set_prior_state: Boolean,
            ) -> Status;
            fn fmi2CancelStep(c: Component) -> Status;
            fn fmi2GetStatus(c: Component, kind: ::std::ffi::c_int, value: *mut Status) -> Status;
            fn fmi2GetRealStatus(c: Component, kind: ::std::ffi::c_int, value: *mut Real) -> Status;
            fn fmi2GetIntegerStatus(
                c: Component,
                kind: ::std::ffi::c_int,
                value: *mut Integer,
            ) -> Status;
            fn fmi2GetBooleanStatus(
                c: Component,
                kind: ::std::ffi::c_int,
                value: *mut Boolean,
            ) -> Status;
            fn fmi2GetStringStatus(
                c: Component,
                kind: ::std::ffi::c_int,
                value: *mut FmiString,
            ) -> Status;
        }
    };
}

#[cfg(feature = "exports")]
mod all {
    crate::export_fmi2!(&crate::instance::library::Binary::ALL);
}
