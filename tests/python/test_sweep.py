"""Parameter sweeps (python/friction_fmu): each row equals a direct fmpy run of its point, the
sweep's means agree with the scipy Radau reference, the local process pool and a Dask cluster
write the same CSV, a refused point is recorded with the FMU's message, an output without a
finite summary fails its point, the heat map has one cell per point and a one-axis sweep is a
line through each point (PNG and SVG), and the workers leave no extracted FMU behind. On the
command line: every bad argument (plan, FMU file, grid file, --out, scheduler) is refused in
one line with exit status 2 before any point runs, a failed point makes the exit status 1,
`local[:N]` starts its own Dask cluster, N/PARAM times use PARAM's start value when the plan
does not set it, and a start line comes before any progress.

Runs are short (30 periods at 3 kHz) and grids tiny, so the file takes a few seconds, most of
it starting the Dask clusters.
"""
import csv
import json
import math
import pathlib
import socket
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
import zipfile

import fmpy
import pytest

from conftest import ROOT, enum_value, fmu_path

sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import style, sweep_plot, switches  # noqa: E402
from friction_fmu.grid import Output, Plan, Span  # noqa: E402
from friction_fmu.sweep import main, run_sweep, write_csv  # noqa: E402

MODEL = "TransverseFriction"
F = 3000.0
STOP = 0.01
MEAN_LAST = Output("FFx", Span(1.0, "f"))  # mean of FFx's samples over the last period


def plan():
    # va = -1 mm/s is below the declared minimum 0: the FMU must refuse that point alone.
    return Plan(
        grid={"vd": [5e-4, 2e-3], "va": [-1e-3, 1e-3, 2e-3]},
        fixed={"f": F, "initial": "sliding"},
        outputs=[Output("FFx_mean"), Output("Fd"), MEAN_LAST],
        stop_time=Span(STOP),
        step=Span(0.1, "f"),
    )


@pytest.fixture(scope="module")
def local():
    return run_sweep(fmu_path(MODEL), plan(), workers=2, progress=False)[0]


@pytest.fixture(scope="module")
def cluster():
    import distributed  # in tests/python/requirements.txt: missing is a failure, not a skip
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as running:
        yield running


def test_each_row_equals_a_direct_fmpy_run(local):
    ok = [r for r in local if r["status"] == "ok"]
    assert len(ok) == 4
    for row in ok:
        result = fmpy.simulate_fmu(
            fmu_path(MODEL),
            start_values={"vd": row["vd"], "va": row["va"], "f": F,
                          "initial": enum_value(MODEL, "initial", "sliding")},
            stop_time=STOP, output_interval=0.1 / F, output=["FFx_mean", "Fd", "FFx"])
        assert row["FFx_mean"] == result["FFx_mean"][-1]
        assert row["Fd"] == result["Fd"][-1]
        last = result["time"] > STOP - 1.0 / F + 1e-12
        assert last.sum() == 10
        assert row[MEAN_LAST.column] == pytest.approx(result["FFx"][last].mean(), rel=1e-14)
        # and the run did something: the drive force is near the friction level
        assert 0.1 < row["FFx_mean"] < 1.2


def test_refused_point_is_recorded_and_the_others_run(local):
    failed = [r for r in local if r["status"] != "ok"]
    assert [(r["vd"], r["va"]) for r in failed] == [(5e-4, -1e-3), (2e-3, -1e-3)]
    for row in failed:
        assert row["status"] == "error"
        assert "va = -0.001 is out of range: expected va >= 0" in row["message"]
        assert "FFx_mean" not in row
    assert all(math.isfinite(r["FFx_mean"]) for r in local if r["status"] == "ok")


def test_discarded_step_is_recorded_with_its_time():
    # rk4 at 50 steps a period does not hold a contact 1000 x stiffer than the paper's (the
    # stiffness table of docs/performance.md): that point alone is discarded, the paper's kt runs.
    stiff = Plan(grid={"kt": [62.86e6, 62.86e9]},
                 fixed={"solver": "rk4", "steps_per_period": 50, "f": F},
                 outputs=[Output("FFx_mean")], stop_time=Span(STOP), step=Span(1.0, "f"))
    rows = run_sweep(fmu_path(MODEL), stiff, workers=1, progress=False)[0]
    assert [r["status"] for r in rows] == ["ok", "discard"]
    assert "fmi2DoStep: the step from t = 0 " in rows[1]["message"]
    assert "rk4: the state became non-finite" in rows[1]["message"]
    assert 0.1 < rows[0]["FFx_mean"] < 1.2


