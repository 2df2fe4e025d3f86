"""Parameter sweeps (python/friction_fmu): each row equals a direct fmpy run of its point, the
sweep's means agree with the scipy Radau reference, the local process pool and a Dask cluster
write the same CSV, a refused point is recorded with the FMU's message, a misspelt plan is
refused before any point runs, the heat map has one cell per point, and the workers leave no
extracted FMU behind.

Runs are short (30 periods at 3 kHz) and grids tiny, so the file takes a few seconds, most of
it starting the Dask cluster.
"""
import csv
import math
import subprocess
import sys
import xml.etree.ElementTree as ET

import fmpy
import pytest

from conftest import ROOT, enum_value, fmu_path

sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import heatmap, switches  # noqa: E402
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


def _rows_without_wall_time(path):
    with open(path) as handle:
        rows = list(csv.DictReader(handle))
    for row in rows:
        assert float(row.pop("wall_time_s")) >= 0.0
    return sorted(rows, key=lambda r: int(r["point"]))


def test_local_processes_and_dask_cluster_write_the_same_csv(local, tmp_path):
    import distributed  # in tests/python/requirements.txt: missing is a failure, not a skip
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        on_dask, summary = run_sweep(fmu_path(MODEL), plan(), scheduler=cluster, progress=False)
    assert summary["ship"] == "bytes"
    write_csv(tmp_path / "local.csv", plan(), local)
    write_csv(tmp_path / "dask.csv", plan(), on_dask)
    a = _rows_without_wall_time(tmp_path / "local.csv")
    b = _rows_without_wall_time(tmp_path / "dask.csv")
    assert len(a) == 6
    assert a == b


def test_heat_map_has_one_cell_per_point(local):
    grid = {**plan().grid, "f": [F]}
    rows = [{**r, "f": F} for r in local]
    units = {"vd": "m/s", "va": "m/s", "FFx_mean": "N"}
    svg = heatmap.render(rows, grid, "va", "vd", "FFx_mean", units)
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    cells = [r for r in root.iter(f"{ns}rect") if r.get("class") == "cell"]
    assert len(cells) == 3 * 2
    gray = [c for c in cells if c.get("fill") == "#cccccc"]
    assert len(gray) == 2
    texts = [t.text for t in root.iter(f"{ns}text")]
    assert "va (m/s)" in texts and "vd (m/s)" in texts and "FFx_mean (N)" in texts
    # the color bar spans exactly the successful points' values
    values = sorted(r["FFx_mean"] for r in local if r["status"] == "ok")
    assert f"{values[0]:.4g}" in texts and f"{values[-1]:.4g}" in texts
    # one panel per value of a faceted third axis
    two = heatmap.render(rows + [{**r, "f": 2.0} for r in rows], {**grid, "f": [F, 2.0]},
                         "va", "vd", "FFx_mean", units)
    cells = [r for r in ET.fromstring(two).iter(f"{ns}rect") if r.get("class") == "cell"]
    assert len(cells) == 2 * 3 * 2


def test_fig8_grid_file_and_times_per_point():
    from friction_fmu.grid import parse_assignment
    from friction_fmu.presets import PRESETS

    fig8 = PRESETS["fig8"]["plan"]()
    points = fig8.points()
    assert len(points) == 6 * 6 * 2
    assert points[1].values == {"vd": 1e-4, "va": 3e-4, "f": 2000.0}  # last axis fastest
    # 150 periods at 3 kHz, averaged over the last 30
    assert fig8.stop_time.at({"f": 3000.0}) == pytest.approx(0.05, rel=1e-15)
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


def _cells(svg):
    ns = "{http://www.w3.org/2000/svg}"
    return [r for r in ET.fromstring(svg).iter(f"{ns}rect") if r.get("class") == "cell"]


