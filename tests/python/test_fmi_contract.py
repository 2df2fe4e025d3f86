"""The FMI 2.0 contract under bad input, for every model, through fmpy's low-level FMU2Slave:
every call in every state where the co-simulation state machine forbids it, unknown value
references, bad parameter values, wrong communication points and steps, FMU states of another
instance, truncated and corrupted serialized states, freeInstance twice or on NULL.

Each must give an error status and a logged message saying what was wrong, and leave the
process (and, for refused calls, the instance) as it was. Names, value references and ranges
come from each FMU's own modelDescription.xml, so the tests follow the variable tables.

Oracle for the legal states: FMI 2.0.4, section 4.2.4 (state machine of a co-simulation slave).
"""
import ctypes
import math
import pathlib
import struct
from ctypes import byref, c_size_t, c_void_p

import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2FMUstate, fmi2LastSuccessfulTime

from conftest import Slave, unzipped

MODELS = ["LongitudinalFriction", "TransverseFriction", "DryFrictionOscillator", "DriveTrain"]

I, IM, SC, SF, T, E = (
    "Instantiated",
    "InitializationMode",
    "StepComplete",
    "StepFailed",
    "Terminated",
    "Error",
)
STATES = [I, IM, SC, SF, T, E]
ALL = set(STATES)
READABLE = {IM, SC, SF, T, E}
WRITABLE = {I, IM, SC}
STATUS = {SC, SF, T}

# (function, states where the standard allows it). fmi2Terminate is also accepted in Error,
# where the standard leaves it open; fmi2CancelStep needs StepPending, which never occurs here
# (doStep is synchronous); the status queries need a step to ask about.
LEGAL = {
    "fmi2SetupExperiment": {I},
    "fmi2EnterInitializationMode": {I},
    "fmi2ExitInitializationMode": {IM},
    "fmi2Terminate": {SC, SF, E},
    "fmi2GetReal": READABLE,
    "fmi2GetInteger": READABLE,
    "fmi2GetBoolean": READABLE,
    "fmi2GetString": READABLE,
    "fmi2SetReal": WRITABLE,
    "fmi2SetInteger": WRITABLE,
    "fmi2SetBoolean": WRITABLE,
    "fmi2SetString": WRITABLE,
    "fmi2GetDirectionalDerivative": READABLE,
    "fmi2SetRealInputDerivatives": WRITABLE,
    "fmi2GetRealOutputDerivatives": {SC, SF, T, E},
    "fmi2DoStep": {SC},
    "fmi2CancelStep": set(),
    "fmi2GetStatus": STATUS,
    "fmi2GetRealStatus": STATUS,
    "fmi2GetIntegerStatus": STATUS,
    "fmi2GetBooleanStatus": STATUS,
    "fmi2GetStringStatus": STATUS,
    # fmi2SetDebugLogging, fmi2Reset, fmi2FreeInstance and the FMU-state functions are legal in
    # every state, so they have no wrong state to test.
}

# Parameters that make the first default-sized step fail (fmi2Discard, state StepFailed): a
# contact so stiff, or a force so large, that the adaptive solver's step falls below its minimum.
STEP_FAILS_WITH = {
    "LongitudinalFriction": {"law": "lugre", "sigma2": 1e300, "vc": 1e300},
    "TransverseFriction": {"kt": 1e300},
    "DryFrictionOscillator": {"P": 1e308},
    "DriveTrain": {"kt_m": 1e308},
}

PHASE_CODE = {state: code for code, state in enumerate(STATES)}


def variables(model, causality=None, type_=None):
    _, md = unzipped(model)
    return [
        v
        for v in md.modelVariables
        if (causality is None or v.causality == causality) and (type_ is None or v.type == type_)
    ]


def default_step(model):
    return float(unzipped(model)[1].defaultExperiment.stepSize)


def refused(slave, call, *fragments, status=3):
    """`call` raises with `status` (Error unless said) and logs a message with every fragment."""
    before = len(slave.messages)
    with pytest.raises(FMICallException) as error:
        call()
    assert error.value.status == status, slave.last_message()
    assert len(slave.messages) > before, "refused without a message"
    message = slave.last_message()
    for fragment in fragments:
        assert fragment in message, f"{fragment!r} not in {message!r}"
    return message