def test_a_point_the_fmu_warned_about_ran_and_carries_its_words():
    # With a periodic start, shooting closes the period at vd 0.5 mm/s; at vd 0.1 mm/s it stalls
    # short of the tolerance (stick-slip), and the FMU warns and runs the transient from the
    # nearest state. Both points ran: neither failed, and the warning is in the row.
    plan = Plan(grid={"vd": [5e-4, 1e-4]},
                fixed={"va": 3e-4, "f": F, "initial": "periodic", "tolerance": 1e-8},
                outputs=[Output("FFx_mean")], stop_time=Span(2.0, "f"), step=Span(1.0, "f"))
    rows, summary = run_sweep(fmu_path(MODEL), plan, workers=1, progress=False)
    assert [r["status"] for r in rows] == ["ok", "warning"]
    assert rows[0]["message"] == ""
    assert "initial = periodic: no periodic orbit to the tolerance" in rows[1]["message"]
    assert "starts from the state nearest to closing the period" in rows[1]["message"]
    assert all(math.isfinite(r["FFx_mean"]) for r in rows)
    assert (summary["failed"], summary["warned"]) == (0, 1)


def _rows_without_wall_time(path):
    with open(path) as handle:
        rows = list(csv.DictReader(handle))
    for row in rows:
        assert float(row.pop("wall_time_s")) >= 0.0
    return sorted(rows, key=lambda r: int(r["point"]))


def test_local_processes_and_dask_cluster_write_the_same_csv(local, cluster, tmp_path):
    on_dask, summary = run_sweep(fmu_path(MODEL), plan(), scheduler=cluster, progress=False)
    assert summary["ship"] == "bytes"
    write_csv(tmp_path / "local.csv", plan(), local)
    write_csv(tmp_path / "dask.csv", plan(), on_dask)
    a = _rows_without_wall_time(tmp_path / "local.csv")
    b = _rows_without_wall_time(tmp_path / "dask.csv")
    assert len(a) == 6
    assert a == b


def _heat_maps(fig):
    return [ax for ax in fig.axes if ax.get_label() != "<colorbar>" and ax.get_visible()]


def test_heat_map_has_one_cell_per_point(local):
    grid = {**plan().grid, "f": [F]}
    rows = [{**r, "f": F} for r in local]
    units = {"vd": "m/s", "va": "m/s", "FFx_mean": "N"}
    (([pinned], values),) = sweep_plot.panels(rows, grid, "va", "vd", "FFx_mean")
    assert pinned == ("f", F)  # the third axis, one value: a single panel
    by_point = {(r["va"], r["vd"]): r.get("FFx_mean") for r in local}
    assert values == [[by_point[(va, vd)] for va in grid["va"]] for vd in grid["vd"]]
    assert sum(v is None for row in values for v in row) == 2  # the refused points
    with style.context():
        fig = sweep_plot.figure(rows, grid, "va", "vd", "FFx_mean", units)
    (ax,) = _heat_maps(fig)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("va (m/s)", "vd (m/s)")
    cells = ax.collections[0].get_array()
    assert cells.size == 3 * 2 and cells.mask.sum() == 2
    (bar,) = [a for a in fig.axes if a.get_label() == "<colorbar>"]
    assert bar.get_ylabel() == "FFx_mean (N)"
    # the colour scale spans the successful points' values
    ok = sorted(r["FFx_mean"] for r in local if r["status"] == "ok")
    assert bar.get_ylim() == pytest.approx((ok[0], ok[-1]), rel=1e-12)
    # one panel per value of a faceted third axis, all on one colour scale
    with style.context():
        two = sweep_plot.figure(rows + [{**r, "f": 2.0} for r in rows],
                                {**grid, "f": [F, 2.0]}, "va", "vd", "FFx_mean", units)
    panels = _heat_maps(two)
    assert [a.get_title("left") for a in panels] == ["f = 3000", "f = 2"]
    assert all(a.collections[0].get_array().size == 3 * 2 for a in panels)
    assert len({a.collections[0].norm.vmax for a in panels}) == 1