def test_one_axis_sweep_draws_one_row(tmp_path):
    """A single grid axis is one row of cells, one per point, each holding that point's value
    in the CSV the same sweep wrote (no cell of a point that was not run)."""
    out = tmp_path / "one"
    vds = [1e-4, 2e-4, 3e-4]
    code = main([fmu_path(MODEL), "--grid", "vd=" + ",".join(map(repr, vds)),
                 "--set", "initial=sliding", "--set", f"f={F!r}", "--output", "FFx_mean",
                 "--stop-time", "3/f", "--step", "1/f", "--workers", "1", "--quiet",
                 "--out", str(out)])
    assert code == 0
    with open(out.with_suffix(".csv")) as handle:
        rows = list(csv.DictReader(handle))
    cells = _cells(out.with_suffix(".svg").read_text())
    assert len(cells) == len(rows) == len(vds)
    assert len({c.get("y") for c in cells}) == 1  # a single row
    titles = [c.find("{http://www.w3.org/2000/svg}title").text for c in cells]
    assert not any("missing" in t for t in titles)
    assert all(c.get("fill") != "#cccccc" for c in cells)
    for vd, row, title in zip(vds, rows, titles):
        assert title == f"vd={vd}: {float(row['FFx_mean']):.6g}"
        assert 0.0 < float(row["FFx_mean"]) < 1.2


def _item_names(variable):
    md = fmpy.read_model_description(fmu_path(MODEL))
    return list(switches.items(next(v for v in md.modelVariables if v.name == variable)))


SMALL_PLAN = ["--grid", "vd=1e-4,2e-4", "--set", "f=3000", "--output", "FFx_mean",
              "--stop-time", "3/f", "--step", "1/f", "--quiet"]
SMALL = [*SMALL_PLAN, "--workers", "1"]


@pytest.mark.parametrize("extra, said", [
    (["--set", "initial=slidng"], ["initial = 'slidng': expected one of"]),
    (["--grid", "initial=sliding,7"], ["initial = 7.0: expected one of"]),
    (["--grid", "va=1e-4,abc"], ["va = 'abc': expected a number"]),
    (["--set", "steps_per_period=2.5"], ["steps_per_period = 2.5: expected a whole number"]),
    (["--stop-time", "3/ff"], ["stop time 3/ff: 'ff' is not a variable of the FMU"]),
    (["--step", "1/va"], ["step 1/va: 'va' is not set at every point"]),
    (["--output", "FFx:mean_last=1/g"], ["output FFx:mean_last=1/g: 'g' is not set"]),
    (["--stop-time", "abc"], ["time 'abc': expected seconds or N/PARAM"]),
    (["--output", "FFxx"], ["the FMU has no variable 'FFxx'"]),
    (["--y", "vdx"], ["--y vdx: not a grid axis (axes: vd)"]),
    (["--x", "va"], ["--x va: not a grid axis (axes: vd)"]),
    (["--color", "Fd"], ["--color Fd: not an output column (FFx_mean)"]),
    (["--fix", "f=3000"], ["--fix f: not a grid axis (axes: vd)"]),
    (["--grid", "f=2e3,3e3", "--fix", "f=1e3"], ["--fix f=1000.0: not a value of that axis"]),
])
def test_misspelt_plan_is_refused_before_any_point_runs(tmp_path, extra, said):
    out = tmp_path / "refused"
    with pytest.raises(SystemExit) as refusal:
        main([fmu_path(MODEL), *SMALL, "--out", str(out), *extra])
    message = refusal.value.code
    assert isinstance(message, str) and message.startswith("error: ") and "\n" not in message
    for phrase in said:
        assert phrase in message
    if "initial" in message:  # the items come from the modelDescription's type definition
        items = _item_names("initial")
        assert len(items) >= 2 and all(f"{name} (" in message for name in items)
    assert not out.with_suffix(".csv").exists()  # refused up front: nothing ran


def test_refusal_is_one_line_and_a_nonzero_exit():
    env = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-m", "friction_fmu.sweep", fmu_path(MODEL), *SMALL,
                           "--y", "vdx"], capture_output=True, text=True, env=env, timeout=60)
    assert done.returncode == 1
    assert done.stderr == "error: --y vdx: not a grid axis (axes: vd)\n"
    assert done.stdout == ""


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