def checksum(data):
    """FNV-1a 64, the FMU's checksum of serialized states."""
    h = 0xCBF29CE484222325
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def serialized_layout(data):
    """Offset of the first number of a serialized state: magic (8), length (8), GUID length (4),
    GUID."""
    (guid_length,) = struct.unpack_from("<I", data, 16)
    return 20 + guid_length


def forge(data, index, value):
    """The serialized state with number `index` replaced and the checksum made to match, so that
    only the FMU's checks of the content stand between it and the instance."""
    data = bytearray(data)
    struct.pack_into("<d", data, serialized_layout(data) + 8 * index, value)
    struct.pack_into("<Q", data, len(data) - 8, checksum(data[:-8]))
    return bytes(data)


def in_state(model, state, name="instance"):
    """A new instance driven into `state`."""
    slave = Slave(model, name)
    if state == I:
        return slave
    if state == IM:
        slave.fmu.setupExperiment(startTime=0.0)
        slave.fmu.enterInitializationMode()
        return slave
    if state == SF:
        slave.initialize(**STEP_FAILS_WITH[model])
        refused(slave, lambda: slave.fmu.doStep(0.0, default_step(model)), "fmi2DoStep", status=2)
        return slave
    slave.initialize()
    slave.fmu.doStep(0.0, default_step(model))
    if state == T:
        slave.fmu.terminate()
    elif state == E:
        # Nothing a well-formed call does leads there on purpose (non-finite outputs, internal
        # errors), so restore an FMU state whose recorded phase is Error.
        state_ = slave.fmu.getFMUstate()
        data = forge(slave.fmu.serializeFMUstate(state_), 0, PHASE_CODE[E])
        slave.fmu.freeFMUstate(state_)
        forged = slave.fmu.deSerializeFMUstate(data)
        slave.fmu.setFMUstate(forged)
        slave.fmu.freeFMUstate(forged)
    return slave


def calls(slave, model):
    """One call of each function with a state-machine rule, with otherwise valid arguments."""
    fmu = slave.fmu
    real_parameter = variables(model, "parameter", "Real")[0].valueReference
    integer_parameter = next(
        v.valueReference for v in variables(model, "parameter") if v.type == "Integer"
    )
    output = variables(model, "output", "Real")[0].valueReference
    real_input = variables(model, "input", "Real")[0].valueReference
    return {
        "fmi2SetupExperiment": lambda: fmu.setupExperiment(startTime=0.0),
        "fmi2EnterInitializationMode": fmu.enterInitializationMode,
        "fmi2ExitInitializationMode": fmu.exitInitializationMode,
        "fmi2Terminate": fmu.terminate,
        "fmi2GetReal": lambda: fmu.getReal([output]),
        "fmi2GetInteger": lambda: fmu.getInteger([integer_parameter]),
        "fmi2GetBoolean": lambda: fmu.getBoolean([output]),
        "fmi2GetString": lambda: fmu.getString([output]),
        "fmi2SetReal": lambda: fmu.setReal([real_input], [0.0]),
        "fmi2SetInteger": lambda: fmu.setInteger([integer_parameter], [1]),
        "fmi2SetBoolean": lambda: fmu.setBoolean([output], [True]),
        "fmi2SetString": lambda: fmu.setString([output], ["x"]),
        "fmi2GetDirectionalDerivative": lambda: fmu.getDirectionalDerivative([output], [real_parameter], [1.0]),
        "fmi2SetRealInputDerivatives": lambda: fmu.setRealInputDerivatives([real_input], [1], [0.0]),
        "fmi2GetRealOutputDerivatives": lambda: fmu.getRealOutputDerivatives([output], [1]),
        "fmi2DoStep": lambda: fmu.doStep(0.0, default_step(model)),
        "fmi2CancelStep": fmu.cancelStep,
        "fmi2GetStatus": lambda: fmu.getStatus(0),
        "fmi2GetRealStatus": lambda: fmu.getRealStatus(2),
        "fmi2GetIntegerStatus": lambda: fmu.getIntegerStatus(0),
        "fmi2GetBooleanStatus": lambda: fmu.getBooleanStatus(3),
        "fmi2GetStringStatus": lambda: fmu.getStringStatus(1),
    }


@pytest.mark.parametrize("state", STATES)
@pytest.mark.parametrize("model", MODELS)
def test_every_call_in_a_wrong_state_is_refused_naming_function_and_state(model, state):
    slave = in_state(model, state)
    wrong = [f for f, legal in LEGAL.items() if state not in legal]
    assert wrong, "the table has no wrong call for this state"
    for function in wrong:
        # A refused call leaves the state as it was: every message names the same state.
        refused(slave, calls(slave, model)[function], function, f"not allowed in state {state}")
    slave.free()