def test_fig8_grid_file_and_times_per_point():
    from friction_fmu.grid import parse_assignment
    from friction_fmu.presets import PRESETS

    fig8 = PRESETS["fig8"]["plan"]()
    points = fig8.points()
    assert len(points) == 6 * 6 * 2
    assert points[1].values == {"vd": 1e-4, "va": 3e-4, "f": 2000.0}  # last axis fastest
    # 30 periods at 3 kHz from the periodic orbit, all of them averaged
    assert fig8.fixed["initial"] == "periodic"
    assert fig8.stop_time.at({"f": 3000.0}) == pytest.approx(0.01, rel=1e-15)
    assert fig8.outputs[1].window.at({"f": 3000.0}) == pytest.approx(0.01, rel=1e-15)
    assert fig8.outputs[1].column == "FFx_mean:mean_last=30/f"
    assert parse_assignment("vd=0.1e-3, 5e-4,1e-3") == ("vd", [1e-4, 5e-4, 1e-3])
    assert parse_assignment("initial=sliding") == ("initial", ["sliding"])


# the corners of the reference's vd x va grid, each under both slip laws
LAWS, REFERENCE_VD, REFERENCE_VA = ["split", "total"], [1e-4, 2e-3], [3e-4, 12e-3]


def test_sweep_agrees_with_scipy_radau_reference():
    """Oracle: tests/reference/transverse/make_reference.py, an independent implementation of
    the ODE solved by scipy's Radau at rtol 1e-11: FFx_mean (the mean of FFx over the last
    period) after 60 periods at 3 kHz from steady sliding. The sweep runs those points with the
    FMU's default solver and tolerance, 40 communication steps a period, as
    test_transverse.py's test_matches_stored_reference does, and meets its tolerance."""
    with open(ROOT / "tests" / "reference" / "transverse" / "means.csv") as handle:
        reference = {(r["slip_law"], float(r["vd"]), float(r["va"])): r
                     for r in csv.DictReader(handle)}
    cases = [reference[(law, vd, va)] for law in LAWS for vd in REFERENCE_VD
             for va in REFERENCE_VA]
    assert {float(r["f"]) for r in cases} == {F}
    assert all(float(r["t_end"]) == pytest.approx(60 / F, rel=1e-15) for r in cases)
    sweep = Plan(grid={"slip_law": LAWS, "vd": REFERENCE_VD, "va": REFERENCE_VA},
                 fixed={"f": F, "initial": "sliding"}, outputs=[Output("FFx_mean")],
                 stop_time=Span(60.0, "f"), step=Span(1.0 / 40, "f"))
    rows, summary = run_sweep(fmu_path(MODEL), sweep, workers=2, progress=False)
    assert summary["failed"] == 0 and len(rows) == len(cases) == 8
    for row in rows:
        expected = float(reference[(row["slip_law"], row["vd"], row["va"])]["FFx_mean"])
        assert abs(row["FFx_mean"] / expected - 1.0) <= 1e-5, (row, expected)


