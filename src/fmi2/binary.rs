//! The macro that exports the FMI 2.0 functions of a library that carries what a
//! [`crate::instance::library::Binary`] says.

/// Exports the 34 FMI 2.0 common and co-simulation functions with their C names, for the
/// library described by `$binary` (a `&'static Binary`, [`crate::instance::library::Binary`]); each forwards to [`super::exports`].
#[macro_export]
macro_rules! export_fmi2 {
    ($binary:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetTypesPlatform() -> $crate::fmi2::ffi::FmiString {
            $crate::fmi2::exports::fmi2GetTypesPlatform()
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetVersion() -> $crate::fmi2::ffi::FmiString {
            $crate::fmi2::exports::fmi2GetVersion()
        }
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
        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeInstance(c: $crate::fmi2::ffi::Component) {
            $crate::fmi2::exports::fmi2FreeInstance(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetDebugLogging(
            c: $crate::fmi2::ffi::Component,
            logging_on: $crate::fmi2::ffi::Boolean,
            n_categories: usize,
            categories: *const $crate::fmi2::ffi::FmiString,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetDebugLogging(c, logging_on, n_categories, categories)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetupExperiment(
            c: $crate::fmi2::ffi::Component,
            tolerance_defined: $crate::fmi2::ffi::Boolean,
            tolerance: $crate::fmi2::ffi::Real,
            start_time: $crate::fmi2::ffi::Real,
            stop_time_defined: $crate::fmi2::ffi::Boolean,
            stop_time: $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetupExperiment(
                c,
                tolerance_defined,
                tolerance,
                start_time,
                stop_time_defined,
                stop_time,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2EnterInitializationMode(
            c: $crate::fmi2::ffi::Component,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2EnterInitializationMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2ExitInitializationMode(
            c: $crate::fmi2::ffi::Component,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2ExitInitializationMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Terminate(
            c: $crate::fmi2::ffi::Component,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2Terminate(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2Reset(
            c: $crate::fmi2::ffi::Component,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2Reset(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetReal(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetReal(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetInteger(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi2::ffi::Integer,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetInteger(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBoolean(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi2::ffi::Boolean,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetBoolean(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetString(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi2::ffi::FmiString,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetString(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetReal(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetReal(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetInteger(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi2::ffi::Integer,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetInteger(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetBoolean(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi2::ffi::Boolean,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetBoolean(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetString(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi2::ffi::FmiString,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetString(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetFMUstate(
            c: $crate::fmi2::ffi::Component,
            state: *mut $crate::fmi2::ffi::FmuState,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetFMUstate(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetFMUstate(
            c: $crate::fmi2::ffi::Component,
            state: $crate::fmi2::ffi::FmuState,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetFMUstate(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2FreeFMUstate(
            c: $crate::fmi2::ffi::Component,
            state: *mut $crate::fmi2::ffi::FmuState,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2FreeFMUstate(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
            c: $crate::fmi2::ffi::Component,
            state: $crate::fmi2::ffi::FmuState,
            size: *mut usize,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SerializedFMUstateSize(c, state, size)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SerializeFMUstate(
            c: $crate::fmi2::ffi::Component,
            state: $crate::fmi2::ffi::FmuState,
            bytes: *mut $crate::fmi2::ffi::Byte,
            size: usize,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SerializeFMUstate(c, state, bytes, size)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
            c: $crate::fmi2::ffi::Component,
            bytes: *const $crate::fmi2::ffi::Byte,
            size: usize,
            state: *mut $crate::fmi2::ffi::FmuState,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2DeSerializeFMUstate(c, bytes, size, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
            c: $crate::fmi2::ffi::Component,
            unknown: *const $crate::fmi2::ffi::ValueReference,
            n_unknown: usize,
            known: *const $crate::fmi2::ffi::ValueReference,
            n_known: usize,
            dv_known: *const $crate::fmi2::ffi::Real,
            dv_unknown: *mut $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetDirectionalDerivative(
                c, unknown, n_unknown, known, n_known, dv_known, dv_unknown,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            order: *const $crate::fmi2::ffi::Integer,
            value: *const $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2SetRealInputDerivatives(c, vr, nvr, order, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
            c: $crate::fmi2::ffi::Component,
            vr: *const $crate::fmi2::ffi::ValueReference,
            nvr: usize,
            order: *const $crate::fmi2::ffi::Integer,
            value: *mut $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetRealOutputDerivatives(c, vr, nvr, order, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2DoStep(
            c: $crate::fmi2::ffi::Component,
            current_communication_point: $crate::fmi2::ffi::Real,
            communication_step_size: $crate::fmi2::ffi::Real,
            no_set_prior_state: $crate::fmi2::ffi::Boolean,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2DoStep(
                c,
                current_communication_point,
                communication_step_size,
                no_set_prior_state,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2CancelStep(
            c: $crate::fmi2::ffi::Component,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2CancelStep(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStatus(
            c: $crate::fmi2::ffi::Component,
            kind: ::std::ffi::c_int,
            value: *mut $crate::fmi2::ffi::Status,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetStatus(c, kind, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetRealStatus(
            c: $crate::fmi2::ffi::Component,
            kind: ::std::ffi::c_int,
            value: *mut $crate::fmi2::ffi::Real,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetRealStatus(c, kind, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetIntegerStatus(
            c: $crate::fmi2::ffi::Component,
            kind: ::std::ffi::c_int,
            value: *mut $crate::fmi2::ffi::Integer,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetIntegerStatus(c, kind, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetBooleanStatus(
            c: $crate::fmi2::ffi::Component,
            kind: ::std::ffi::c_int,
            value: *mut $crate::fmi2::ffi::Boolean,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetBooleanStatus(c, kind, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi2GetStringStatus(
            c: $crate::fmi2::ffi::Component,
            kind: ::std::ffi::c_int,
            value: *mut $crate::fmi2::ffi::FmiString,
        ) -> $crate::fmi2::ffi::Status {
            $crate::fmi2::exports::fmi2GetStringStatus(c, kind, value)
        }
    };
}

#[cfg(feature = "exports")]
mod all {
    crate::export_fmi2!(&crate::instance::library::Binary::ALL);
}
