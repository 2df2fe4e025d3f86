"""The FMI 3.0 FMUs (fmu-out/fmi3/) in fmpy: the same core as the FMI 2.0 FMUs, so the same numbers.

- Every output of every model's and variant's default experiment equals the FMI 2.0 FMU's within
  1e-12 of its range (fmpy's own master for both standards).
- FMU states: taken, serialized, read back into another instance, set; the restored run goes on
  to the same bits.
- A step that cannot be completed returns fmi3Discard with lastSuccessfulTime where the instance
  is, which is where the step started.
- Variable communication steps and output derivatives give what the FMI 2.0 FMU gives.
- Switches are Int32, as in FMI 2.0; the messages name FMI 3.0's functions and states.
- An importer's intermediate-update callback is called at the end of each internal step inside a
  communication step; an input it sets there drives the model from that time on, exactly as a
  communication point there would.
"""
import ctypes
import pathlib

import fmpy
import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave, fmi3LogMessageCallback

from conftest import FMU_DIR, fmu_path

FMI3_DIR = FMU_DIR / "fmi3"
MODELS = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain"]
VARIANTS = sorted(p.stem for p in (FMU_DIR / "variants").glob("*.fmu"))


def fmi3_path(name, variant=False):
    path = FMI3_DIR / ("variants" if variant else "") / f"{name}.fmu"
    assert path.exists(), f"{path} is missing: run `friction-fmu build` first"
    return str(path)


def fmi2_path(name, variant=False):
    return str(FMU_DIR / "variants" / f"{name}.fmu") if variant else fmu_path(name)


def real_outputs(md):
    return [v.name for v in md.modelVariables if v.causality == "output" and v.type in ("Real", "Float64")]


@pytest.mark.parametrize("name,variant", [(m, False) for m in MODELS] + [(v, True) for v in VARIANTS])
def test_every_output_equals_the_fmi2_fmus(name, variant):
    two, three = fmi2_path(name, variant), fmi3_path(name, variant)
    md2, md3 = fmpy.read_model_description(two), fmpy.read_model_description(three)
    assert md3.fmiVersion == "3.0"
    assert md3.instantiationToken == md2.guid
    outputs = real_outputs(md2)
    assert outputs == real_outputs(md3)
    step, stop = float(md2.defaultExperiment.stepSize), float(md2.defaultExperiment.stopTime)
    runs = [fmpy.simulate_fmu(path, stop_time=stop, output_interval=step, output=outputs) for path in (two, three)]
    assert len(runs[0]) == len(runs[1]) == round(stop / step) + 1
    for output in outputs:
        want, got = runs[0][output], runs[1][output]
        scale = want.max() - want.min() or abs(want).max() or 1.0
        assert abs(got - want).max() <= 1e-12 * scale, f"{name}.{output}"


def item(md, switch, name):
    """The number of a switch's item, from the description that lists them ("(1 a, 2 b)")."""
    description = next(v.description for v in md.modelVariables if v.name == switch)
    listed = description[description.rindex("(") + 1:description.rindex(")")]
    return next(int(number) for number, label in (entry.split(" ", 1) for entry in listed.split(", "))
                if label == name)