def test_one_axis_sweep_is_a_line_plot(tmp_path):
    """A single grid axis is a line plot, PNG and SVG, through one point per grid value, each
    the value in the CSV the same sweep wrote; a fixed solver gives the line its style."""
    out = tmp_path / "one"
    vds = [1e-4, 2e-4, 3e-4]
    code = main([fmu_path(MODEL), "--grid", "vd=" + ",".join(map(repr, vds)),
                 "--set", "initial=sliding", "--set", f"f={F!r}", "--output", "FFx_mean",
                 "--stop-time", "3/f", "--step", "1/f", "--workers", "1", "--quiet",
                 "--out", str(out)])
    assert code == 0
    with open(out.with_suffix(".csv")) as handle:
        rows = list(csv.DictReader(handle))
    assert out.with_suffix(".png").read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    ET.fromstring(out.with_suffix(".svg").read_text())  # well-formed
    values = [float(row["FFx_mean"]) for row in rows]
    assert all(0.0 < v < 1.2 for v in values)
    points = [{"vd": vd, "status": "ok", "FFx_mean": v} for vd, v in zip(vds, values)]
    with style.context():
        fig = sweep_plot.figure(points, {"vd": vds}, "vd", None, "FFx_mean", {"vd": "m/s"},
                                solver="radau5")
    (ax,) = fig.axes
    assert len(ax.collections) == 0  # no heat map cells
    (line,) = ax.get_lines()
    assert list(line.get_xdata()) == vds and list(line.get_ydata()) == values
    assert (line.get_color(), line.get_marker()) == (style.SOLVERS["radau5"].color,
                                                     style.SOLVERS["radau5"].marker)
    assert ax.get_xlabel() == "vd (m/s)"


def _item_names(variable):
    md = fmpy.read_model_description(fmu_path(MODEL))
    return list(switches.items(next(v for v in md.modelVariables if v.name == variable)))


SMALL_PLAN = ["--grid", "vd=1e-4,2e-4", "--set", "f=3000", "--output", "FFx_mean",
              "--stop-time", "3/f", "--step", "1/f", "--quiet"]
SMALL = [*SMALL_PLAN, "--workers", "1"]


def _refusal(capsys, argv, out):
    """The one line `main` refused `argv` with, after checking it refused before any point ran:
    exit status 2, nothing on stdout, no CSV."""
    code = main(argv)
    captured = capsys.readouterr()
    assert code == 2, captured
    assert captured.out == ""
    assert captured.err.startswith("error: ") and captured.err.count("\n") == 1
    assert not out.with_suffix(".csv").is_file()  # refused up front: nothing ran
    return captured.err.removesuffix("\n")


