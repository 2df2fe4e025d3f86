"""The task every worker runs: one grid point, one simulation through fmpy's FMU2Slave (or one
run along given communication points, `run_series`, for a fit to a measured time series).

The FMU travels as an `FmuSource`: by path (the worker reads the file itself, which needs a
filesystem shared with the client) or as the bytes of the .fmu (works anywhere). A worker
extracts each FMU once, keeps its shared library loaded, and instantiates it once per point.
A refusal by the FMU (error, discard, fatal) becomes the row's status and message, and so does
an output without a finite summary (status error): a failed point never raises out of
`run_point`. A point the FMU ran but warned about (a periodic start that fell back to the
transient, say) has status warning and the FMU's words; rows with status ok or warning hold only
finite numbers.
"""
import ctypes
import hashlib
import itertools
import math
import os
import pathlib
import shutil
import tempfile
import threading
import time as clock
from dataclasses import dataclass
from multiprocessing import util

import fmpy
from fmpy.fmi2 import FMU2Slave

from . import switches

STATUS = ["ok", "warning", "discard", "error", "fatal", "pending"]
WARNING = STATUS.index("warning")
# The statuses of a point that ran to its stop time: its outputs are in the row.
RAN = ("ok", "warning")


@dataclass(frozen=True)
class FmuSource:
    """An FMU as a path or as bytes, named by the digest of its content."""

    digest: str
    path: str | None = None
    data: bytes | None = None

    @staticmethod
    def by_path(path):
        path = os.path.abspath(path)
        return FmuSource(_digest(pathlib.Path(path).read_bytes()), path=path)

    @staticmethod
    def by_bytes(path):
        data = pathlib.Path(path).read_bytes()
        return FmuSource(_digest(data), data=data)


def _digest(data):
    return hashlib.sha256(data).hexdigest()[:16]


class _Loaded:
    """An extracted FMU in this process: directory, model description, variables by name."""

    def __init__(self, source):
        self.directory = tempfile.mkdtemp(prefix=f"friction_fmu_{source.digest}_")
        # Removed when this process exits, by multiprocessing's finalizers: they run when a pool
        # worker exits as when the main process does, where atexit handlers do not run in a
        # worker (it leaves through os._exit).
        util.Finalize(self, shutil.rmtree, args=(self.directory, True), exitpriority=0)
        if source.data is not None:
            archive = os.path.join(self.directory, "model.fmu")
            pathlib.Path(archive).write_bytes(source.data)
        else:
            archive = source.path
        self.unzipdir = fmpy.extract(archive, unzipdir=os.path.join(self.directory, "x"))
        self.md = fmpy.read_model_description(self.unzipdir)
        self.variables = {v.name: v for v in self.md.modelVariables}
        self.starts = start_values(self.md)
        identifier = self.md.coSimulation.modelIdentifier
        # FMU2Slave.freeInstance unloads the library; this handle keeps it resident between
        # points so it is not reloaded for each one.
        self._anchor = ctypes.CDLL(os.path.join(
            self.unzipdir, "binaries", fmpy.platform, identifier + fmpy.sharedLibraryExtension))


_CACHE = {}
_CACHE_LOCK = threading.Lock()


def loaded(source):
    with _CACHE_LOCK:
        if source.digest not in _CACHE:
            _CACHE[source.digest] = _Loaded(source)
        return _CACHE[source.digest]


# fmpy's C logger proxy holds ONE Python logger for the whole process, so there is one, never
# freed, which hands each message to the instance it belongs to by its environment pointer.
_MESSAGES = {}
_ENVIRONMENTS = itertools.count(1)


def _log(environment, instance_name, status, category, message):
    messages = _MESSAGES.get(environment or 0)
    if messages is not None:
        messages.append((status, message.decode("utf-8", errors="replace")))


_LOGGER = None