def test_the_step_failed_recipes_really_fail_the_step():
    """in_state(StepFailed) relies on these: the status the master asks for is Discard."""
    for model in MODELS:
        slave = in_state(model, SF)
        assert slave.fmu.getStatus(0) == 2  # fmi2Discard: the last step did not complete
        assert slave.fmu.getRealStatus(2) == 0.0  # fmi2LastSuccessfulTime
        slave.free()


# Steps that fail part-way, after good ones: two_phase at 1 Hz creates energy in its sixth
# step (the stability matrix's case), and a drive velocity of 1e300 m/s, set after ten steps,
# is finite and accepted but beyond any step.
DISCARDED_PART_WAY = {
    "two_phase at 1 Hz": ({"f": 1.0, "initial": "sliding", "solver": "two_phase"}, 1e-3, None),
    "vd_in 1e300": ({"drive_source": "input"}, 1 / 60000, ("vd_in", 1e300, 10)),
}


@pytest.mark.parametrize("case", DISCARDED_PART_WAY)
def test_a_discarded_step_leaves_the_model_where_the_step_started(case):
    """Regression: after fmi2Discard the model stayed where the failed step stopped, so outputs
    read in StepFailed came from a model part-way through the step or from a non-finite state
    ("FF is NaN"). Oracle: the values read just before the step, at lastSuccessfulTime, for
    the outputs and their derivatives; a state taken in StepFailed is at that time too."""
    params, h, late_input = DISCARDED_PART_WAY[case]
    slave = Slave("TransverseFriction")
    slave.initialize(**params)
    fmu = slave.fmu
    outputs = [v.valueReference for v in variables("TransverseFriction", "output", "Real")]
    for i in range(20):
        if late_input and i == late_input[2]:
            fmu.setReal([slave.vr[late_input[0]]], [late_input[1]])
        before = fmu.getReal(outputs)
        rates = fmu.getRealOutputDerivatives(outputs, [1] * len(outputs))
        try:
            fmu.doStep(i * h, h)
        except FMICallException as error:
            assert error.status == 2, slave.last_message()  # fmi2Discard
            break
    else:
        pytest.fail("every step succeeded: the case no longer fails part-way")
    assert i > 0, "the first step failed: nothing to roll back to but the start"
    message = slave.last_message()
    assert fmu.getRealStatus(fmi2LastSuccessfulTime) == i * h
    assert fmu.getReal(outputs) == before
    assert fmu.getRealOutputDerivatives(outputs, [1] * len(outputs)) == rates
    # The state taken now restores into a fresh instance at that time, with those outputs.
    data = fmu.serializeFMUstate(fmu.getFMUstate())
    other = Slave("TransverseFriction", "other")
    other.initialize(**params)
    other.fmu.setFMUstate(other.fmu.deSerializeFMUstate(data))
    assert other.fmu.getReal(outputs) == before
    assert "back at lastSuccessfulTime" in message, message
    other.free()
    slave.free()


@pytest.mark.parametrize("model", MODELS)
def test_unknown_value_references_are_refused(model):
    slave = in_state(model, SC)
    unknown = max(v.valueReference for v in variables(model)) + 1
    fmu = slave.fmu
    for vr in (unknown, 2**32 - 1):
        for name, call in [
            ("fmi2GetReal", lambda: fmu.getReal([vr])),
            ("fmi2GetInteger", lambda: fmu.getInteger([vr])),
            ("fmi2GetBoolean", lambda: fmu.getBoolean([vr])),
            ("fmi2SetReal", lambda: fmu.setReal([vr], [1.0])),
            ("fmi2SetInteger", lambda: fmu.setInteger([vr], [1])),
        ]:
            refused(slave, call, name, f"unknown value reference {vr}", model)
    # A known reference among them does not make the call half-succeed: all or nothing.
    first_input = variables(model, "input", "Real")[0]
    before = fmu.getReal([first_input.valueReference])
    refused(slave, lambda: fmu.setReal([first_input.valueReference, unknown], [123.0, 1.0]), "unknown")
    assert fmu.getReal([first_input.valueReference]) == before
    slave.free()


