"""input_scheme through fmpy, as a co-simulation engine uses it: DriveTrain and TransverseFriction
coupled by a Jacobi master that sets every input at every communication point and never a
derivative (what libcosim and ecos do), and LongitudinalFriction's two inputs.

- the past values the scheme reads are FMU state: a state got, or serialized, in the middle of a
  run and set again goes on to the same bits as the run that was not interrupted; so does a run
  after fmi2Reset, and a step retaken after fmi2Discard;
- variable communication steps: the scheme follows the values' times, and the error stays that of
  the mean step (against the monolithic reference);
- extrapolated is second order, corrected faster (the engine tests hold the shipped one, corrected);
- a derivative the master sets takes precedence: with derivatives, every scheme gives the same bits.
"""
import csv
import math
import subprocess
import sys

import pytest
from fmpy.fmi1 import FMICallException

from conftest import ROOT, Slave

from friction_fmu.coupling_error import reference, slope

REFERENCE = reference(ROOT / "tests" / "reference" / "drive" / "reference.csv")
STOP = 0.04


class System:
    """The drive-coupled case of DriveFriction.ssp, stepped by a Jacobi master."""

    def __init__(self, scheme):
        self.drive, self.friction = Slave("DriveTrain", "drive"), Slave("TransverseFriction", "friction")
        self.drive.initialize(input_scheme=scheme)
        self.friction.initialize(drive_source="input", va=0.0, initial="rest", vd_in=0.0, input_scheme=scheme)
        self.t = 0.0

    def outputs(self):
        return (self.t, self.drive.get("v_nut")[0], self.friction.get("Fd")[0])

    def step(self, h, derivatives=False):
        v_nut, fd = self.drive.get("v_nut")[0], self.friction.get("Fd")[0]
        self.friction.fmu.setReal([self.friction.vr["vd_in"]], [v_nut])
        self.drive.fmu.setReal([self.drive.vr["F_load"]], [fd])
        if derivatives:
            rates = (self.drive.fmu.getRealOutputDerivatives([self.drive.vr["v_nut"]], [1])[0],
                     self.friction.fmu.getRealOutputDerivatives([self.friction.vr["Fd"]], [1])[0])
            self.friction.fmu.setRealInputDerivatives([self.friction.vr["vd_in"]], [1], [rates[0]])
            self.drive.fmu.setRealInputDerivatives([self.drive.vr["F_load"]], [1], [rates[1]])
        self.drive.fmu.doStep(self.t, h)
        self.friction.fmu.doStep(self.t, h)
        self.t += h

    def run(self, steps, derivatives=False):
        rows = [self.outputs()]
        for h in steps:
            self.step(h, derivatives)
            rows.append(self.outputs())
        return rows

    def slaves(self):
        return (self.drive, self.friction)

    def free(self):
        for slave in self.slaves():
            slave.free()


def uniform(h, stop=STOP):
    return [h] * round(stop / h)


def fd_error(rows):
    return max(abs(fd - REFERENCE[round(t, 12)][2]) for t, _, fd in rows)


@pytest.mark.parametrize("scheme", ["extrapolated", "corrected"])
def test_a_state_set_again_goes_on_to_the_same_bits(scheme):
    steps = uniform(1e-4, 0.01)
    system = System(scheme)
    system.run(steps[:40])
    t = system.t
    states = [s.fmu.getFMUstate() for s in system.slaves()]
    serialized = [s.fmu.serializeFMUstate(state) for s, state in zip(system.slaves(), states)]
    uninterrupted = system.run(steps[40:])
    for s, state in zip(system.slaves(), states):
        s.fmu.setFMUstate(state)
    system.t = t
    assert system.run(steps[40:]) == uninterrupted
    for s, data in zip(system.slaves(), serialized):
        s.fmu.setFMUstate(s.fmu.deSerializeFMUstate(data))
    system.t = t
    assert system.run(steps[40:]) == uninterrupted
    system.free()


@pytest.mark.parametrize("scheme", ["extrapolated", "corrected"])
def test_a_reset_run_is_the_first_run(scheme):
    system = System(scheme)
    first = system.run(uniform(1e-4, 0.005))
    for slave in system.slaves():
        slave.fmu.reset()
    system.drive.initialize(input_scheme=scheme)
    system.friction.initialize(drive_source="input", va=0.0, initial="rest", vd_in=0.0, input_scheme=scheme)
    system.t = 0.0
    assert system.run(uniform(1e-4, 0.005)) == first
    system.free()


def test_a_step_retaken_after_a_discard_goes_on_as_if_none_had_failed():
    """LongitudinalFriction refuses a step over which the normal force would not stay > 0
    (fmi2Discard). The master sets the state it got before the step and retakes it: the inputs'
    history goes back with the rest."""
    def run(discard_at):
        slave = Slave("LongitudinalFriction")
        slave.initialize(velocity_source="input", normal_force_source="input", law="dahl",
                         input_scheme="corrected")
        vr_in, fn_in = slave.vr["vr_in"], slave.vr["FN_in"]
        h, out = 2e-6, []
        for k in range(30):
            t = k * h
            slave.fmu.setReal([vr_in, fn_in], [0.1 + 0.2 * math.sin(4e4 * t), 0.2 + 0.05 * math.cos(3e4 * t)])
            if k == discard_at:
                before = slave.fmu.getFMUstate()
                slave.fmu.setRealInputDerivatives([fn_in], [1], [-1e6])
                with pytest.raises(FMICallException) as failed:
                    slave.fmu.doStep(t, h)
                assert failed.value.status == 2, slave.last_message()  # fmi2Discard
                assert "FN_in > 0" in slave.last_message()
                slave.fmu.setFMUstate(before)
                # Set again without a derivative: the scheme moves it, as in the other run.
                slave.fmu.setReal([vr_in, fn_in], [0.1 + 0.2 * math.sin(4e4 * t), 0.2 + 0.05 * math.cos(3e4 * t)])
            slave.fmu.doStep(t, h)
            out.append(tuple(slave.get("FT", "W_diss", "z")))
        slave.free()
        return out

    assert run(discard_at=12) == run(discard_at=None)


