"""Shared fixtures: where the built FMUs are, and a small simulate helper.

The FMUs are packed by `friction-fmu build` into fmu-out/ before pytest runs (tests/run.sh does
both); a missing FMU is an error, never a skip.
"""
import os
import pathlib
import sys
import tempfile

import fmpy
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import switches  # noqa: E402
FMU_DIR = ROOT / "fmu-out"


def fmu_path(model_identifier):
    path = FMU_DIR / f"{model_identifier}.fmu"
    assert path.exists(), f"{path} is missing: run `friction-fmu build` first"
    return str(path)


def enum_value(model_identifier, variable, item):
    """The integer of a switch's item, read from the FMU's own modelDescription."""
    return switches.value(fmpy.read_model_description(fmu_path(model_identifier)), variable, item)


def simulate(model_identifier, start_values=None, stop_time=None, step=None, outputs=None, **kw):
    """fmpy.simulate_fmu with our FMU, returning the structured result array."""
    return fmpy.simulate_fmu(
        fmu_path(model_identifier),
        start_values=start_values or {},
        stop_time=stop_time,
        output_interval=step,
        output=outputs,
        **kw,
    )


def assert_default_experiment_matches_fmpy(fmu, run, bound):
    """Runs `run(step, stop)` (another importer's recording of `fmu`'s DefaultExperiment, a record
    array with a time column) and fmpy on the same points; every Real output within `bound` of its
    range."""
    md = fmpy.read_model_description(str(fmu))
    step, stop = float(md.defaultExperiment.stepSize), float(md.defaultExperiment.stopTime)
    outputs = [v.name for v in md.modelVariables if v.causality == "output" and v.type == "Real"]
    result = run(step, stop)
    reference = fmpy.simulate_fmu(str(fmu), stop_time=stop, output_interval=step, output=outputs)
    assert len(result) == len(reference) == round(stop / step) + 1
    assert max(abs(result["time"] - reference["time"])) <= 1e-9 * stop
    for output in outputs:
        want = reference[output]
        scale = want.max() - want.min() or abs(want).max() or 1.0
        error = abs(result[output] - want).max() / scale
        assert error <= bound, f"{fmu.stem}.{output}: {error:.2e} of its range"


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session", autouse=True)
def temporary_files_under_basetemp(tmp_path_factory):
    """Temporary files of the session (and of the processes it starts) go under pytest's base
    directory, which keeps only the last few sessions: fmpy.simulate_fmu removes the FMU it
    extracted only when the run succeeds, and many runs here are refused on purpose."""
    directory = str(tmp_path_factory.mktemp("tmp"))
    saved = tempfile.tempdir, os.environ.get("TMPDIR")
    tempfile.tempdir = directory
    os.environ["TMPDIR"] = directory
    yield
    tempfile.tempdir = saved[0]
    if saved[1] is None:
        del os.environ["TMPDIR"]
    else:
        os.environ["TMPDIR"] = saved[1]


_UNZIPPED = {}


def unzipped(model_identifier):
    """Extracts an FMU once per session and returns (directory, model description)."""
    if model_identifier not in _UNZIPPED:
        path = fmu_path(model_identifier)
        _UNZIPPED[model_identifier] = (fmpy.extract(path), fmpy.read_model_description(path))
    return _UNZIPPED[model_identifier]


# fmpy's native logger proxy keeps ONE logger in a global, replaced by every addLoggerProxy call,
# and shared with the callbacks fmpy.simulate_fmu uses. So there is one logger for the whole
# session, never freed, which routes messages to the instance they belong to by its environment
# pointer (and prints those of instances not created here, as fmpy's own logger does).
_LOGS = {}


def _log(environment, instance_name, status, category, message):
    text = message.decode("utf-8", errors="replace")
    messages = _LOGS.get(environment or 0)
    if messages is None:
        label = ["OK", "WARNING", "DISCARD", "ERROR", "FATAL", "PENDING"][status]
        print(f"[{label}] {text}")
    else:
        messages.append((status, category.decode("utf-8", errors="replace"), text))


def _make_logger():
    from fmpy.fmi2 import fmi2CallbackLoggerTYPE

    return fmi2CallbackLoggerTYPE(_log)


_LOGGER = _make_logger()


class Slave:
    """An FMU2Slave with its log captured, and value references looked up by name."""

    def __init__(self, model_identifier, instance_name="instance", guid=None, logging_on=False):
        from ctypes import byref, c_void_p
        from fmpy.fmi2 import (
            FMU2Slave,
            fmi2CallbackFunctions,
            fmi2CallbackAllocateMemoryTYPE,
            fmi2CallbackFreeMemoryTYPE,
        )
        from fmpy import calloc, free
        from fmpy.logging import addLoggerProxy

        directory, md = unzipped(model_identifier)
        self.md = md
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.messages = []
        self._environment = len(_LOGS) + 1
        _LOGS[self._environment] = self.messages

        self._callbacks = fmi2CallbackFunctions()
        self._callbacks.logger = _LOGGER
        self._callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self._callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self._callbacks.componentEnvironment = c_void_p(self._environment)
        addLoggerProxy(byref(self._callbacks))
        self.fmu = FMU2Slave(
            guid=guid or md.guid,
            unzipDirectory=directory,
            modelIdentifier=md.coSimulation.modelIdentifier,
            instanceName=instance_name,
        )
        self.fmu.instantiate(callbacks=self._callbacks, loggingOn=logging_on)

    def set(self, **values):
        for name, value in values.items():
            var = next(v for v in self.md.modelVariables if v.name == name)
            if var.type == "Real":
                self.fmu.setReal([self.vr[name]], [value])
            else:
                if isinstance(value, str):
                    value = enum_value(self.md.coSimulation.modelIdentifier, name, value)
                self.fmu.setInteger([self.vr[name]], [value])

    def get(self, *names):
        return self.fmu.getReal([self.vr[n] for n in names])

    def initialize(self, start_time=0.0, stop_time=None, **values):
        self.fmu.setupExperiment(startTime=start_time, stopTime=stop_time)
        self.set(**values)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()

    def last_message(self):
        return self.messages[-1][2] if self.messages else ""

    def free(self):
        self.fmu.freeInstance()
