"""Co-simulation of DriveTrain and TransverseFriction (examples/drive_coupling.py, Jacobi with a
fixed communication step H) against the monolithic reference of both models in one ODE
(tests/reference/drive/make_reference.py, scipy Radau at rtol 1e-11; its CSV is committed).

The case: motor switched on at rest, breakaway of the body at ~8 ms, then sliding with a ~200 Hz
ringing of the body on the drive spring, 0.04 s, no support vibration. Every time scale is
resolved by the steps used here, so the error is the coupling error: the FMUs' own integration
error is far below it (at H = 0.05 ms with derivatives the Fd error is still falling as H^2,
1.9e-5 N).

Measured (max over the communication points, H = 0.4, 0.2, 0.1 ms):
  held inputs:        Fd error 4.24e-2, 2.13e-2, 1.06e-2 N      slope 1.00
  first derivatives:  Fd error 1.75e-3, 3.63e-4, 8.11e-5 N      slope 2.22
                      v_nut error 6.3e-10, 1.4e-10, 3.1e-11 m/s  slope 2.16
"""
import math
import pathlib
import sys

import pytest
import fmpy
from fmpy.fmi1 import FMICallException

from conftest import Slave, fmu_path

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "examples"))
import drive_coupling  # noqa: E402

STEPS = [4e-4, 2e-4, 1e-4]


@pytest.fixture(scope="module")
def errors():
    """{derivatives: [(v_nut, Fd, x) errors for each H in STEPS]}."""
    ref = drive_coupling.reference()
    return {
        derivatives: [drive_coupling.coupling_error(drive_coupling.couple(h, derivatives), ref) for h in STEPS]
        for derivatives in (False, True)
    }


def test_coupled_run_matches_the_monolithic_reference_at_the_finest_step(errors):
    """Tolerance at H = 0.1 ms with first derivatives: |Fd - Fd_ref| <= 1.2e-4 N (1.2e-4 of
    FC = 0.978 N), |v_nut - v_nut_ref| <= 5e-11 m/s (1e-7 of the 0.5 mm/s), |x - x_ref| <= 1.5e-10 m.
    With held inputs the error is first order: Fd within 1.2e-2 N."""
    v_nut, fd, x = errors[True][-1]
    assert fd <= 1.2e-4, fd
    assert v_nut <= 5e-11, v_nut
    assert x <= 1.5e-10, x
    assert errors[False][-1][1] <= 1.2e-2, errors[False][-1]


def test_coupling_error_is_first_order_held_and_second_order_with_derivatives(errors):
    held = drive_coupling.slope(STEPS, [e[1] for e in errors[False]])
    linear = drive_coupling.slope(STEPS, [e[1] for e in errors[True]])
    linear_v = drive_coupling.slope(STEPS, [e[0] for e in errors[True]])
    assert 0.8 <= held <= 1.3, held
    assert 1.7 <= linear <= 2.4, linear
    assert 1.7 <= linear_v <= 2.4, linear_v


@pytest.mark.parametrize(
    "model, interpolates",
    [("TransverseFriction", True), ("DriveTrain", True), ("LongitudinalFriction", False), ("DryFrictionOscillator", False)],
)
def test_model_description_declares_what_the_functions_do(model, interpolates):
    cs = fmpy.read_model_description(fmu_path(model)).coSimulation
    assert cs.canInterpolateInputs == interpolates
    assert cs.maxOutputDerivativeOrder == (1 if interpolates else 0)
    slave = Slave(model)
    slave.initialize()
    first_input = next(v for v in slave.md.modelVariables if v.causality == "input")
    first_output = next(v for v in slave.md.modelVariables if v.causality == "output")
    if interpolates:
        slave.fmu.setRealInputDerivatives([first_input.valueReference], [1], [0.5])
        slave.fmu.doStep(0.0, 1e-5)
    else:
        with pytest.raises(FMICallException):
            slave.fmu.setRealInputDerivatives([first_input.valueReference], [1], [0.5])
        assert "canInterpolateInputs = false" in slave.last_message()
        with pytest.raises(FMICallException):
            slave.fmu.getRealOutputDerivatives([first_output.valueReference], [1])
        assert "maxOutputDerivativeOrder = 0" in slave.last_message()
    slave.free()