@pytest.mark.parametrize("extra, said", [
    (["--set", "initial=slidng"], ["initial = 'slidng': expected one of"]),
    (["--grid", "initial=sliding,7"], ["initial = 7.0: expected one of"]),
    (["--grid", "va=1e-4,abc"], ["va = 'abc': expected a number"]),
    (["--set", "steps_per_period=2.5"], ["steps_per_period = 2.5: expected a whole number"]),
    (["--stop-time", "3/ff"], ["stop time 3/ff: 'ff' is not a variable of the FMU"]),
    (["--step", "1/FF"], ["step 1/FF: FF is an output; N/PARAM divides by a parameter"]),
    (["--output", "FFx:mean_last=1/g2"], ["output FFx:mean_last=1/g2: 'g2' is not a variable"]),
    (["--stop-time", "abc"], ["time 'abc': expected seconds or N/PARAM"]),
    (["--output", "FFxx"], ["the FMU has no variable 'FFxx'"]),
    (["--y", "vdx"], ["--y vdx: not a grid axis (axes: vd)"]),
    (["--x", "va"], ["--x va: not a grid axis (axes: vd)"]),
    (["--color", "Fd"], ["--color Fd: not an output column (FFx_mean)"]),
    (["--fix", "f=3000"], ["--fix f: not a grid axis (axes: vd)"]),
    (["--grid", "f=2e3,3e3", "--fix", "f=1e3"], ["--fix f=1000.0: not a value of that axis"]),
    # a count of workers is a whole number >= 1
    (["--workers", "-1"], ["argument --workers: '-1': expected a whole number >= 1"]),
    (["--workers", "0"], ["argument --workers: '0': expected a whole number >= 1"]),
    (["--workerz", "2"], ["unrecognized arguments: --workerz 2 (see --help)"]),
    # times are finite, and a point is at most 1e8 communication steps
    (["--stop-time", "inf"], ["time 'inf': expected a finite number"]),
    (["--stop-time", "nan/f"], ["time 'nan/f': expected a finite number"]),
    (["--step", "nan"], ["time 'nan': expected a finite number"]),
    (["--output", "FFx:mean_last=nan"], ["time 'nan': expected a finite number"]),
    (["--stop-time", "1e300"], ["stop time 1e+300 s at a step of 0.000333333 s at f = 3000.0 "
                                "is 3e+303 communication steps a point: at most 1e+08"]),
    (["--step", "1e-300"], ["stop time 0.001 s at a step of 1e-300 s at f = 3000.0 is 1e+297 "
                            "communication steps a point: at most 1e+08 are allowed"]),
    (["--step=-1/f"], ["step -1/f is -0.0003333333333333333 s at f = 3000.0: expected a finite "
                       "step > 0"]),
    (["--stop-time", "0"], ["stop time 0 is 0.0 s: expected a finite time after the start, 0 s"]),
    # values are finite numbers of a parameter or input, within the declared range
    (["--grid", "va=nan"], ["va = nan: expected a finite number"]),
    (["--set", "va=-inf"], ["va = -inf: expected a finite number"]),
    (["--set", "FF=1"], ["FF is an output; --grid and --set take parameters and inputs: "
                         "slip_law, solver,", ", f, vd_in"]),
    (["--grid", "va=1e-3,-1e-3"], ["va = -0.001 is outside the declared range: expected "
                                   "0 <= va (m/s)"]),
    (["--set", "tolerance=0.1"], ["tolerance = 0.1 is outside the declared range: expected "
                                  "1e-14 <= tolerance <= 0.01"]),
    (["--set", "f=0"], ["f = 0.0 is outside the declared range: expected "
                        "2.2250738585072014e-308 <= f (Hz)"]),
    (["--set", "steps_per_period=0"], ["expected 1 <= steps_per_period <= 100000000"]),
    # a mean over no time, an axis given twice, more processes than the machine can use
    (["--output", "FF:mean_last=-1"], ["the window mean_last=-1 is not a time > 0"]),
    (["--output", "FF:mean_last=0/f"], ["the window mean_last=0/f is not a time > 0"]),
    (["--grid", "vd=2e-3"], ["--grid vd=2e-3: vd is already an axis"]),
    (["--workers", "100000"], ["--workers: '100000': expected at most",
                               "local processes (4 per CPU"]),
])
def test_misspelt_plan_is_refused_before_any_point_runs(tmp_path, capsys, extra, said):
    out = tmp_path / "refused"
    message = _refusal(capsys, [fmu_path(MODEL), *SMALL, "--out", str(out), *extra], out)
    for phrase in said:
        assert phrase in message
    if "initial =" in message:  # the items come from the modelDescription's type definition
        items = _item_names("initial")
        assert len(items) >= 2 and all(f"{name} (" in message for name in items)


def test_refusal_is_one_line_and_exit_status_2():
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL), *SMALL,
                           "--y", "vdx"], capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 2
    assert done.stderr == "error: --y vdx: not a grid axis (axes: vd)\n"
    assert done.stdout == ""


def test_a_file_that_is_not_an_fmu_is_refused(tmp_path, capsys):
    text = tmp_path / "text.fmu"
    text.write_text("not a zip\n")
    empty = tmp_path / "empty.fmu"
    with zipfile.ZipFile(empty, "w") as archive:
        archive.writestr("binaries/readme.txt", "no model description\n")
    out = tmp_path / "refused"
    for fmu, said in [(text, f"{text}: not an FMU (not a zip archive)"),
                      (empty, f"{empty}: not an FMU (no modelDescription.xml in the archive)"),
                      (tmp_path / "missing.fmu", "No such file or directory")]:
        assert said in _refusal(capsys, [str(fmu), *SMALL, "--out", str(out)], out)


BAD_GRID_FILES = [
    ("list.toml", 'grid = [1e-4, 2e-4]\n', "grid: expected a table of axes"),
    ("scalar.toml", '[grid]\nvd = 1e-4\n', "grid.vd = 0.0001: expected a non-empty list"),
    ("string.json", '{"grid": {"vd": "1e-4,2e-4"}}', "grid.vd = '1e-4,2e-4': expected a non-empty"),
    ("empty.toml", '[grid]\nvd = []\n', "grid.vd = []: expected a non-empty list"),
    ("set.toml", '[grid]\nvd = [1e-4]\n[set]\nf = [1e3, 2e3]\n',
     "set.f = [1000.0, 2000.0]: expected one value (a list is a grid axis)"),
    ("outputs.toml", 'outputs = "FFx_mean"\n[grid]\nvd = [1e-4]\n',
     "outputs = 'FFx_mean': expected a list"),
    ("top.json", '[1, 2]', "expected a table with the keys grid"),
    ("syntax.json", '{"grid": }', "Expecting value: line 1 column 10"),
]