def _callbacks(environment):
    global _LOGGER
    from fmpy import calloc, free
    from fmpy.fmi2 import (
        fmi2CallbackAllocateMemoryTYPE,
        fmi2CallbackFreeMemoryTYPE,
        fmi2CallbackFunctions,
        fmi2CallbackLoggerTYPE,
    )
    from fmpy.logging import addLoggerProxy

    if _LOGGER is None:
        _LOGGER = fmi2CallbackLoggerTYPE(_log)
    callbacks = fmi2CallbackFunctions()
    callbacks.logger = _LOGGER
    callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
    callbacks.componentEnvironment = ctypes.c_void_p(environment)
    addLoggerProxy(ctypes.byref(callbacks))
    return callbacks


def _set(fmu, fmu_vars, name, value):
    var = fmu_vars.get(name)
    if var is None:
        raise ValueError(f"{name!r} is not a variable of this FMU")
    vr = [var.valueReference]
    if var.type == "Real":
        fmu.setReal(vr, [float(value)])
    elif var.type == "Boolean":
        fmu.setBoolean(vr, [str(value).lower() in ("1", "1.0", "true")])
    elif var.type == "Integer":
        if isinstance(value, str):
            items = switches.items(var) or {}
            if value not in items:
                raise ValueError(f"{name} = {value!r}: expected one of {sorted(items)}")
            value = items[value]
        fmu.setInteger(vr, [int(value)])
    else:
        raise ValueError(f"{name}: variables of type {var.type} cannot be set by a sweep")


def start_values(md):
    """The FMU's start value of every variable that has one, by name."""
    return {v.name: v.start for v in md.modelVariables if v.start is not None}


def experiment_times(md, plan, values):
    """(start, stop, step) of one point: the plan's, else the FMU's DefaultExperiment. `values`
    are what an N/PARAM time divides by: the point's values over the FMU's start values (so
    `50/f` with no f in the plan is 50 periods of the FMU's default f)."""
    experiment = md.defaultExperiment
    stop = plan.stop_time.at(values) if plan.stop_time else float(experiment.stopTime)
    step = plan.step.at(values) if plan.step else float(experiment.stepSize)
    return plan.start_time, stop, step


def _simulate(fmu, lib, plan, values, outputs):
    """Steps from start to stop like fmpy.simulate_fmu does (communication points
    start + n*step, the last one clipped to stop); returns times and sampled outputs."""
    start, stop, step = experiment_times(lib.md, plan, {**lib.starts, **values})
    refs = [lib.variables[o.variable].valueReference for o in outputs]
    fmu.setupExperiment(startTime=start, stopTime=stop)
    for name, value in values.items():
        _set(fmu, lib.variables, name, value)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    times, samples = [start], [fmu.getReal(refs)]
    t, n = start, 0
    while not (t > stop or _isclose(t, stop)):
        target = start + (n + 1) * step
        if target > stop and not _isclose(target, stop):
            target = stop
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=target - t)
        t, n = target, n + 1
        times.append(t)
        samples.append(fmu.getReal(refs))
    return times, samples


def _isclose(a, b):
    return math.isclose(a, b)  # the comparison fmpy.simulate_fmu makes of communication points


class NoSummary(Exception):
    """An output without a finite summary (a window holding no sample, a NaN sample): the
    point failed although the FMU did not."""


def collect(outputs, values, times, samples):
    """One finite number per output: the last sample, or the mean of the samples in the
    window; raises NoSummary for an output that has none."""
    stop = times[-1]
    result = {}
    for k, output in enumerate(outputs):
        if output.window is None:
            value = samples[-1][k]
        else:
            since = stop - output.window.at(values)
            chosen = [s[k] for t, s in zip(times, samples)
                      if t > since and not _isclose(t, since)]
            if not chosen:
                raise NoSummary(f"{output.column}: no communication point in the last "
                                f"{stop - since:g} s before t = {stop:g} s")
            value = sum(chosen) / len(chosen)
        if not math.isfinite(value):
            raise NoSummary(f"{output.column} = {value} at t = {stop:g} s: not a finite number")
        result[output.column] = value
    return result


