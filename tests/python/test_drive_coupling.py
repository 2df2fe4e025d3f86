"""Co-simulation of DriveTrain and TransverseFriction (friction_fmu.couple, Jacobi with a fixed
communication step H) against the monolithic reference of both models in one ODE
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

The command `python -m friction_fmu.couple`: its CSV at the default case is the library's run to
the bit, --held and --derivatives give other runs (each input as the FMU saw it: held, or
extrapolated with the derivative passed), every bad argument is refused in one line with exit
status 2 before anything runs, an FMU's discard ends the run with exit status 1, its message and
the rows up to the last good point, and the PNG and SVG plots are written.
"""
import csv
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest
import fmpy
from fmpy.fmi1 import FMICallException

from conftest import FMU_DIR, ROOT, Slave, fmu_path

from friction_fmu.couple import columns, couple, main, run  # conftest puts python/ on the path
from friction_fmu.coupling_error import coupling_error, reference, slope

REFERENCE = ROOT / "tests" / "reference" / "drive" / "reference.csv"
STEPS = [4e-4, 2e-4, 1e-4]


@pytest.fixture(scope="module")
def errors():
    """{derivatives: [(v_nut, Fd, x) errors for each H in STEPS]}."""
    ref = reference(REFERENCE)
    return {
        derivatives: [coupling_error(couple(h, derivatives, fmu_dir=FMU_DIR), ref) for h in STEPS]
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
    held = slope(STEPS, [e[1] for e in errors[False]])
    linear = slope(STEPS, [e[1] for e in errors[True]])
    linear_v = slope(STEPS, [e[0] for e in errors[True]])
    assert 0.8 <= held <= 1.3, held
    assert 1.7 <= linear <= 2.4, linear
    assert 1.7 <= linear_v <= 2.4, linear_v


@pytest.mark.parametrize(
    "model, interpolates",
    [("TransverseFriction", True), ("DriveTrain", True), ("LongitudinalFriction", True), ("DryFrictionOscillator", False)],
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


@pytest.mark.parametrize("model, setup", [
    ("DriveTrain", {}),
    ("TransverseFriction", {"drive_source": "input"}),
    ("LongitudinalFriction", {"velocity_source": "input", "normal_force_source": "input"}),
])
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


# -- the command line: python -m friction_fmu.couple ----------------------------------------

def _csv(path):
    """(header, rows as the texts written)."""
    with open(path, newline="") as handle:
        header, *rows = list(csv.reader(handle))
    return header, rows


def _texts(rows, derivatives):
    return [[repr(row[c]) for c in columns(derivatives)] for row in rows]


@pytest.fixture(scope="module")
def default_command(tmp_path_factory):
    """The command at its defaults but --out, as a user runs it (its own process, from the
    checkout, so the default --fmu-dir fmu-out is ours); -> (process, prefix)."""
    prefix = tmp_path_factory.mktemp("couple") / "drive_friction"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    done = subprocess.run([sys.executable, "-m", "friction_fmu.couple", "--out", str(prefix)],
                          capture_output=True, text=True, env=env, cwd=ROOT, timeout=120)
    return done, prefix


def test_the_command_writes_the_library_run_to_the_bit(default_command):
    done, prefix = default_command
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    lines = done.stdout.splitlines()
    assert lines[0].startswith("coupling DriveTrain.v_nut -> TransverseFriction.vd_in")
    assert "400 steps to 0.04 s" in lines[0] and "with first derivatives" in lines[0]
    assert lines[1:] == [f"wrote {prefix}{suffix}" for suffix in (".csv", ".png", ".svg")]
    header, texts = _csv(f"{prefix}.csv")
    assert header == list(columns(True))
    assert "vd_in" in header and "FF" in header and "FFx" in header
    rows = run(fmu_dir=FMU_DIR)  # the defaults: step 1e-4, stop 0.04, derivatives
    assert texts == _texts(rows, True)
    # and it is the master the error tests above measure
    assert [(r["time"], r["v_nut"], r["x_nut"], r["Fd"], r["x"]) for r in rows] == couple(
        1e-4, True, fmu_dir=FMU_DIR)


def test_held_and_derivatives_are_different_runs(default_command, tmp_path, capsys):
    _, prefix = default_command
    assert main(["--held", "--fmu-dir", str(FMU_DIR), "--out", str(tmp_path / "held")]) == 0
    assert "inputs held" in capsys.readouterr().out
    header, held = _csv(tmp_path / "held.csv")
    assert header == list(columns(False))  # no derivatives passed, no derivative columns
    _, linear = _csv(f"{prefix}.csv")
    held = [dict(zip(header, map(float, row))) for row in held]
    linear = [dict(zip(columns(True), map(float, row))) for row in linear]
    assert len(held) == len(linear) == 401
    assert [r["time"] for r in held] == [r["time"] for r in linear]
    assert held[0]["Fd"] == linear[0]["Fd"] == 0.0  # both start at rest...
    assert max(abs(a["Fd"] - b["Fd"]) for a, b in zip(held, linear)) > 1e-3  # ...then part
    assert max(abs(a["v_nut"] - b["v_nut"]) for a, b in zip(held, linear)) > 1e-9
    # each input as its FMU saw it at the end of a step: held, or extrapolated over H
    h = 1e-4
    for before, now in zip(held, held[1:]):
        assert (now["vd_in"], now["F_load"]) == (before["v_nut"], before["Fd"])
    for before, now in zip(linear, linear[1:]):
        assert now["vd_in"] == before["v_nut"] + before["dv_nut_dt"] * h
        assert now["F_load"] == before["Fd"] + before["dFd_dt"] * h
    assert [(r["time"], r["v_nut"], r["Fd"]) for r in held] == [
        (t, v, fd) for t, v, _, fd, _ in couple(h, False, fmu_dir=FMU_DIR)]


def test_the_plots_are_written(default_command):
    _, prefix = default_command
    png = prefix.with_name(prefix.name + ".png").read_bytes()
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 20_000
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert width >= 600 and height >= 600
    svg = prefix.with_name(prefix.name + ".svg").read_text()
    assert "<svg" in svg and "<path" in svg and len(svg) > 20_000
    ET.fromstring(svg)  # well-formed
    for label in ("nut velocity v_nut (mm/s)", "drive force Fd (N)", "friction force FF (N)",
                  "time t (ms)"):
        assert label in svg  # matplotlib keeps each text as a comment beside its paths


REFUSED = [
    (["--set", "friction.nosuch=1"], "TransverseFriction has no variable 'nosuch'"),
    (["--set", "drive.kdd=1"], "DriveTrain has no variable 'kdd'"),
    (["--set", "gear.n=50"], "'gear' is not a coupled FMU"),
    (["--set", "friction.m"], "expected friction.NAME=VALUE or drive.NAME=VALUE"),
    (["--set", "friction.Fd=1"], "Fd is an output; --set takes parameters of TransverseFriction"),
    (["--set", "drive.V_in=2"], "V_in is an input; --set takes parameters of DriveTrain"),
    (["--set", "friction.vd_in=0"], "vd_in is the coupled input"),
    (["--set", "drive.F_load=0"], "F_load is the coupled input"),
    (["--set", "friction.initial=bogus"], "initial = 'bogus': expected one of rest (1)"),
    (["--set", "friction.initial=7"], "initial = 7: expected one of rest (1)"),
    (["--set", "friction.drive_source=prescribed"], "only with drive_source = input"),
    (["--set", "friction.m=nan"], "m = nan: expected a finite number"),
    (["--set", "drive.R=inf"], "R = inf: expected a finite number"),
    (["--set", "friction.m=-1"], "m = -1.0 is outside the declared range"),
    (["--set", "friction.steps_per_period=2.5"], "expected a whole number"),
    (["--step", "nan"], "argument --step: 'nan': expected a finite number of seconds > 0"),
    (["--step", "inf"], "argument --step: 'inf'"),
    (["--step", "0"], "argument --step: '0'"),
    (["--step", "-1e-4"], "argument --step: '-1e-4'"),
    (["--stop-time", "-inf"], "argument --stop-time: '-inf'"),
    (["--stop-time", "0"], "argument --stop-time: '0'"),
    (["--stop-time", "0.04", "--step", "3e-4"],
     "stop time 0.04 s is 133.333 steps of 0.0003 s: expected a whole number of steps"),
    (["--stop-time", "1e-5"], "expected a whole number of steps"),
    (["--stop-time", "1e5"], "is 1e+09 steps: at most 1e+08 are allowed"),
    (["--held", "--derivatives"], "not allowed with argument"),
    (["--bogus"], "unrecognized arguments: --bogus"),
    (["--fmu-dir", "{tmp}/none"], "--fmu-dir {tmp}/none: no such directory"),
    (["--fmu-dir", "{tmp}"], "--fmu-dir {tmp}: no DriveTrain.fmu in it"),
    (["--fmu-dir", "{tmp}/fake"], "{tmp}/fake/DriveTrain.fmu: not an FMU (not a zip archive)"),
    (["--out", "{tmp}/afile/run"], "--out {tmp}/afile/run: {tmp}/afile is a file, not a directory"),
    (["--out", "/proc/run"], "--out /proc/run: cannot write in /proc"),
    (["--out", "{tmp}/taken"], "--out {tmp}/taken: cannot write {tmp}/taken.csv"),
]


@pytest.mark.parametrize("argv, said", REFUSED, ids=[" ".join(a) for a, _ in REFUSED])
def test_every_bad_argument_is_refused_in_one_line_before_anything_runs(argv, said, tmp_path,
                                                                        capsys):
    (tmp_path / "afile").write_text("")
    (tmp_path / "taken.csv").mkdir()
    (tmp_path / "fake").mkdir()
    (tmp_path / "fake" / "DriveTrain.fmu").write_text("not a zip\n")
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    out = [] if "--out" in argv else ["--out", str(tmp_path / "out" / "run")]
    fmu_dir = [] if "--fmu-dir" in argv else ["--fmu-dir", str(FMU_DIR)]
    assert main([*argv, *fmu_dir, *out]) == 2
    captured = capsys.readouterr()
    assert captured.out == ""  # not even the start line: nothing ran
    assert captured.err.startswith("error: ") and captured.err.count("\n") == 1, captured.err
    assert said.replace("{tmp}", str(tmp_path)) in captured.err
    assert not any((tmp_path / "out").glob("run.*"))


def test_a_refusal_is_exit_status_2_and_one_line_without_a_traceback(tmp_path):
    env = {**os.environ, "PYTHONPATH": str(ROOT / "python")}
    done = subprocess.run([sys.executable, "-m", "friction_fmu.couple", "--fmu-dir", str(FMU_DIR),
                           "--set", "friction.Fd=1", "--out", str(tmp_path / "run")],
                          capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr.startswith("error: --set friction.Fd=1: Fd is an output; --set takes "
                                  "parameters of TransverseFriction: ")
    assert done.stderr.count("\n") == 1 and "Traceback" not in done.stderr


def test_a_discarded_step_ends_the_run_with_its_time_the_fmus_message_and_the_good_rows(
        tmp_path, capsys):
    # rk4 at 20 steps a vibration period does not hold a contact 1000 x stiffer than the
    # paper's: the second step becomes non-finite and the FMU discards it
    stiff = ["--set", "friction.solver=rk4", "--set", "friction.steps_per_period=20",
             "--set", "friction.kt=62.86e9"]
    prefix = tmp_path / "stiff"
    assert main([*stiff, "--fmu-dir", str(FMU_DIR), "--out", str(prefix)]) == 1
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1, captured.err
    assert captured.err.startswith("error: at t = 0.0001 s (the step to 0.0002 s): "
                                   "TransverseFriction: fmi2DoStep returned fmi2Discard: ")
    assert "non-finite" in captured.err  # the FMU's own words
    assert captured.out.splitlines()[1:] == [f"wrote {prefix}{s}" for s in (".csv", ".png", ".svg")]
    header, texts = _csv(f"{prefix}.csv")
    assert [float(row[0]) for row in texts] == [0.0, 1e-4]  # up to the last good point
    assert all(math.isfinite(float(v)) for row in texts for v in row)
    assert prefix.with_suffix(".png").read_bytes().startswith(b"\x89PNG")