@pytest.mark.parametrize("name, text, said", BAD_GRID_FILES,
                         ids=[name for name, _, _ in BAD_GRID_FILES])
def test_grid_file_of_the_wrong_shape_is_refused(tmp_path, capsys, name, text, said):
    grid_file = tmp_path / name
    grid_file.write_text(text)
    out = tmp_path / "refused"
    message = _refusal(capsys, [fmu_path(MODEL), "--grid-file", str(grid_file), "--output",
                                "FFx_mean", "--stop-time", "1e-3", "--workers", "1", "--quiet",
                                "--out", str(out)], out)
    assert f"{grid_file}: {said}" in message


def test_out_that_cannot_be_written_is_refused(tmp_path, capsys):
    afile = tmp_path / "afile"
    afile.write_text("")
    (tmp_path / "taken.csv").mkdir()
    for out, said in [(afile / "sweep", f"{afile} is a file, not a directory"),
                      (afile / "deeper" / "sweep", f"cannot write in {afile / 'deeper'} (Not a "
                                                   "directory)"),
                      (pathlib.Path("/proc/sweep"), "cannot write in /proc"),
                      (tmp_path / "taken", f"cannot write {tmp_path / 'taken.csv'}")]:
        message = _refusal(capsys, [fmu_path(MODEL), *SMALL, "--out", str(out)], out)
        assert message.startswith(f"error: --out {out}: {said}")


def _written(tmp_path):
    return sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*") if p.is_file())


@pytest.mark.parametrize("out, files", [
    ("results/", ["results/TransverseFriction-sweep.csv", "results/TransverseFriction-sweep.json",
                  "results/TransverseFriction-sweep.png", "results/TransverseFriction-sweep.svg"]),
    ("run.f2.5", ["run.f2.5.csv", "run.f2.5.json", "run.f2.5.png", "run.f2.5.svg"]),
    ("run.csv", ["run.csv", "run.json", "run.png", "run.svg"]),
])
def test_out_prefix_directory_and_dots(tmp_path, out, files):
    """A directory (ending in /, or existing) holds MODEL-sweep.*; a prefix keeps its dots."""
    assert main([fmu_path(MODEL), *SMALL, "--out", f"{tmp_path}/{out}"]) == 0
    assert _written(tmp_path) == files
    (tmp_path / "existing").mkdir()
    assert main([fmu_path(MODEL), *SMALL, "--out", str(tmp_path / "existing")]) == 0
    assert [f for f in _written(tmp_path) if f.startswith("existing")] == [
        "existing/TransverseFriction-sweep.csv", "existing/TransverseFriction-sweep.json",
        "existing/TransverseFriction-sweep.png", "existing/TransverseFriction-sweep.svg"]


def _free_port():
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def test_scheduler_that_does_not_answer_is_refused(tmp_path, capsys):
    out = tmp_path / "refused"
    address = f"tcp://127.0.0.1:{_free_port()}"
    began = time.monotonic()
    message = _refusal(capsys, [fmu_path(MODEL), *SMALL_PLAN, "--scheduler", address,
                                "--connect-timeout", "0.5", "--out", str(out)], out)
    assert message == (f"error: --scheduler {address}: no Dask scheduler answered within 0.5 s "
                       "(--connect-timeout)")
    assert time.monotonic() - began < 5


@pytest.mark.parametrize("extra, said", [
    (["--scheduler", "local:0"], "--scheduler local:0: expected local or local:N, N >= 1"),
    (["--scheduler", "local:two"], "--scheduler local:two: expected local or local:N"),
    (["--scheduler", "local:2", "--workers", "2"], "--workers sizes the local process pool"),
    (["--scheduler", "local:100000"], "--scheduler local:100000: expected at most"),
    (["--connect-timeout", "nan"], "argument --connect-timeout: 'nan': expected a finite number of "
                                   "seconds > 0"),
])
def test_scheduler_arguments_are_checked(tmp_path, capsys, extra, said):
    out = tmp_path / "refused"
    message = _refusal(capsys, [fmu_path(MODEL), *SMALL_PLAN, "--out", str(out), *extra], out)
    assert said in message