def bad_values(variable):
    """Values a Real parameter must refuse, from its declared range (min/max in the XML)."""
    values = [math.nan, math.inf, -math.inf]
    low = None if variable.min is None else float(variable.min)
    high = None if variable.max is None else float(variable.max)
    if low is not None and math.isfinite(low):
        values += [-1e300] if low > -1e300 else []
        values += [low - max(abs(low), 1.0)]
        if 0 < low < 1e-300:
            values += [0.0, -0.0]  # "strictly positive"
    if high is not None and math.isfinite(high):
        values += [high + max(abs(high), 1.0), 1e300]
    return values


@pytest.mark.parametrize("model", MODELS)
def test_bad_parameter_values_are_refused_with_name_and_expectation(model):
    slave = Slave(model)
    for variable in variables(model, "parameter"):
        vr = variable.valueReference
        if variable.type == "Real":
            for value in bad_values(variable):
                refused(slave, lambda: slave.fmu.setReal([vr], [value]), "fmi2SetReal", variable.name, "expected")
        else:
            low, high = int(variable.min), int(variable.max)
            outside = [v for v in {low - 1, high + 1, -(2**31), 2**31 - 1} if not low <= v <= high]
            for value in outside:
                refused(slave, lambda: slave.fmu.setInteger([vr], [value]), "fmi2SetInteger", variable.name, "expected")
    # Nothing was stored: the instance initialises with its start values.
    slave.initialize()
    slave.fmu.doStep(0.0, default_step(model))
    slave.free()


@pytest.mark.parametrize("model", MODELS)
def test_wrong_communication_point_or_step_is_refused_and_the_instance_goes_on(model):
    slave = in_state(model, SC)
    h = default_step(model)
    fmu = slave.fmu
    refused(slave, lambda: fmu.doStep(0.0, h), "fmi2DoStep", "expected currentCommunicationPoint = ")
    refused(slave, lambda: fmu.doStep(h + 0.5, h), "fmi2DoStep", "but was")
    refused(slave, lambda: fmu.doStep(math.nan, h), "fmi2DoStep", "but was NaN")
    for step in (0.0, -0.0, -h, math.nan, math.inf, -math.inf):
        refused(slave, lambda: fmu.doStep(h, step), "fmi2DoStep", "communicationStepSize", "expected a finite step > 0")
    # Regression: Rust spells 1e300 out in 301 digits; messages give such numbers as 1e300.
    refused(slave, lambda: fmu.doStep(1e300, h), "fmi2DoStep", "but was 1e300")
    fmu.doStep(h, h)  # still usable
    slave.free()


@pytest.mark.parametrize("model", MODELS)
def test_the_master_clock_is_followed_not_the_sum_of_steps(model):
    """Regression: time was the sum of the steps, and a master computing t_i = t0 + i h, whose
    points round-off moves a hair from that sum at each step, was refused once the gap grew past
    1e-12 (after 1e5 steps). Here the master's clock gains 2e-13 s a step: each point is within
    the check's 1e-12 of where the last step ended, the sum of the steps drifts past it within
    100 steps."""
    slave = in_state(model, SC)
    h = default_step(model)
    for i in range(1, 300):
        slave.fmu.doStep(i * (h + 2e-13), h)
    # The last step ended where the master's clock put it, not at the sum of the steps.
    end = 299 * (h + 2e-13) + h
    assert abs(slave.fmu.getRealStatus(fmi2LastSuccessfulTime) - end) <= 4e-16 * end
    slave.free()


def test_the_communication_point_slack_is_relative_to_t():
    """docs/interoperability.md: a point is accepted within 1e-12 (1 + |t|) s of the FMU's t (plus
    4 ulps of the step), relative once t > 1 s, and the refusal says that slack."""
    for model in MODELS:
        t0 = 1e3
        h = default_step(model)
        slave = Slave(model)
        slave.initialize(start_time=t0)
        slack = 1e-12 * (1 + t0)
        refused(slave, lambda: slave.fmu.doStep(t0 + 1.2 * slack, h), "fmi2DoStep",
                "expected currentCommunicationPoint = 1000 (within 1.0e-9 s: 1e-12 (1 + |t|) and "
                "4 ulps of the step) but was")
        slave.fmu.doStep(t0 + 0.8 * slack, h)  # 8e-10 s off: taken, where 1e-12 s would not be
        slave.free()


