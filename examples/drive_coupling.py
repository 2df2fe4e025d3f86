#!/usr/bin/env python3
"""Coupling error of DriveTrain + TransverseFriction against the monolithic reference, for a few H.

The master is friction_fmu.couple (a Jacobi master on fmpy with a fixed communication step H,
inputs held or moved linearly with the partner's output derivatives); `python -m
friction_fmu.couple` runs one case and writes its CSV and plot. This prints the largest error of
the default case (motor switched on at rest, breakaway at ~8 ms, then sliding with a ~200 Hz
ringing, 0.04 s, no support vibration) against the monolithic reference (both models in one ODE,
tests/reference/drive/), held and with derivatives: first order in H, then second.

Run:    .venv/bin/python examples/drive_coupling.py   (after `friction-fmu build`; README: Python)
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import couple as master  # noqa: E402
from friction_fmu.coupling_error import coupling_error, reference, slope  # noqa: E402

FMU_DIR = ROOT / "fmu-out"
REFERENCE = ROOT / "tests" / "reference" / "drive" / "reference.csv"
STOP_TIME = master.STOP_TIME


def couple(step, derivatives, stop_time=STOP_TIME, friction=None, drive=None):
    """Rows (t, v_nut, x_nut, Fd, x) of the master on this checkout's FMUs, whatever the
    current directory."""
    return master.couple(step, derivatives, stop_time, friction, drive, fmu_dir=FMU_DIR)


def main():
    ref = reference(REFERENCE)
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
        print(f"order of the Fd error, {'with' if derivatives else 'without'} derivatives: "
              f"{slope(steps, fd_errors):.2f}")


if __name__ == "__main__":
    main()
