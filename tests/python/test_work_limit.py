"""A communication step that would need millions of integration steps is refused, not run.

Oracle: the FMU's documented work limit (src/solve/mod.rs: at most 2e6 integration steps and 1e7
right-hand-side evaluations per doStep). In-range parameters can ask for absurd work (a terahertz vibration, a picogram body, a
1e8 rad/s forcing); without the limit doStep ran for minutes. With it, the step ends with
fmi2Discard, a message saying what to change, lastSuccessfulTime at the step's start, and the
instance still answers.
"""
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import fmi2LastSuccessfulTime

from conftest import Slave

CASES = [
    ("LongitudinalFriction", {"f": 1e12}, 8.3e-7),
    ("TransverseFriction", {"m": 1e-12}, 1 / 60000),
    ("DryFrictionOscillator", {"w": 1e8}, 0.0628),
]


@pytest.mark.parametrize("model, params, step", CASES)
def test_absurd_work_ends_in_discard_with_a_message(model, params, step):
    slave = Slave(model)
    slave.initialize(**params)
    with pytest.raises(FMICallException) as error:
        slave.fmu.doStep(0.0, step)
    assert error.value.status == 2  # fmi2Discard
    message = slave.last_message()
    assert "more than 2000000" in message and "steps" in message, message
    assert slave.fmu.getRealStatus(fmi2LastSuccessfulTime) == 0.0
    slave.free()