def test_a_step_lost_to_the_round_off_of_t_is_refused():
    """Regression: at startTime 1e6 a step of 1e-11 s returned OK and time stood still."""
    for model in MODELS:
        slave = Slave(model)
        slave.initialize(start_time=1e6)
        refused(slave, lambda: slave.fmu.doStep(1e6, 1e-11), "fmi2DoStep", "does not move past t")
        slave.free()


def test_step_past_the_stop_time_is_refused():
    for model in MODELS:
        slave = Slave(model)
        h = default_step(model)
        slave.initialize(stop_time=h)
        refused(slave, lambda: slave.fmu.doStep(0.0, 2 * h), "fmi2DoStep", "stopTime")
        slave.fmu.doStep(0.0, h)
        slave.free()


@pytest.mark.parametrize("model", MODELS)
def test_fmu_state_of_another_instance_is_refused(model):
    a, b = in_state(model, SC, "a"), in_state(model, SC, "b")
    state_a = a.fmu.getFMUstate()
    not_ours = "not made by this instance"
    refused(b, lambda: b.fmu.setFMUstate(state_a), "fmi2SetFMUstate", not_ours)
    refused(b, lambda: b.fmu.freeFMUstate(state_a), "fmi2FreeFMUstate", not_ours)
    refused(b, lambda: b.fmu.serializeFMUstate(state_a), "fmi2SerializedFMUstateSize", not_ours)
    refused(
        b,
        lambda: b.fmu.fmi2SerializeFMUstate(b.fmu.component, state_a, ctypes.create_string_buffer(4096), 4096),
        "fmi2SerializeFMUstate",
        not_ours,
    )
    # fmi2GetFMUstate may overwrite a state, but only one of the same instance.
    slot = fmi2FMUstate(state_a.value)
    refused(b, lambda: b.fmu.fmi2GetFMUstate(b.fmu.component, byref(slot)), "fmi2GetFMUstate", "neither NULL nor a state of this instance")
    # A's state survived all that, and once freed it is refused by A itself.
    a.fmu.setFMUstate(state_a)
    stale = fmi2FMUstate(state_a.value)
    a.fmu.freeFMUstate(state_a)
    refused(a, lambda: a.fmu.setFMUstate(stale), "fmi2SetFMUstate", "or was freed")
    a.free()
    b.free()


def test_state_of_another_model_is_refused():
    a, b = in_state(MODELS[0], SC, "a"), in_state(MODELS[1], SC, "b")
    state = a.fmu.getFMUstate()
    data = a.fmu.serializeFMUstate(state)
    refused(b, lambda: b.fmu.setFMUstate(state), "fmi2SetFMUstate", "not made by this instance")
    refused(b, lambda: b.fmu.deSerializeFMUstate(data), "fmi2DeSerializeFMUstate", "another model")
    a.fmu.freeFMUstate(state)
    a.free()
    b.free()


