//! The macro that exports the FMI 3.0 functions of a library that carries what a
//! [`crate::instance::library::Binary`] says.

/// Exports the 75 FMI 3.0 functions with their C names, for the library described by `$binary`
/// (a `&'static Binary`, [`crate::instance::library::Binary`]); each forwards to
/// [`super::exports`], fmi3InstantiateCoSimulation with `$binary`, the others through
/// [`crate::forward_exports`].
#[macro_export]
macro_rules! export_fmi3 {
    ($binary:expr) => {
        #[no_mangle]
        #[allow(clippy::too_many_arguments)]
        pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
            instance_name: $crate::fmi3::ffi::FmiString,
            instantiation_token: $crate::fmi3::ffi::FmiString,
            resource_path: $crate::fmi3::ffi::FmiString,
            visible: $crate::fmi3::ffi::Boolean,
            logging_on: $crate::fmi3::ffi::Boolean,
            event_mode_used: $crate::fmi3::ffi::Boolean,
            early_return_allowed: $crate::fmi3::ffi::Boolean,
            required_intermediate_variables: *const $crate::fmi3::ffi::ValueReference,
            n_required_intermediate_variables: usize,
            instance_environment: $crate::fmi3::ffi::InstanceEnvironment,
            log_message: Option<$crate::fmi3::ffi::LogMessageCallback>,
            intermediate_update: Option<$crate::fmi3::ffi::IntermediateUpdateCallback>,
        ) -> $crate::fmi3::ffi::FmiInstance {
            $crate::fmi3::exports::instantiate_co_simulation(
                $binary,
                instance_name,
                instantiation_token,
                resource_path,
                visible,
                logging_on,
                event_mode_used,
                early_return_allowed,
                required_intermediate_variables,
                n_required_intermediate_variables,
                instance_environment,
                log_message,
                intermediate_update,
            )
        }
        $crate::forward_exports! {
            fmi3_forwarded, [$crate::fmi3::exports], [$crate::fmi3::ffi];
            fn fmi3GetVersion() -> FmiString;
            fn fmi3SetDebugLogging(
                c: FmiInstance,
                logging_on: Boolean,
                n_categories: usize,
                categories: *const FmiString,
            ) -> Status;
            fn fmi3InstantiateModelExchange(
                instance_name: FmiString,
                instantiation_token: FmiString,
                resource_path: FmiString,
                visible: Boolean,
                logging_on: Boolean,
                environment: InstanceEnvironment,
                log_message: Option<LogMessageCallback>,
            ) -> FmiInstance;
            fn fmi3InstantiateScheduledExecution(
                instance_name: FmiString,
                instantiation_token: FmiString,
                resource_path: FmiString,
                visible: Boolean,
                logging_on: Boolean,
                environment: InstanceEnvironment,
                log_message: Option<LogMessageCallback>,
                clock_update: Option<ClockUpdateCallback>,
                lock_preemption: Option<LockPreemptionCallback>,
                unlock_preemption: Option<UnlockPreemptionCallback>,
            ) -> FmiInstance;
            fn fmi3FreeInstance(c: FmiInstance);
            fn fmi3EnterInitializationMode(
                c: FmiInstance,
                tolerance_defined: Boolean,
                tolerance: f64,
                start_time: f64,
                stop_time_defined: Boolean,
                stop_time: f64,
            ) -> Status;
            fn fmi3ExitInitializationMode(c: FmiInstance) -> Status;
            fn fmi3EnterEventMode(c: FmiInstance) -> Status;
            fn fmi3Terminate(c: FmiInstance) -> Status;
            fn fmi3Reset(c: FmiInstance) -> Status;
            fn fmi3GetBinary(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value_sizes: *mut usize,
                value: *mut BinaryValue,
                n_values: usize,
            ) -> Status;
            fn fmi3SetBinary(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value_sizes: *const usize,
                value: *const BinaryValue,
                n_values: usize,
            ) -> Status;
            fn fmi3GetClock(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut Clock,
            ) -> Status;
            fn fmi3SetClock(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const Clock,
            ) -> Status;
            fn fmi3GetNumberOfVariableDependencies(
                c: FmiInstance,
                value_reference: ValueReference,
                n_dependencies: *mut usize,
            ) -> Status;
            fn fmi3GetVariableDependencies(
                c: FmiInstance,
                dependent: ValueReference,
                element_indices_of_dependent: *mut usize,
                independents: *mut ValueReference,
                element_indices_of_independents: *mut usize,
                dependency_kinds: *mut DependencyKind,
                n_dependencies: usize,
            ) -> Status;
            fn fmi3GetFMUState(c: FmiInstance, state: *mut FmuState) -> Status;
            fn fmi3SetFMUState(c: FmiInstance, state: FmuState) -> Status;
            fn fmi3FreeFMUState(c: FmiInstance, state: *mut FmuState) -> Status;
            fn fmi3SerializedFMUStateSize(
                c: FmiInstance,
                state: FmuState,
                size: *mut usize,
            ) -> Status;
            fn fmi3SerializeFMUState(
                c: FmiInstance,
                state: FmuState,
                bytes: *mut Byte,
                size: usize,
            ) -> Status;
            fn fmi3DeserializeFMUState(
                c: FmiInstance,
                bytes: *const Byte,
                size: usize,
                state: *mut FmuState,
            ) -> Status;
            fn fmi3GetDirectionalDerivative(
                c: FmiInstance,
                unknowns: *const ValueReference,
                n_unknowns: usize,
                knowns: *const ValueReference,
                n_knowns: usize,
                seed: *const f64,
                n_seed: usize,
                sensitivity: *mut f64,
                n_sensitivity: usize,
            ) -> Status;
            fn fmi3GetAdjointDerivative(
                c: FmiInstance,
                unknowns: *const ValueReference,
                n_unknowns: usize,
                knowns: *const ValueReference,
                n_knowns: usize,
                seed: *const f64,
                n_seed: usize,
                sensitivity: *mut f64,
                n_sensitivity: usize,
            ) -> Status;
            fn fmi3EnterConfigurationMode(c: FmiInstance) -> Status;
            fn fmi3ExitConfigurationMode(c: FmiInstance) -> Status;
            fn fmi3GetIntervalDecimal(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                intervals: *mut f64,
                qualifiers: *mut IntervalQualifier,
            ) -> Status;
            fn fmi3GetIntervalFraction(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                counters: *mut u64,
                resolutions: *mut u64,
                qualifiers: *mut IntervalQualifier,
            ) -> Status;
            fn fmi3GetShiftDecimal(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                shifts: *mut f64,
            ) -> Status;
            fn fmi3GetShiftFraction(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                counters: *mut u64,
                resolutions: *mut u64,
            ) -> Status;
            fn fmi3SetIntervalDecimal(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                intervals: *const f64,
            ) -> Status;
            fn fmi3SetIntervalFraction(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                counters: *const u64,
                resolutions: *const u64,
            ) -> Status;
            fn fmi3SetShiftDecimal(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                shifts: *const f64,
            ) -> Status;
            fn fmi3SetShiftFraction(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                counters: *const u64,
                resolutions: *const u64,
            ) -> Status;
            fn fmi3EvaluateDiscreteStates(c: FmiInstance) -> Status;
            fn fmi3UpdateDiscreteStates(
                c: FmiInstance,
                discrete_states_need_update: *mut Boolean,
                terminate_simulation: *mut Boolean,
                nominals_changed: *mut Boolean,
                values_changed: *mut Boolean,
                next_event_time_defined: *mut Boolean,
                next_event_time: *mut f64,
            ) -> Status;
            fn fmi3EnterContinuousTimeMode(c: FmiInstance) -> Status;
            fn fmi3CompletedIntegratorStep(
                c: FmiInstance,
                no_set_fmu_state_prior_to_current_point: Boolean,
                enter_event_mode: *mut Boolean,
                terminate_simulation: *mut Boolean,
            ) -> Status;
            fn fmi3SetTime(c: FmiInstance, time: f64) -> Status;
            fn fmi3SetContinuousStates(c: FmiInstance, states: *const f64, n: usize) -> Status;
            fn fmi3GetContinuousStateDerivatives(
                c: FmiInstance,
                derivatives: *mut f64,
                n: usize,
            ) -> Status;
            fn fmi3GetEventIndicators(c: FmiInstance, indicators: *mut f64, n: usize) -> Status;
            fn fmi3GetContinuousStates(c: FmiInstance, states: *mut f64, n: usize) -> Status;
            fn fmi3GetNominalsOfContinuousStates(
                c: FmiInstance,
                nominals: *mut f64,
                n: usize,
            ) -> Status;
            fn fmi3GetNumberOfEventIndicators(c: FmiInstance, n: *mut usize) -> Status;
            fn fmi3GetNumberOfContinuousStates(c: FmiInstance, n: *mut usize) -> Status;
            fn fmi3EnterStepMode(c: FmiInstance) -> Status;
            fn fmi3GetOutputDerivatives(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                order: *const i32,
                value: *mut f64,
                n_values: usize,
            ) -> Status;
            fn fmi3DoStep(
                c: FmiInstance,
                current_communication_point: f64,
                communication_step_size: f64,
                no_set_fmu_state_prior_to_current_point: Boolean,
                event_handling_needed: *mut Boolean,
                terminate_simulation: *mut Boolean,
                early_return: *mut Boolean,
                last_successful_time: *mut f64,
            ) -> Status;
            fn fmi3ActivateModelPartition(
                c: FmiInstance,
                clock_reference: ValueReference,
                activation_time: f64,
            ) -> Status;
            fn fmi3GetFloat64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut f64,
                n_values: usize,
            ) -> Status;
            fn fmi3SetFloat64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const f64,
                n_values: usize,
            ) -> Status;
            fn fmi3GetInt32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut i32,
                n_values: usize,
            ) -> Status;
            fn fmi3SetInt32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const i32,
                n_values: usize,
            ) -> Status;
            fn fmi3GetInt64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut i64,
                n_values: usize,
            ) -> Status;
            fn fmi3SetInt64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const i64,
                n_values: usize,
            ) -> Status;
            fn fmi3GetFloat32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut f32,
                n_values: usize,
            ) -> Status;
            fn fmi3SetFloat32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const f32,
                n_values: usize,
            ) -> Status;
            fn fmi3GetInt8(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut i8,
                n_values: usize,
            ) -> Status;
            fn fmi3SetInt8(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const i8,
                n_values: usize,
            ) -> Status;
            fn fmi3GetUInt8(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut u8,
                n_values: usize,
            ) -> Status;
            fn fmi3SetUInt8(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const u8,
                n_values: usize,
            ) -> Status;
            fn fmi3GetInt16(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut i16,
                n_values: usize,
            ) -> Status;
            fn fmi3SetInt16(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const i16,
                n_values: usize,
            ) -> Status;
            fn fmi3GetUInt16(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut u16,
                n_values: usize,
            ) -> Status;
            fn fmi3SetUInt16(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const u16,
                n_values: usize,
            ) -> Status;
            fn fmi3GetUInt32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut u32,
                n_values: usize,
            ) -> Status;
            fn fmi3SetUInt32(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const u32,
                n_values: usize,
            ) -> Status;
            fn fmi3GetUInt64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut u64,
                n_values: usize,
            ) -> Status;
            fn fmi3SetUInt64(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const u64,
                n_values: usize,
            ) -> Status;
            fn fmi3GetBoolean(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut Boolean,
                n_values: usize,
            ) -> Status;
            fn fmi3SetBoolean(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const Boolean,
                n_values: usize,
            ) -> Status;
            fn fmi3GetString(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *mut FmiString,
                n_values: usize,
            ) -> Status;
            fn fmi3SetString(
                c: FmiInstance,
                vr: *const ValueReference,
                nvr: usize,
                value: *const FmiString,
                n_values: usize,
            ) -> Status;
        }
    };
}

#[cfg(feature = "exports")]
mod all {
    crate::export_fmi3!(&crate::instance::library::Binary::ALL);
}
