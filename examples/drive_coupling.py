#!/usr/bin/env python3
"""Co-simulation of DriveTrain and TransverseFriction with a small fixed-step master on fmpy.

The nut of the drive's lead screw is the far end of the friction model's drive spring:

    DriveTrain.v_nut      -> TransverseFriction.vd_in   (drive_source = input)
    TransverseFriction.Fd -> DriveTrain.F_load

Jacobi coupling with a fixed communication step H: at each communication point both FMUs'
outputs are read, handed to the other's inputs, and both step by H. With `derivatives=True` the
master also reads the outputs' first derivatives (fmi2GetRealOutputDerivatives) and passes them
with the inputs (fmi2SetRealInputDerivatives), so each FMU sees its input move linearly over the
step instead of held: the coupling error then falls as H^2 instead of H.

The case (also the test's, tests/python/test_drive_coupling.py): the motor is switched on at
t = 0 with everything at rest; the drive spring stretches until the body breaks away (~8 ms)
and then slides at the nut's speed with a ringing of the body on the spring (~200 Hz). No
support vibration (va = 0), so every time scale is resolved by H.

Run:    .venv/bin/python examples/drive_coupling.py   (after `friction-fmu build`; README: Python)
Prints the coupling error against the monolithic reference (tests/reference/drive/) for a few H.
"""
import csv
import math
import pathlib
import shutil
import sys

import fmpy
from fmpy.fmi2 import FMU2Slave

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import switches  # noqa: E402
FMU_DIR = ROOT / "fmu-out"
REFERENCE = ROOT / "tests" / "reference" / "drive" / "reference.csv"

# The coupled case: TransverseFriction's defaults without the vibration, driven from the nut.
FRICTION = {"drive_source": "input", "va": 0.0, "initial": "rest", "vd_in": 0.0}
DRIVE = {}
STOP_TIME = 0.04


class Fmu:
    """One FMU2Slave, with variables by name."""

    def __init__(self, model_identifier, instance_name):
        path = str(FMU_DIR / f"{model_identifier}.fmu")
        self.md = fmpy.read_model_description(path)
        self.directory = fmpy.extract(path)
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.slave = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.directory,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=instance_name,
        )
        self.slave.instantiate()

    def vr(self, name):
        return self.vars[name].valueReference

    def set(self, **values):
        for name, value in values.items():
            var = self.vars[name]
            if isinstance(value, str):
                self.slave.setInteger([var.valueReference], [switches.items(var)[value]])
            elif var.type == "Integer":
                self.slave.setInteger([var.valueReference], [int(value)])
            else:
                self.slave.setReal([var.valueReference], [float(value)])

    def start(self, **values):
        self.slave.setupExperiment(startTime=0.0)
        self.set(**values)
        self.slave.enterInitializationMode()
        self.slave.exitInitializationMode()

    def get(self, name):
        return self.slave.getReal([self.vr(name)])[0]

    def rate(self, name):
        return self.slave.getRealOutputDerivatives([self.vr(name)], [1])[0]

    def give(self, name, value, rate=None):
        self.slave.setReal([self.vr(name)], [value])
        if rate is not None:
            self.slave.setRealInputDerivatives([self.vr(name)], [1], [rate])

    def close(self):
        self.slave.terminate()
        self.slave.freeInstance()
        shutil.rmtree(self.directory, ignore_errors=True)


def couple(step, derivatives, stop_time=STOP_TIME, friction=None, drive=None):
    """Jacobi co-simulation with communication step `step`; returns rows
    (t, v_nut, x_nut, Fd, x) at every communication point, t = 0 included."""
    motor = Fmu("DriveTrain", "drive")
    body = Fmu("TransverseFriction", "friction")
    try:
        motor.start(**{**DRIVE, **(drive or {})})
        body.start(**{**FRICTION, **(friction or {})})
        rows = []
        steps = round(stop_time / step)
        for k in range(steps + 1):
            t = k * step
            # Jacobi: every output at t first, then every input, then both steps.
            v_nut = motor.get("v_nut")
            v_rate = motor.rate("v_nut") if derivatives else None
            body.give("vd_in", v_nut, v_rate)
            fd = body.get("Fd")  # after vd_in: Fd feeds through hd (vd_in - x')
            fd_rate = body.rate("Fd") if derivatives else None
            motor.give("F_load", fd, fd_rate)
            rows.append((t, v_nut, motor.get("x_nut"), fd, body.get("x")))
            if k == steps:
                break
            motor.slave.doStep(t, step)
            body.slave.doStep(t, step)
        return rows
    finally:
        motor.close()
        body.close()


def reference():
    """The monolithic reference: {t: (v_nut, x_nut, Fd, x)} on its sampling grid."""
    with open(REFERENCE) as f:
        return {
            round(float(r["t"]), 12): (float(r["v_nut"]), float(r["x_nut"]), float(r["Fd"]), float(r["x"]))
            for r in csv.DictReader(f)
        }


def coupling_error(rows, ref):
    """Largest difference from the reference over the communication points, per quantity:
    (v_nut in m/s, Fd in N, x in m)."""
    errors = [0.0, 0.0, 0.0]
    for t, v_nut, _, fd, x in rows:
        want = ref[round(t, 12)]
        for i, (got, exact) in enumerate([(v_nut, want[0]), (fd, want[2]), (x, want[3])]):
            errors[i] = max(errors[i], abs(got - exact))
    return errors


def slope(steps, errors):
    """Least-squares slope of log(error) against log(step)."""
    xs = [math.log(h) for h in steps]
    ys = [math.log(e) for e in errors]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    ref = reference()
    steps = [4e-4, 2e-4, 1e-4]
    # no pipes inside a cell: they would split the Markdown table's columns
    print("| H (s) | inputs | max abs v_nut err (m/s) | max abs Fd err (N) | max abs x err (m) |")
    print("|---|---|---|---|---|")
    for derivatives in (False, True):
        fd_errors = []
        for h in steps:
            e = coupling_error(couple(h, derivatives), ref)
            fd_errors.append(e[1])
            kind = "linear (derivatives)" if derivatives else "held"
            print(f"| {h:.0e} | {kind} | {e[0]:.2e} | {e[1]:.2e} | {e[2]:.2e} |")
        print(f"order of the Fd error, {'with' if derivatives else 'without'} derivatives: {slope(steps, fd_errors):.2f}")


if __name__ == "__main__":
    main()