@pytest.mark.parametrize("model", MODELS)
def test_truncated_or_corrupted_serialized_state_is_refused(model):
    slave = in_state(model, SC)
    state = slave.fmu.getFMUstate()
    data = slave.fmu.serializeFMUstate(state)
    slave.fmu.freeFMUstate(state)
    bad = {f"first {n} bytes": data[:n] for n in (1, 8, 12, 20, len(data) // 2, len(data) - 8, len(data) - 1)}
    bad["one byte more"] = data + b"\0"
    for i in range(0, len(data), max(1, len(data) // 24)):
        flipped = bytearray(data)
        flipped[i] ^= 0x10
        bad[f"bit flip at byte {i}"] = bytes(flipped)
    for what, corrupted in bad.items():
        message = refused(slave, lambda: slave.fmu.deSerializeFMUstate(corrupted), "fmi2DeSerializeFMUstate", "not valid")
        assert message, what
    # The intact bytes still load: the refusals above were about the bytes, not the instance.
    restored = slave.fmu.deSerializeFMUstate(data)
    slave.fmu.setFMUstate(restored)
    slave.fmu.freeFMUstate(restored)
    slave.free()


# Serializes a state, puts its bytes at the very end of a readable page followed by one that
# cannot be read, and deserializes them with a size 4096 bytes too large: reading past the data
# ends the process with SIGSEGV. Run in its own process, so that a crash fails this test only.
OVERSIZED = r"""
import ctypes, mmap, sys
from ctypes import byref, c_void_p
sys.path.insert(0, sys.argv[1])
from conftest import Slave
slave = Slave("LongitudinalFriction")
slave.initialize()
fmu = slave.fmu
data = fmu.serializeFMUstate(fmu.getFMUstate())
page = mmap.PAGESIZE
pages = mmap.mmap(-1, 2 * page)
libc = ctypes.CDLL(None, use_errno=True)
libc.mprotect.argtypes = [c_void_p, ctypes.c_size_t, ctypes.c_int]
base = ctypes.addressof(ctypes.c_char.from_buffer(pages))
PROT_NONE = 0
assert libc.mprotect(base + page, page, PROT_NONE) == 0, ctypes.get_errno()
pages[page - len(data):page] = data
state = c_void_p()
fmu.dll.fmi2DeSerializeFMUstate.argtypes = [c_void_p, c_void_p, ctypes.c_size_t, c_void_p]
status = fmu.dll.fmi2DeSerializeFMUstate(fmu.component, base + page - len(data), len(data) + page, byref(state))
print(status, slave.last_message())
"""


def test_a_size_larger_than_the_serialized_state_is_refused_without_reading_past_it():
    """Regression: fmi2DeSerializeFMUstate ran its checksum over `size` bytes, so a size larger
    than the data read past its end. Oracle: the data's own length, now in its header."""
    import subprocess
    import sys

    here = str(pathlib.Path(__file__).parent)
    run = subprocess.run([sys.executable, "-c", OVERSIZED, here], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, f"exit {run.returncode}: {run.stderr[-2000:]}"
    status, message = run.stdout.strip().split(" ", 1)
    assert status == "3", message  # fmi2Error
    assert "is not valid" in message and "bytes long" in message, message


@pytest.mark.parametrize("model", MODELS)
def test_corrupted_state_with_a_matching_checksum_is_refused(model):
    """Regressions: bytes whose checksum matches but whose content is bad once loaded a start
    time of -inf (the next doStep never returned) and NaN parameters (outputs NaN with OK)."""
    slave = in_state(model, SC)
    state = slave.fmu.getFMUstate()
    data = slave.fmu.serializeFMUstate(state)
    slave.fmu.freeFMUstate(state)
    # Numbers: phase, start time, stop time (NaN = none), time, last successful time, count.
    for index, value in [(0, 99.0), (1, -math.inf), (1, math.nan), (3, math.inf), (3, -1.0), (4, math.nan), (5, 3.0)]:
        refused(slave, lambda: slave.fmu.deSerializeFMUstate(forge(data, index, value)), "fmi2DeSerializeFMUstate", "not valid")
    for variable in variables(model, "parameter", "Real"):
        index = 6 + [v.name for v in variables(model)].index(variable.name)
        forged = slave.fmu.deSerializeFMUstate(forge(data, index, math.nan))
        refused(slave, lambda: slave.fmu.setFMUstate(forged), "fmi2SetFMUstate", variable.name, "expected a finite number")
        slave.fmu.freeFMUstate(forged)
    # Regression: start, time and last successful time all at -1e300 (in order, so the bytes
    # load) and the model's own clock left where it was: the next doStep never returned.
    far = forge(forge(forge(data, 1, -1e300), 3, -1e300), 4, -1e300)
    forged = slave.fmu.deSerializeFMUstate(far)
    refused(slave, lambda: slave.fmu.setFMUstate(forged), "fmi2SetFMUstate", "expected the same time")
    slave.fmu.freeFMUstate(forged)
    slave.fmu.doStep(default_step(model), default_step(model))
    slave.free()
    # Regression: a state of a new instance (no model yet) relabelled StepComplete was taken,
    # and the next doStep said fmi2ExitInitializationMode had not succeeded.
    fresh = in_state(model, I)
    state = fresh.fmu.getFMUstate()
    data = fresh.fmu.serializeFMUstate(state)
    forged = fresh.fmu.deSerializeFMUstate(forge(data, 0, PHASE_CODE[SC]))
    refused(fresh, lambda: fresh.fmu.setFMUstate(forged), "fmi2SetFMUstate", "StepComplete without a model state")
    for s in (state, forged):
        fresh.fmu.freeFMUstate(s)
    fresh.free()


@pytest.mark.parametrize("model", MODELS)
def test_outputs_that_cannot_be_evaluated_are_refused_not_returned_as_nan(model):
    """Regression: at startTime = 1.8e308 LongitudinalFriction's vr and TransverseFriction's FF
    were NaN, and fmi2GetReal returned them with fmi2OK. Finite values, or a refusal."""
    slave = Slave(model)
    slave.fmu.setupExperiment(startTime=1.7976931348623157e308)
    slave.fmu.enterInitializationMode()
    outputs = [v.valueReference for v in variables(model, "output", "Real")]
    for phase in (IM, SC):
        if phase == SC:
            slave.fmu.exitInitializationMode()
        try:
            values = slave.fmu.getReal(outputs)
        except FMICallException as error:
            assert error.status == 3
            assert "fmi2GetReal" in slave.last_message()
            assert "expected a finite value" in slave.last_message()
        else:
            assert all(math.isfinite(x) for x in values), (phase, values)
    slave.free()


def library(slave):
    """The FMU's shared library as fmpy loaded it, with the argument types we call it with."""
    dll = slave.fmu.dll
    dll.fmi2FreeInstance.argtypes = [c_void_p]
    dll.fmi2FreeInstance.restype = None
    dll.fmi2DoStep.argtypes = [c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    dll.fmi2GetReal.argtypes = [c_void_p, c_void_p, c_size_t, c_void_p]
    dll.fmi2Reset.argtypes = [c_void_p]
    return dll


@pytest.mark.parametrize("model", MODELS)
def test_free_instance_twice_or_on_null_is_harmless(model):
    keeper = Slave(model, "keeper")  # holds the library loaded while the other is freed by hand
    slave = in_state(model, SC)
    dll = library(slave)
    component = slave.fmu.component
    dll.fmi2FreeInstance(component)
    dll.fmi2FreeInstance(component)
    dll.fmi2FreeInstance(None)
    # Calls on the freed instance or on NULL are errors (no logger is left to tell).
    logged = len(slave.messages)
    vr = (ctypes.c_uint * 1)(variables(model, "output", "Real")[0].valueReference)
    value = (ctypes.c_double * 1)()
    for c in (component, None):
        assert dll.fmi2DoStep(c, 0.0, default_step(model), 1) == 3
        assert dll.fmi2GetReal(c, vr, 1, value) == 3
        assert dll.fmi2Reset(c) == 3
    assert len(slave.messages) == logged
    slave.fmu.freeLibrary()
    # The other instance never noticed.
    keeper.initialize()
    keeper.fmu.doStep(0.0, default_step(model))
    keeper.free()


GOVERNED_INPUTS = [  # (model, switch, input): the input is read only when the switch is `input`
    ("LongitudinalFriction", "velocity_source", "vr_in"),
    ("TransverseFriction", "drive_source", "vd_in"),
    ("DryFrictionOscillator", "force_source", "P_in"),
    ("DriveTrain", "voltage_source", "V_in"),
]


def set_real(slave, name, value):
    """fmi2SetReal's status (fmpy's setReal drops it)."""
    from fmpy.fmi2 import fmi2Real, fmi2ValueReference

    return slave.fmu.fmi2SetReal(slave.fmu.component, (fmi2ValueReference * 1)(slave.vr[name]), 1,
                                 (fmi2Real * 1)(value))


@pytest.mark.parametrize("model, switch, input_name", GOVERNED_INPUTS)
def test_an_input_the_configuration_does_not_read_is_never_set_silently(model, switch, input_name):
    """Set during initialization: fmi2ExitInitializationMode warns, naming the switch; set
    during the run: that fmi2SetReal warns, once per run. With the switch flipped: no warning."""
    slave = Slave(model)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    assert set_real(slave, input_name, 0.0) == 0
    assert slave.fmu.exitInitializationMode() == 1  # fmi2Warning
    assert f"{input_name} is set but not read" in slave.last_message()
    assert f"expected {switch} = input" in slave.last_message()
    slave.free()

    slave = Slave(model)
    slave.initialize()
    count = len(slave.messages)
    assert set_real(slave, input_name, 0.0) == 1
    assert slave.last_message().startswith(f"fmi2SetReal: {input_name} is set but not read")
    assert set_real(slave, input_name, 0.0) == 0
    assert len(slave.messages) == count + 1
    slave.free()

    slave = Slave(model)
    slave.fmu.setupExperiment(startTime=0.0)
    slave.fmu.enterInitializationMode()
    assert set_real(slave, input_name, 0.0) == 0
    slave.set(**{switch: "input"})  # the switch may come after its input
    assert slave.fmu.exitInitializationMode() == 0
    assert set_real(slave, input_name, 0.0) == 0
    assert slave.messages == []
    slave.free()