class Slave3:
    """An FMU3Slave of an FMI 3.0 FMU of ours, with its log captured."""

    def __init__(self, name, instance_name="instance", intermediate_update=None):
        self.path = fmi3_path(name)
        self.md = fmpy.read_model_description(self.path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.messages = []
        self.fmu = FMU3Slave(
            guid=self.md.instantiationToken,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            unzipDirectory=fmpy.extract(self.path),
            instanceName=instance_name,
        )

        def log(environment, status, category, message):
            self.messages.append((status, message.decode("utf-8", errors="replace")))

        self.fmu.instantiate(logMessage=log, intermediateUpdate=intermediate_update)

    def initialize(self, **integers):
        for name, value in integers.items():
            self.fmu.setInt32([self.vr[name]], [value])
        self.fmu.enterInitializationMode(startTime=0.0)
        self.fmu.exitInitializationMode()

    def outputs(self):
        return self.fmu.getFloat64([v.valueReference for v in self.md.modelVariables if v.causality == "output"])

    def do_step(self, t, h):
        """fmi3DoStep called as C sees it: (status, lastSuccessfulTime), without fmpy's raise."""
        event, terminate, early = ctypes.c_bool(), ctypes.c_bool(), ctypes.c_bool()
        last = ctypes.c_double()
        function = self.fmu.dll.fmi3DoStep
        function.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_bool,
                             ctypes.POINTER(ctypes.c_bool), ctypes.POINTER(ctypes.c_bool),
                             ctypes.POINTER(ctypes.c_bool), ctypes.POINTER(ctypes.c_double)]
        function.restype = ctypes.c_int
        status = function(self.fmu.component, t, h, False, ctypes.byref(event), ctypes.byref(terminate),
                          ctypes.byref(early), ctypes.byref(last))
        assert not (event.value or early.value)
        return status, last.value

    def free(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


@pytest.mark.parametrize("name", MODELS)
def test_a_restored_state_goes_on_to_the_same_bits(name):
    h = float(Slave3(name, "probe").md.defaultExperiment.stepSize) / 4
    slave = Slave3(name)
    slave.initialize()
    for i in range(5):
        assert slave.do_step(i * h, h)[0] <= 1
    data = slave.fmu.serializeFMUState(slave.fmu.getFMUState())
    for i in range(5, 10):
        slave.do_step(i * h, h)
    want = slave.outputs()
    other = Slave3(name, "other")
    other.initialize()
    other.fmu.setFMUState(other.fmu.deserializeFMUState(data))
    for i in range(5, 10):
        assert other.do_step(i * h, h)[0] <= 1
    assert np.array_equal(np.array(other.outputs()).view(np.int64), np.array(want).view(np.int64))
    slave.free()
    other.free()


def test_a_discarded_step_gives_the_last_successful_time():
    """A contact so stiff that dopri5's step falls below its minimum in the first step: fmi3Discard,
    lastSuccessfulTime the start, the state StepDiscarded (another step is refused, naming it)."""
    slave = Slave3("TransverseFriction")
    slave.fmu.setFloat64([slave.vr["kt"]], [1e300])
    slave.fmu.enterInitializationMode(startTime=0.25)
    slave.fmu.exitInitializationMode()
    status, last = slave.do_step(0.25, 1e-3)
    assert status == 2, slave.messages[-1]
    assert last == 0.25
    assert "back at lastSuccessfulTime = 0.25" in slave.messages[-1][1]
    status, _ = slave.do_step(0.25, 1e-3)
    assert status == 3
    assert "fmi3DoStep is not allowed in state StepDiscarded: expected StepMode" in slave.messages[-1][1]
    slave.free()


@pytest.mark.parametrize("name", MODELS)
def test_variable_steps_and_output_derivatives_are_the_fmi2_fmus(name):
    from conftest import Slave

    two = Slave(name)
    two.fmu.setupExperiment(startTime=0.0)
    two.fmu.enterInitializationMode()
    two.fmu.exitInitializationMode()
    three = Slave3(name)
    three.initialize()
    md = three.md
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    steps = float(md.defaultExperiment.stepSize) * np.array([0.3, 1.0, 0.07, 2.0, 0.5])
    t = 0.0
    for h in steps:
        two.fmu.doStep(t, h)
        assert three.do_step(t, h) == (0, t + h)
        t += h
        assert three.fmu.getFloat64(outputs) == two.fmu.getReal(outputs)
        assert three.fmu.getFloat64([three.vr["time"]]) == [t]
    if md.coSimulation.maxOutputDerivativeOrder:
        reals = [v.valueReference for v in md.modelVariables if v.causality == "output"]
        assert three.fmu.getOutputDerivatives(reals, [1] * len(reals)) == \
            two.fmu.getRealOutputDerivatives(reals, [1] * len(reals))
    two.free()
    three.free()


def test_switches_are_int32_as_in_fmi2_and_refused_as_int64():
    """Switches are Int32 with their items in the description (docs/interoperability.md, FMI
    3.0: why not Enumerations); an Int64 setter names what it reached."""
    slave = Slave3("TransverseFriction")
    solver = slave.vr["solver"]
    variable = next(v for v in slave.md.modelVariables if v.name == "solver")
    assert variable.type == "Int32"
    assert "6 dop853" in variable.description
    slave.fmu.setInt32([solver], [6])
    slave.fmu.enterInitializationMode(startTime=0.0)
    assert slave.fmu.getInt32([solver]) == [6]
    with pytest.raises(FMICallException):
        slave.fmu.setFloat64([slave.vr["time"]], [1.0])
    assert "time is the independent variable: it can be read, not set" in slave.messages[-1][1]
    with pytest.raises(FMICallException):
        slave.fmu.setInt64([solver], [6])
    assert "fmi3SetInt64: value reference 2 is solver, not a Int64 variable" in slave.messages[-1][1]
    slave.fmu.freeInstance()


def test_what_these_fmus_do_not_offer_is_refused_with_a_message():
    slave = Slave3("DriveTrain")
    slave.initialize()
    for call, fragment in [
        (slave.fmu.enterEventMode, "fmi3EnterEventMode: not supported: this FMU has no event mode"),
        (slave.fmu.enterStepMode, "fmi3EnterStepMode: not needed"),
        (slave.fmu.enterConfigurationMode, "no structural parameters"),
    ]:
        with pytest.raises(FMICallException):
            call()
        assert fragment in slave.messages[-1][1], slave.messages[-1]
    slave.free()


@pytest.mark.parametrize("model", MODELS)
def test_ecos_runs_the_fmi3_fmus_as_fmpy_runs_the_fmi2_ones(model, tmp_path):
    """ecos imports FMI 3.0 co-simulation: each FMI 3.0 FMU's default experiment in ecos against
    fmpy's run of the FMI 2.0 FMU, every output within 1e-9 of its range (the bound of the FMI 2.0
    engine test; the two standards' runs are the same to 1e-12 above)."""
    from test_engines import run_engine

    md = fmpy.read_model_description(fmi3_path(model))
    step, stop = float(md.defaultExperiment.stepSize), float(md.defaultExperiment.stopTime)
    steps = round(stop / step)
    outputs = real_outputs(md)
    status, summary, result, log = run_engine(
        "ecos", {"fmu": fmi3_path(model), "step": step, "steps": steps, "record": [f"m.{o}" for o in outputs]},
        tmp_path)
    assert status == 0 and summary["ok"], log
    reference = fmpy.simulate_fmu(fmu_path(model), stop_time=stop, output_interval=step, output=outputs)
    assert len(result["time"]) == len(reference) == steps + 1
    for output in outputs:
        want = reference[output]
        scale = np.ptp(want) or np.max(np.abs(want)) or 1.0
        error = np.max(np.abs(result[f"m.{output}"] - want)) / scale
        assert error <= 1e-9, f"{model}.{output}: {error:.2e} of its range"


def test_inputs_set_at_the_internal_steps_drive_the_model_from_there():
    """LongitudinalFriction (dopri5) driven through vr_in, the base's velocity vc + va cos(2 pi f t)
    given by the importer, at communication steps of 3.7 vibration periods. With an intermediate-update callback that sets vr_in at every internal step, the
    run equals (to 1e-12 of FT's range) one without the callback whose communication points are
    the callback's times as well, setting vr_in there: the FMU calls back inside the step, at its
    own steps, and takes the input from that time on. Outputs read in the callback move."""
    seen = []

    def update(environment, time, set_requested, get_allowed, finished, can_return_early, early, early_time):
        assert set_requested and get_allowed and finished and not can_return_early
        seen.append((time, slave.fmu.getFloat64([slave.vr["FT"]])[0]))
        slave.fmu.setFloat64([slave.vr["vr_in"]], [velocity(time)])

    def start(instance):
        source = item(instance.md, "velocity_source", "input")
        instance.fmu.setInt32([instance.vr["velocity_source"]], [source])
        instance.fmu.setInt32([instance.vr["solver"]], [item(instance.md, "solver", "dopri5")])
        instance.fmu.enterInitializationMode(startTime=0.0)
        instance.fmu.setFloat64([instance.vr["vr_in"]], [velocity(0.0)])
        instance.fmu.exitInitializationMode()

    probe = Slave3("LongitudinalFriction", "probe")
    probe.fmu.enterInitializationMode(startTime=0.0)
    vc, va, f = probe.fmu.getFloat64([probe.vr[n] for n in ("vc", "va", "f")])
    probe.fmu.freeInstance()

    def velocity(t):
        return vc + va * np.cos(2 * np.pi * f * t)

    h = 3.7 / f
    slave = Slave3("LongitudinalFriction", intermediate_update=update)
    start(slave)
    points, outputs = [0.0], []
    for i in range(20):
        t = i * h
        slave.fmu.setFloat64([slave.vr["vr_in"]], [velocity(t)])
        before = len(seen)
        # The input scheme's watch for an unstable coupling counts each internal step as a
        # communication step and may warn here (docs/interoperability.md, "What the FMI 3.0
        # functions do"); nothing else may.
        status, last = slave.do_step(t, h)
        assert last == t + h and (status == 0 or "input_scheme" in slave.messages[-1][1]), slave.messages[-1:]
        inside = [time for time, _ in seen[before:]]
        assert all(t < time < t + h for time in inside)
        points += inside + [t + h]
        outputs.append(slave.fmu.getFloat64([slave.vr["FT"]])[0])
    assert len(seen) > 100, "few internal steps inside the communication steps"
    assert np.ptp([ft for _, ft in seen]) > 0
    slave.free()

    plain = Slave3("LongitudinalFriction", "plain")
    start(plain)
    want = []
    for t, end in zip(points, points[1:]):
        plain.fmu.setFloat64([plain.vr["vr_in"]], [velocity(t)])
        assert plain.do_step(t, end - t)[0] <= 1
        if any(abs(end - (i + 1) * h) < 1e-15 for i in range(20)):
            want.append(plain.fmu.getFloat64([plain.vr["FT"]])[0])
    plain.free()
    assert len(want) == len(outputs)
    scale = np.ptp(want)
    assert np.max(np.abs(np.array(outputs) - want)) <= 1e-12 * scale