@pytest.mark.parametrize("scheduler", ["tcp://127.0.0.1:1", "local:2"])
def test_a_scheduler_without_distributed_is_refused_in_a_line(tmp_path, capsys, monkeypatch,
                                                              scheduler):
    """Where Dask's distributed is not installed (None in sys.modules makes its import fail),
    --scheduler is refused in one line that says what to install, not with the traceback."""
    monkeypatch.setitem(sys.modules, "distributed", None)
    out = tmp_path / "refused"
    message = _refusal(capsys, [fmu_path(MODEL), *SMALL_PLAN, "--scheduler", scheduler,
                                "--out", str(out)], out)
    assert message == (f"error: --scheduler {scheduler} needs Dask's distributed, which is not "
                       "installed here: pip install -e 'python[dask]'")


def test_a_summary_without_a_finite_value_fails_its_point(tmp_path):
    """A window holding no communication point has no mean: the point is an error with the
    reason, never a NaN with status ok."""
    empty = Output("FFx", Span(0.0))
    rows = run_sweep(fmu_path(MODEL), Plan(grid={"vd": [1e-4]}, fixed={"f": F},
                                           outputs=[Output("FFx_mean"), empty],
                                           stop_time=Span(3.0, "f"), step=Span(1.0, "f")),
                     workers=1, progress=False)[0]
    assert rows[0]["status"] == "error"
    assert rows[0]["message"] == "FFx:mean_last=0: no communication point in the last 0 s " \
                                 "before t = 0.001 s"
    assert empty.column not in rows[0] and "FFx_mean" not in rows[0]
    # (from the command line a window of no time is refused before any point runs:
    # test_misspelt_plan_is_refused_before_any_point_runs)


def test_exit_status_is_1_when_some_points_fail(tmp_path):
    # the stiff contact of test_discarded_step_is_recorded_with_its_time: one point of two fails
    out = tmp_path / "some"
    code = main([fmu_path(MODEL), "--grid", "kt=62.86e6,62.86e9", "--set", "solver=rk4",
                 "--set", "steps_per_period=50", "--set", "f=3000", "--output", "FFx_mean",
                 "--stop-time", str(STOP), "--step", "1/f", "--workers", "1", "--quiet",
                 "--out", str(out)])
    assert code == 1
    with open(out.with_suffix(".csv")) as handle:
        assert [r["status"] for r in csv.DictReader(handle)] == ["ok", "discard"]


def _csv_rows(path):
    with open(path) as handle:
        return [{k: v for k, v in r.items() if k != "wall_time_s"} for r in csv.DictReader(handle)]


def test_periods_of_a_parameter_the_plan_does_not_set_use_its_start_value(tmp_path):
    """`3/f` and `mean_last=1/f` with no f in the plan are periods of the FMU's start value of
    f (3 kHz): the same rows as with f = 3000 set."""
    common = [fmu_path(MODEL), "--grid", "vd=1e-4,2e-4", "--output", "FFx_mean", "--output",
              "FFx:mean_last=1/f", "--stop-time", "3/f", "--step", "0.25/f", "--workers", "1",
              "--quiet"]
    assert _start_value("f") == "3e3"
    assert main([*common, "--out", str(tmp_path / "default")]) == 0
    assert main([*common, "--set", "f=3000", "--out", str(tmp_path / "set")]) == 0
    default = _csv_rows(tmp_path / "default.csv")
    assert default == _csv_rows(tmp_path / "set.csv")
    assert [r["status"] for r in default] == ["ok", "ok"]


def _start_value(variable):
    md = fmpy.read_model_description(fmu_path(MODEL))
    return next(v.start for v in md.modelVariables if v.name == variable)