def run_point(source, plan, point):
    """One row of the sweep: the point's values, its outputs (or its status and the FMU's
    message), and the wall and CPU time of the run (instantiate to free; a worker's one-time
    extraction of the FMU is not in them). The CPU time is this thread's: a Dask worker may run
    several points at once in one process, each on its own thread, and the FMU steps on the
    calling thread."""
    values = {**plan.fixed, **point.values}

    def simulate(fmu, lib):
        times, samples = _simulate(fmu, lib, plan, values, plan.outputs)
        return collect(plan.outputs, {**lib.starts, **values}, times, samples)

    return _run(source, f"point{point.index}", {"point": point.index, **point.values}, simulate)


@dataclass(frozen=True)
class Series:
    """A run along given communication points: `times` (increasing), the values of inputs at
    each of them (`inputs`, name -> list; each set at the start of the step that follows),
    parameters and constant inputs (`fixed`), and the Real outputs sampled at every point."""

    times: tuple
    inputs: dict
    fixed: dict
    outputs: tuple


def run_series(source, series, index=0):
    """One run along `series`: a row with each output's samples (a list, one per time), or its
    status and the FMU's message, as `run_point` gives them."""

    def simulate(fmu, lib):
        return dict(zip(series.outputs, zip(*_simulate_series(fmu, lib, series))))

    return _run(source, f"run{index}", {"run": index}, simulate)


def _simulate_series(fmu, lib, series):
    times = series.times
    refs = [lib.variables[name].valueReference for name in series.outputs]
    fmu.setupExperiment(startTime=times[0], stopTime=times[-1])
    for name, value in series.fixed.items():
        _set(fmu, lib.variables, name, value)
    for name, values in series.inputs.items():
        _set(fmu, lib.variables, name, values[0])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    samples = [fmu.getReal(refs)]
    for k in range(1, len(times)):
        if k > 1:  # the first step's inputs went in before initialization
            for name, values in series.inputs.items():
                _set(fmu, lib.variables, name, values[k - 1])
        fmu.doStep(currentCommunicationPoint=times[k - 1],
                   communicationStepSize=times[k] - times[k - 1])
        samples.append(fmu.getReal(refs))
    for k, sample in enumerate(samples):
        for name, value in zip(series.outputs, sample):
            if not math.isfinite(value):
                raise NoSummary(f"{name} = {value} at t = {times[k]:g} s: not a finite number")
    return samples


def _run(source, instance_name, row, simulate):
    """Instantiates the FMU, runs `simulate(fmu, lib)` (a dict of results for the row) and
    frees it. A refusal by the FMU, or results that are no finite numbers, become the row's
    status and message; so does a warning the FMU gave. Adds the run's wall and CPU time."""
    environment = next(_ENVIRONMENTS)
    messages = _MESSAGES[environment] = []
    fmu = None
    began, cpu = clock.perf_counter(), clock.thread_time()
    try:
        lib = loaded(source)
        began, cpu = clock.perf_counter(), clock.thread_time()
        fmu = FMU2Slave(guid=lib.md.guid, unzipDirectory=lib.unzipdir,
                        modelIdentifier=lib.md.coSimulation.modelIdentifier,
                        instanceName=instance_name)
        fmu.instantiate(callbacks=_callbacks(environment))
        row.update(simulate(fmu, lib))
        warned = [text for status, text in messages if status == WARNING]
        row["status"], row["message"] = ("warning", " | ".join(warned)) if warned else ("ok", "")
    except NoSummary as error:  # the reason is ours: the FMU's warnings would not explain it
        row["status"], row["message"] = "error", str(error)
    except fmpy.fmi1.FMICallException as error:
        row["status"] = STATUS[error.status] if 0 <= error.status < len(STATUS) else "error"
        row["message"] = _explain(messages, error)
    except Exception as error:  # a bad plan (unknown variable, item) fails the point only
        row["status"], row["message"] = "error", _explain(messages, error)
    finally:
        if fmu is not None and getattr(fmu, "component", None) is not None:
            fmu.freeInstance()
        del _MESSAGES[environment]
    row["wall_time_s"] = clock.perf_counter() - began
    row["cpu_time_s"] = clock.thread_time() - cpu  # this thread's CPU time only
    return row


def _explain(messages, error):
    """The FMU's own words (its warnings and errors) when it gave any, else the exception."""
    said = [text for status, text in messages if status >= 1]
    return " | ".join(said) if said else str(error)