def test_variable_steps_keep_the_error_of_the_steps():
    """Steps of 0.05 and 0.15 ms in turn: the scheme reads the values' times, so the error is
    between the uniform runs' at 0.1 and 0.2 ms (4.7e-5 and 2.4e-4 N; measured 1.4e-4 N), where
    holding the inputs is 1e-2 N off."""
    steps = [0.5e-4, 1.5e-4] * 200
    errors = {}
    for scheme in ("held", "corrected"):
        system = System(scheme)
        rows = system.run(steps)
        system.free()
        assert abs(rows[-1][0] - STOP) < 1e-12
        errors[scheme] = fd_error(rows)
    assert errors["corrected"] <= 2e-4 and errors["corrected"] <= errors["held"] / 50, errors


def test_extrapolated_is_second_order_and_corrected_faster():
    hs = [2e-4, 1e-4, 5e-5]
    orders = {}
    for scheme in ("extrapolated", "corrected"):
        errors = []
        for h in hs:
            system = System(scheme)
            errors.append(fd_error(system.run(uniform(h))))
            system.free()
        orders[scheme] = slope(hs, errors)
    assert 1.8 <= orders["extrapolated"] <= 2.2, orders
    assert orders["corrected"] >= 2.3, orders


def test_a_masters_derivatives_take_precedence_over_every_scheme():
    runs = []
    for scheme in ("held", "extrapolated", "corrected"):
        system = System(scheme)
        runs.append(system.run(uniform(1e-4, 0.01), derivatives=True))
        system.free()
    assert runs[0] == runs[1] == runs[2]


# -- stability -------------------------------------------------------------------------------

sys.path.insert(0, str(ROOT / "tests" / "reference" / "drive"))
import stability  # noqa: E402  (the linear analysis, tests/reference/drive/stability.py)

STIFF_SPRING = 9.2e7  # kd x 100: the bound falls from seconds to about 10 ms


def stiff_run(scheme, h, steps=60):
    """The body held on a spring 100 times stiffer: (Fd at the end, the FMUs' warnings)."""
    drive, friction = Slave("DriveTrain", "drive"), Slave("TransverseFriction", "friction")
    drive.initialize(input_scheme=scheme)
    friction.initialize(drive_source="input", va=0.0, initial="rest", vd_in=0.0, input_scheme=scheme,
                        kd=STIFF_SPRING, body="held")
    t = 0.0
    for _ in range(steps):
        v_nut, fd = drive.get("v_nut")[0], friction.get("Fd")[0]
        friction.fmu.setReal([friction.vr["vd_in"]], [v_nut])
        drive.fmu.setReal([drive.vr["F_load"]], [fd])
        drive.fmu.doStep(t, h)
        friction.fmu.doStep(t, h)
        t += h
    warnings = [text for slave in (drive, friction) for status, _, text in slave.messages if status == 1]
    fd = friction.get("Fd")[0]
    drive.free()
    friction.free()
    return fd, warnings


@pytest.mark.parametrize("scheme", ["held", "extrapolated", "corrected"])
def test_past_the_stability_bound_each_fmu_says_so_once_with_the_bound(scheme):
    bound = stability.largest_stable_step(STIFF_SPRING, scheme)
    fd, warnings = stiff_run(scheme, 0.8 * bound, steps=120)
    # Below the bound: the motor stalls against the spring (at about 894 N), quietly.
    assert warnings == [] and abs(fd - 893.5) < 0.02 * 893.5, (fd, warnings)
    _, warnings = stiff_run(scheme, 1.3 * bound)
    assert len(warnings) == 2, warnings  # one from each FMU, for its coupled input
    for text, name in zip(warnings, ("F_load", "vd_in")):
        assert f"input_scheme = {scheme}: {name} oscillates" in text, text
        estimate = float(text.split(f"largest stable step with {scheme} is ")[1].split(" s")[0])
        assert abs(estimate / bound - 1.0) < 0.25, (estimate, bound)


def test_the_error_plot_shows_each_scheme_in_libcosim_and_the_derivative_master(tmp_path):
    prefix = tmp_path / "schemes"
    done = subprocess.run([sys.executable, str(ROOT / "examples" / "input_schemes.py"), str(prefix)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert prefix.with_suffix(".png").stat().st_size > 10_000
    assert prefix.with_suffix(".svg").read_text().count("<path") > 4
    with open(prefix.with_suffix(".csv")) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 401
    largest = {name: max(float(r[name]) for r in rows) for name in rows[0] if name != "time"}
    assert largest["Fd error, libcosim, held"] > 1e-2
    assert 1e-4 < largest["Fd error, libcosim, extrapolated"] < 2e-4
    assert largest["Fd error, libcosim, corrected"] < 1e-4
    assert largest["Fd error, fmpy with output derivatives"] < 1e-4