def test_start_line_comes_first_and_progress_is_plain_lines_off_a_terminal(tmp_path):
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    out = tmp_path / "plain"
    done = subprocess.run([sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL),
                           *[a for a in SMALL if a != "--quiet"], "--out", str(out)],
                          capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "\r" not in done.stderr and "\x1b" not in done.stderr
    lines = done.stderr.splitlines()
    assert lines[0] == (f"sweeping TransverseFriction: 2 points on local, 1 process, writing "
                        f"{out}.csv (and .png, .svg, .json)")
    assert lines[-1].startswith("2/2  elapsed ")
    assert len(lines) <= 3  # a line every 5 s at most, and the last


def test_command_line_on_a_scheduler_address(cluster, tmp_path):
    out = tmp_path / "address"
    assert main([fmu_path(MODEL), *SMALL_PLAN, "--scheduler", cluster.scheduler_address,
                 "--out", str(out)]) == 0
    summary = json.loads(out.with_suffix(".json").read_text())
    assert summary["executor"] == f"dask {cluster.scheduler_address}"
    assert [r["status"] for r in _csv_rows(out.with_suffix(".csv"))] == ["ok", "ok"]


def test_local_scheduler_starts_a_cluster_without_pythonpath(tmp_path):
    """`--scheduler local:1` starts its own LocalCluster; run from python/ with no PYTHONPATH,
    its worker imports the package all the same, and the rows are those of the local pool."""
    env = {"PATH": "/usr/bin:/bin", "TMPDIR": str(tmp_path)}
    out = tmp_path / "local"
    done = subprocess.run([sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL),
                           *SMALL_PLAN, "--scheduler", "local:1", "--out", str(out)],
                          capture_output=True, text=True, env=env, timeout=120,
                          cwd=ROOT / "python")
    assert done.returncode == 0, done.stderr
    summary = json.loads(out.with_suffix(".json").read_text())
    assert summary["executor"] == "a Dask LocalCluster of 1 worker"
    assert main([fmu_path(MODEL), *SMALL, "--out", str(tmp_path / "pool")]) == 0
    assert _csv_rows(out.with_suffix(".csv")) == _csv_rows(tmp_path / "pool.csv")


def test_workers_remove_their_extracted_fmu(tmp_path):
    """Each worker extracts the FMU into the temporary directory; a sweep leaves none behind (a
    process-pool worker exits without running atexit handlers)."""
    temp = tmp_path / "tmp"
    temp.mkdir()
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin", "TMPDIR": str(temp)}
    done = subprocess.run([sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL),
                           *SMALL_PLAN, "--workers", "2", "--out", str(tmp_path / "two")],
                          capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "two.csv").exists()
    assert sorted(p.name for p in temp.iterdir()) == []


def _children(pid):
    """The process ids whose parent is `pid` (from /proc)."""
    found = []
    for entry in pathlib.Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                found.append(int(entry.name))
    return found


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc and prctl are Linux's")
def test_pool_processes_end_with_a_sweep_that_is_killed(tmp_path):
    """SIGKILL gives the sweep no chance to stop its pool: the kernel ends the processes, which
    asked for it when they started."""
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    # long enough to be killed while its two processes run points
    sweep = subprocess.Popen(
        [sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL), "--grid",
         "vd=" + ",".join(f"{1e-4 * (1 + k)}" for k in range(400)), "--set", "f=3000",
         "--output", "FFx_mean", "--stop-time", "300/f", "--step", "1/f", "--quiet",
         "--workers", "2", "--out", str(tmp_path / "killed")],
        env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while len(_children(sweep.pid)) < 2 and time.monotonic() < deadline:
        time.sleep(0.05)
    pool = _children(sweep.pid)
    assert len(pool) >= 2, pool
    sweep.kill()
    sweep.wait()
    deadline = time.monotonic() + 20
    while any(pathlib.Path(f"/proc/{pid}").exists() for pid in pool) and time.monotonic() < deadline:
        time.sleep(0.05)
    # a zombie is an ended process its (now gone) parent did not reap: init reaps it
    alive = [pid for pid in pool if pathlib.Path(f"/proc/{pid}").exists()
             and (pathlib.Path(f"/proc/{pid}") / "stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"]
    assert alive == [], alive
