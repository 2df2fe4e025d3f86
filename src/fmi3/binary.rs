//! The macro that exports the FMI 3.0 functions of a library that carries what a
//! [`crate::instance::library::Binary`] says.

/// Exports the 75 FMI 3.0 functions with their C names, for the library described by `$binary`
/// (a `&'static Binary`, [`crate::instance::library::Binary`]); each forwards to
/// [`super::exports`].
#[macro_export]
macro_rules! export_fmi3 {
    ($binary:expr) => {
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetVersion() -> $crate::fmi3::ffi::FmiString {
            $crate::fmi3::exports::fmi3GetVersion()
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetDebugLogging(
            c: $crate::fmi3::ffi::FmiInstance,
            logging_on: $crate::fmi3::ffi::Boolean,
            n_categories: usize,
            categories: *const $crate::fmi3::ffi::FmiString,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetDebugLogging(c, logging_on, n_categories, categories)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3InstantiateModelExchange(
            instance_name: $crate::fmi3::ffi::FmiString,
            instantiation_token: $crate::fmi3::ffi::FmiString,
            resource_path: $crate::fmi3::ffi::FmiString,
            visible: $crate::fmi3::ffi::Boolean,
            logging_on: $crate::fmi3::ffi::Boolean,
            environment: $crate::fmi3::ffi::InstanceEnvironment,
            log_message: Option<$crate::fmi3::ffi::LogMessageCallback>,
        ) -> $crate::fmi3::ffi::FmiInstance {
            $crate::fmi3::exports::fmi3InstantiateModelExchange(
                instance_name,
                instantiation_token,
                resource_path,
                visible,
                logging_on,
                environment,
                log_message,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
            instance_name: $crate::fmi3::ffi::FmiString,
            instantiation_token: $crate::fmi3::ffi::FmiString,
            resource_path: $crate::fmi3::ffi::FmiString,
            visible: $crate::fmi3::ffi::Boolean,
            logging_on: $crate::fmi3::ffi::Boolean,
            environment: $crate::fmi3::ffi::InstanceEnvironment,
            log_message: Option<$crate::fmi3::ffi::LogMessageCallback>,
            clock_update: Option<$crate::fmi3::ffi::ClockUpdateCallback>,
            lock_preemption: Option<$crate::fmi3::ffi::LockPreemptionCallback>,
            unlock_preemption: Option<$crate::fmi3::ffi::UnlockPreemptionCallback>,
        ) -> $crate::fmi3::ffi::FmiInstance {
            $crate::fmi3::exports::fmi3InstantiateScheduledExecution(
                instance_name,
                instantiation_token,
                resource_path,
                visible,
                logging_on,
                environment,
                log_message,
                clock_update,
                lock_preemption,
                unlock_preemption,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3FreeInstance(c: $crate::fmi3::ffi::FmiInstance) {
            $crate::fmi3::exports::fmi3FreeInstance(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EnterInitializationMode(
            c: $crate::fmi3::ffi::FmiInstance,
            tolerance_defined: $crate::fmi3::ffi::Boolean,
            tolerance: f64,
            start_time: f64,
            stop_time_defined: $crate::fmi3::ffi::Boolean,
            stop_time: f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EnterInitializationMode(
                c,
                tolerance_defined,
                tolerance,
                start_time,
                stop_time_defined,
                stop_time,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3ExitInitializationMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3ExitInitializationMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EnterEventMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EnterEventMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3Terminate(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3Terminate(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3Reset(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3Reset(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetBinary(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value_sizes: *mut usize,
            value: *mut $crate::fmi3::ffi::BinaryValue,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetBinary(c, vr, nvr, value_sizes, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetBinary(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value_sizes: *const usize,
            value: *const $crate::fmi3::ffi::BinaryValue,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetBinary(c, vr, nvr, value_sizes, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetClock(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi3::ffi::Clock,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetClock(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetClock(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi3::ffi::Clock,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetClock(c, vr, nvr, value)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
            c: $crate::fmi3::ffi::FmiInstance,
            value_reference: $crate::fmi3::ffi::ValueReference,
            n_dependencies: *mut usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetNumberOfVariableDependencies(
                c,
                value_reference,
                n_dependencies,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetVariableDependencies(
            c: $crate::fmi3::ffi::FmiInstance,
            dependent: $crate::fmi3::ffi::ValueReference,
            element_indices_of_dependent: *mut usize,
            independents: *mut $crate::fmi3::ffi::ValueReference,
            element_indices_of_independents: *mut usize,
            dependency_kinds: *mut $crate::fmi3::ffi::DependencyKind,
            n_dependencies: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetVariableDependencies(
                c,
                dependent,
                element_indices_of_dependent,
                independents,
                element_indices_of_independents,
                dependency_kinds,
                n_dependencies,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetFMUState(
            c: $crate::fmi3::ffi::FmiInstance,
            state: *mut $crate::fmi3::ffi::FmuState,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetFMUState(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetFMUState(
            c: $crate::fmi3::ffi::FmiInstance,
            state: $crate::fmi3::ffi::FmuState,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetFMUState(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3FreeFMUState(
            c: $crate::fmi3::ffi::FmiInstance,
            state: *mut $crate::fmi3::ffi::FmuState,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3FreeFMUState(c, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
            c: $crate::fmi3::ffi::FmiInstance,
            state: $crate::fmi3::ffi::FmuState,
            size: *mut usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SerializedFMUStateSize(c, state, size)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SerializeFMUState(
            c: $crate::fmi3::ffi::FmiInstance,
            state: $crate::fmi3::ffi::FmuState,
            bytes: *mut $crate::fmi3::ffi::Byte,
            size: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SerializeFMUState(c, state, bytes, size)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3DeserializeFMUState(
            c: $crate::fmi3::ffi::FmiInstance,
            bytes: *const $crate::fmi3::ffi::Byte,
            size: usize,
            state: *mut $crate::fmi3::ffi::FmuState,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3DeserializeFMUState(c, bytes, size, state)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
            c: $crate::fmi3::ffi::FmiInstance,
            unknowns: *const $crate::fmi3::ffi::ValueReference,
            n_unknowns: usize,
            knowns: *const $crate::fmi3::ffi::ValueReference,
            n_knowns: usize,
            seed: *const f64,
            n_seed: usize,
            sensitivity: *mut f64,
            n_sensitivity: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetDirectionalDerivative(
                c,
                unknowns,
                n_unknowns,
                knowns,
                n_knowns,
                seed,
                n_seed,
                sensitivity,
                n_sensitivity,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetAdjointDerivative(
            c: $crate::fmi3::ffi::FmiInstance,
            unknowns: *const $crate::fmi3::ffi::ValueReference,
            n_unknowns: usize,
            knowns: *const $crate::fmi3::ffi::ValueReference,
            n_knowns: usize,
            seed: *const f64,
            n_seed: usize,
            sensitivity: *mut f64,
            n_sensitivity: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetAdjointDerivative(
                c,
                unknowns,
                n_unknowns,
                knowns,
                n_knowns,
                seed,
                n_seed,
                sensitivity,
                n_sensitivity,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EnterConfigurationMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EnterConfigurationMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3ExitConfigurationMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3ExitConfigurationMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetIntervalDecimal(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            intervals: *mut f64,
            qualifiers: *mut $crate::fmi3::ffi::IntervalQualifier,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetIntervalDecimal(c, vr, nvr, intervals, qualifiers)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetIntervalFraction(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            counters: *mut u64,
            resolutions: *mut u64,
            qualifiers: *mut $crate::fmi3::ffi::IntervalQualifier,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetIntervalFraction(
                c,
                vr,
                nvr,
                counters,
                resolutions,
                qualifiers,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetShiftDecimal(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            shifts: *mut f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetShiftDecimal(c, vr, nvr, shifts)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetShiftFraction(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            counters: *mut u64,
            resolutions: *mut u64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetShiftFraction(c, vr, nvr, counters, resolutions)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetIntervalDecimal(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            intervals: *const f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetIntervalDecimal(c, vr, nvr, intervals)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetIntervalFraction(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            counters: *const u64,
            resolutions: *const u64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetIntervalFraction(c, vr, nvr, counters, resolutions)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetShiftDecimal(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            shifts: *const f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetShiftDecimal(c, vr, nvr, shifts)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetShiftFraction(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            counters: *const u64,
            resolutions: *const u64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetShiftFraction(c, vr, nvr, counters, resolutions)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EvaluateDiscreteStates(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
            c: $crate::fmi3::ffi::FmiInstance,
            discrete_states_need_update: *mut $crate::fmi3::ffi::Boolean,
            terminate_simulation: *mut $crate::fmi3::ffi::Boolean,
            nominals_changed: *mut $crate::fmi3::ffi::Boolean,
            values_changed: *mut $crate::fmi3::ffi::Boolean,
            next_event_time_defined: *mut $crate::fmi3::ffi::Boolean,
            next_event_time: *mut f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3UpdateDiscreteStates(
                c,
                discrete_states_need_update,
                terminate_simulation,
                nominals_changed,
                values_changed,
                next_event_time_defined,
                next_event_time,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EnterContinuousTimeMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
            c: $crate::fmi3::ffi::FmiInstance,
            no_set_fmu_state_prior_to_current_point: $crate::fmi3::ffi::Boolean,
            enter_event_mode: *mut $crate::fmi3::ffi::Boolean,
            terminate_simulation: *mut $crate::fmi3::ffi::Boolean,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3CompletedIntegratorStep(
                c,
                no_set_fmu_state_prior_to_current_point,
                enter_event_mode,
                terminate_simulation,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetTime(
            c: $crate::fmi3::ffi::FmiInstance,
            time: f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetTime(c, time)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetContinuousStates(
            c: $crate::fmi3::ffi::FmiInstance,
            states: *const f64,
            n: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetContinuousStates(c, states, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
            c: $crate::fmi3::ffi::FmiInstance,
            derivatives: *mut f64,
            n: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetContinuousStateDerivatives(c, derivatives, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetEventIndicators(
            c: $crate::fmi3::ffi::FmiInstance,
            indicators: *mut f64,
            n: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetEventIndicators(c, indicators, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetContinuousStates(
            c: $crate::fmi3::ffi::FmiInstance,
            states: *mut f64,
            n: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetContinuousStates(c, states, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
            c: $crate::fmi3::ffi::FmiInstance,
            nominals: *mut f64,
            n: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetNominalsOfContinuousStates(c, nominals, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(
            c: $crate::fmi3::ffi::FmiInstance,
            n: *mut usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetNumberOfEventIndicators(c, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(
            c: $crate::fmi3::ffi::FmiInstance,
            n: *mut usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetNumberOfContinuousStates(c, n)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3EnterStepMode(
            c: $crate::fmi3::ffi::FmiInstance,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3EnterStepMode(c)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetOutputDerivatives(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            order: *const i32,
            value: *mut f64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetOutputDerivatives(c, vr, nvr, order, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3DoStep(
            c: $crate::fmi3::ffi::FmiInstance,
            current_communication_point: f64,
            communication_step_size: f64,
            no_set_fmu_state_prior_to_current_point: $crate::fmi3::ffi::Boolean,
            event_handling_needed: *mut $crate::fmi3::ffi::Boolean,
            terminate_simulation: *mut $crate::fmi3::ffi::Boolean,
            early_return: *mut $crate::fmi3::ffi::Boolean,
            last_successful_time: *mut f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3DoStep(
                c,
                current_communication_point,
                communication_step_size,
                no_set_fmu_state_prior_to_current_point,
                event_handling_needed,
                terminate_simulation,
                early_return,
                last_successful_time,
            )
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3ActivateModelPartition(
            c: $crate::fmi3::ffi::FmiInstance,
            clock_reference: $crate::fmi3::ffi::ValueReference,
            activation_time: f64,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3ActivateModelPartition(c, clock_reference, activation_time)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetFloat64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut f64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetFloat64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetFloat64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const f64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetFloat64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetInt32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut i32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetInt32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetInt32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const i32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetInt32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetInt64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut i64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetInt64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetInt64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const i64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetInt64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetFloat32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut f32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetFloat32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetFloat32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const f32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetFloat32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetInt8(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut i8,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetInt8(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetInt8(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const i8,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetInt8(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetUInt8(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut u8,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetUInt8(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetUInt8(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const u8,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetUInt8(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetInt16(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut i16,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetInt16(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetInt16(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const i16,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetInt16(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetUInt16(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut u16,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetUInt16(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetUInt16(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const u16,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetUInt16(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetUInt32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut u32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetUInt32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetUInt32(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const u32,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetUInt32(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetUInt64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut u64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetUInt64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetUInt64(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const u64,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetUInt64(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetBoolean(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi3::ffi::Boolean,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetBoolean(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetBoolean(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi3::ffi::Boolean,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetBoolean(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3GetString(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *mut $crate::fmi3::ffi::FmiString,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3GetString(c, vr, nvr, value, n_values)
        }
        #[no_mangle]
        pub unsafe extern "C" fn fmi3SetString(
            c: $crate::fmi3::ffi::FmiInstance,
            vr: *const $crate::fmi3::ffi::ValueReference,
            nvr: usize,
            value: *const $crate::fmi3::ffi::FmiString,
            n_values: usize,
        ) -> $crate::fmi3::ffi::Status {
            $crate::fmi3::exports::fmi3SetString(c, vr, nvr, value, n_values)
        }
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
    };
}

#[cfg(feature = "exports")]
mod all {
    crate::export_fmi3!(&crate::instance::library::Binary::ALL);
}
