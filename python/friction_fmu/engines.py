"""Runs one FMU or one SSP system in a co-simulation engine from PyPI: libcosim (libcosimpy) or
ecos (ecospy), with the engine's default fixed-step algorithm, reading Real variables at t = 0
and after every step.

SPEC (a dict): {"fmu": path} (one instance, named "m") or {"ssp": path}, with "step" (s) and
"steps" (how many); or, libcosim only, {"osp": a directory holding OspSystemStructure.xml, whose
algorithm sets the steps}, with "stop" (s) and "max_samples" (the most steps recorded); "values": {"instance.variable": value} set before initialization (int for Integer,
float for Real; for ecos on an SSP, the archive's parameter set instead); "record":
["instance.variable", ...]; "log": the engine's log level. Each function returns (whether every
step completed, the engine's time at the end, {"time": array, variable: array}).

libcosim ends its process (std::terminate) on some FMU errors: tests/python/engine_run.py runs
these in a process of their own.
"""
import ctypes

import numpy as np


def run_libcosim(spec):
    from libcosimpy._internal import libcosimc, wrap_function
    from libcosimpy.CosimEnums import CosimVariableType
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel[spec.get("log", "WARNING")])
    if "osp" in spec:
        # the algorithm, its step sizes and the system from an OspSystemStructure.xml
        execution = CosimExecution.from_osp_config_file(spec["osp"])
        slaves = {s.name.decode(): s.index for s in execution.slave_infos()}
        # ECCO reads the power bond's inputs after every step, which libcosim allows only for
        # variables an observer exposes: without it the second step fails
        execution.add_observer(CosimObserver.create_last_value())
        target_ns, n = round(spec["stop"] * 1e9), spec["max_samples"]
    elif "ssp" in spec:
        step_ns = round(spec["step"] * 1e9)
        execution = CosimExecution.from_ssp_file(spec["ssp"], step_size=step_ns)
        slaves = {s.name.decode(): s.index for s in execution.slave_infos()}
        target_ns, n = spec["steps"] * step_ns, spec["steps"] + 1
    else:
        step_ns = round(spec["step"] * 1e9)
        target_ns, n = spec["steps"] * step_ns, spec["steps"] + 1
        execution = CosimExecution.from_step_size(step_ns)
        slaves = {"m": execution.add_local_slave(CosimLocalSlave(fmu_path=spec["fmu"], instance_name="m"))}
    variables = {
        name: {v.name.decode(): v for v in execution.slave_variables(index)} for name, index in slaves.items()
    }
    for key, value in spec.get("values", {}).items():
        instance, name = key.split(".", 1)
        var = variables[instance][name]
        setter = execution.integer_initial_value if isinstance(value, int) else execution.real_initial_value
        if not setter(slaves[instance], var.reference, value):
            raise RuntimeError(f"libcosim refused the initial value {key} = {value}")
    observer = CosimObserver.create_time_series()
    execution.add_observer(observer)
    for key in spec["record"]:
        instance, name = key.split(".", 1)
        observer.start_time_series(slaves[instance], variables[instance][name].reference, CosimVariableType.REAL)
    ok = execution.simulate_until(target_ns)
    end = execution.status().current_time / 1e9

    # libcosimpy 0.0.6's time_series_real_samples drops the last sample when read from step 0
    # (it trims by counting step numbers equal to 0): read them through the C function.
    samples = wrap_function(
        libcosimc(), "cosim_observer_slave_get_real_samples", ctypes.c_int64,
        [ctypes.POINTER(CosimObserver), ctypes.c_int, ctypes.c_uint32, ctypes.c_int64, ctypes.c_size_t,
         ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(ctypes.c_int64)])
    result = {}
    for key in spec["record"]:
        instance, name = key.split(".", 1)
        values, steps, times = (ctypes.c_double * n)(), (ctypes.c_int64 * n)(), (ctypes.c_int64 * n)()
        k = samples(observer.ptr(), slaves[instance], variables[instance][name].reference, 0, n, values, steps, times)
        result["time"] = np.array(times[:k]) / 1e9
        result[key] = np.array(values[:k])
    return ok, end, result


def run_ecos(spec):
    from ecospy import EcosLib, EcosSimulation, EcosSimulationStructure, SimulationListener

    EcosLib.set_log_level(spec.get("log", "warn"))
    values = {key.replace(".", "::", 1): value for key, value in spec.get("values", {}).items()}
    if "ssp" in spec:
        simulation = EcosSimulation(ssp_path=spec["ssp"], step_size=spec["step"])
        parameter_set = "initialValues"
        if values:
            raise ValueError("set values of an SSP system in its parameter set")
    else:
        structure = EcosSimulationStructure()
        structure.add_model("m", spec["fmu"])
        parameter_set = "values" if values else None
        if values:
            structure.add_parameter_set(parameter_set, values)
        simulation = EcosSimulation(structure=structure, step_size=spec["step"])
    names = [key.replace(".", "::", 1) for key in spec["record"]]
    rows = []

    class Recorder(SimulationListener):
        def post(self, info):
            rows.append([info.time] + [simulation.get_real(name) for name in names])

    simulation.add_listener("recorder", Recorder())
    ok = simulation.init(parameter_set=parameter_set)
    # The listener is called after every step, not after initialization.
    rows.insert(0, [simulation.get_time()] + [simulation.get_real(name) for name in names])
    # step(n), not step_until: ecos adds up its time in floating point and stops a step short.
    simulation.step(spec["steps"])
    end = simulation.get_time()
    simulation.terminate()
    simulation.free()
    table = np.array(rows)
    result = {"time": table[:, 0], **{key: table[:, i + 1] for i, key in enumerate(spec["record"])}}
    return bool(ok) and len(rows) == spec["steps"] + 1, end, result