def refused(slave, call, *fragments):
    with pytest.raises(FMICallException) as error:
        call()
    assert error.value.status == 3
    for fragment in fragments:
        assert fragment in slave.last_message(), slave.last_message()


def test_unsupported_orders_and_variables_are_refused_with_a_message():
    slave = Slave("TransverseFriction")
    slave.initialize(drive_source="input")
    vd_in, fd, kt = (slave.vr[n] for n in ("vd_in", "Fd", "kt"))
    fmu = slave.fmu
    refused(slave, lambda: fmu.setRealInputDerivatives([vd_in], [2], [0.1]), "order 2", "order 1")
    refused(slave, lambda: fmu.setRealInputDerivatives([fd], [1], [0.1]), "Fd is not an input")
    refused(slave, lambda: fmu.setRealInputDerivatives([kt], [1], [0.1]), "kt is not an input")
    refused(slave, lambda: fmu.setRealInputDerivatives([vd_in], [1], [math.nan]), "expected a finite number")
    refused(slave, lambda: fmu.getRealOutputDerivatives([fd], [2]), "order 2", "maxOutputDerivativeOrder = 1")
    refused(slave, lambda: fmu.getRealOutputDerivatives([vd_in], [1]), "vd_in is not an output")
    # maxOutputDerivativeOrder is the whole model's: every output has its derivative.
    outputs = [v.valueReference for v in slave.md.modelVariables if v.causality == "output"]
    assert all(math.isfinite(d) for d in fmu.getRealOutputDerivatives(outputs, [1] * len(outputs)))
    # Oracle for the accepted ones: body at rest and unloaded, so Fd' = kd vd_in, x' = 0.
    fmu.setReal([vd_in], [2e-4])
    kd = slave.get("kd")[0]
    assert fmu.getRealOutputDerivatives([fd, slave.vr["x"]], [1, 1]) == [kd * 2e-4, 0.0]
    slave.free()


@pytest.mark.parametrize("model, setup", [("DriveTrain", {}), ("TransverseFriction", {"drive_source": "input"})])
def test_a_restored_state_keeps_the_input_derivatives_set_for_the_next_step(model, setup):
    """Regression: fmi2SetFMUstate (and a deserialized state) dropped the derivatives set for the
    coming step, so a master that rolled back to retake the step got other physics (FMI 2.0,
    2.1.8: the restored state is the whole state). Oracle: the run that was not rolled back."""
    slave = Slave(model)
    slave.initialize(**setup)
    inputs = [v.valueReference for v in slave.md.modelVariables if v.causality == "input"]
    outputs = [v.valueReference for v in slave.md.modelVariables if v.causality == "output"]
    fmu = slave.fmu
    fmu.setRealInputDerivatives(inputs, [1] * len(inputs), [0.5 * (k + 1) for k in range(len(inputs))])
    state = fmu.getFMUstate()
    data = fmu.serializeFMUstate(state)
    fmu.doStep(0.0, 1e-4)
    first = fmu.getReal(outputs)
    fmu.setFMUstate(state)
    fmu.doStep(0.0, 1e-4)
    assert fmu.getReal(outputs) == first
    restored = fmu.deSerializeFMUstate(data)
    fmu.setFMUstate(restored)
    fmu.doStep(0.0, 1e-4)
    assert fmu.getReal(outputs) == first
    # And the derivative still applies to one step only: without it the step differs.
    fmu.setFMUstate(restored)
    fmu.setReal(inputs, fmu.getReal(inputs))
    fmu.doStep(0.0, 1e-4)
    assert fmu.getReal(outputs) != first
    for s in (state, restored):
        fmu.freeFMUstate(s)
    slave.free()
