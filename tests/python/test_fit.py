"""The fit command (python/friction_fmu/fit.py) on LongitudinalFriction.

- Synthetic data made by the FMU itself (direct fmpy runs, apart from the fit's machinery) at
  known parameter values, with Gaussian noise of known size from a fixed seed: the fit gives
  the values back within 3 of its standard errors, its standard errors and residuals match the
  noise, and the CSV's fitted column is a direct fmpy run at the fitted values. A table of
  experiments (Dahl's kt and alpha; kt without noise, to the solver's accuracy) and a time
  series with an input column (kt from FT over the first periods from rest).
- Paper L's Table 1, experiment column (Littmann et al. 2001a): Dahl's kt, kt with alpha, and
  LuGre's kt fitted; the residuals at the paper's kt = 0.056 N/um are those of the paper's own
  Dahl column, and the fit's are smaller, at a minimum (direct runs on either side of it).
- Bad input is refused in one line with exit status 2 before any run (the executor is never
  started), a singular Jacobian after the first one; a run the FMU refuses stops the fit with
  exit status 1 and the FMU's words.

Runs are one vibration period from the periodic orbit or 20 periods from rest (about 2 ms
each), on tables of 6 to 8 experiments, so the file costs a few seconds.
"""
import csv
import json
import math
import sys

import numpy as np
import pytest

from conftest import ROOT, enum_value, fmu_path, simulate

sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import fit  # noqa: E402

MODEL = "LongitudinalFriction"
F = 6e4  # the FMU's default vibration frequency, paper L's 60 kHz
FC = 0.1 * 0.02 * 9.81  # mu m g: paper L's Coulomb force, the FMU's defaults

# Paper L (Leus & Gutowski 2008), Table 1 (va = 0.264 m/s): the constant sliding velocity vc
# (m/s), the mean friction force FT (N) measured by Littmann et al. (2001a), the experiment
# column, and the paper's Dahl column at its hand-picked kt = 0.056 N/um.
TABLE1_VC = [0.324, 0.264, 0.230, 0.199, 0.146, 0.095]
TABLE1_EXPERIMENT = [0.0197, 0.0187, 0.0179, 0.0168, 0.0112, 0.0077]
TABLE1_DAHL = [0.0196, 0.0196, 0.0181, 0.0156, 0.0109, 0.0066]
PAPER_KT = 5.6e4  # N/m


def write_csv(path, header, rows, comment=None):
    with open(path, "w", newline="") as handle:
        if comment:
            handle.write(f"# {comment}\n")
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows(rows)
    return str(path)


def ft_mean(vc, **values):
    """FT_mean after 20 periods from rest, by fmpy directly (the fit's oracle)."""
    start = {"vc": vc, "initial": enum_value(MODEL, "initial", "rest"),
             "law": enum_value(MODEL, "law", values.pop("law", "dahl")), **values}
    result = simulate(MODEL, start, stop_time=20 / F, step=20 / F, outputs=["FT_mean"])
    return float(result["FT_mean"][-1])


def run_fit(tmp_path, data, *options, name="fit"):
    """fit.main in this process; returns (exit status, the JSON, the CSV rows)."""
    out = tmp_path / name
    status = fit.main(["--fmu", fmu_path(MODEL), "--data", data, "--workers", "2",
                       "--out", str(out), *options])
    if status != 0:
        return status, None, None
    report = json.loads((tmp_path / f"{name}.json").read_text())
    with open(tmp_path / f"{name}.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    for suffix in (".png", ".svg"):
        assert (tmp_path / f"{name}{suffix}").stat().st_size > 0
    return status, report, rows


def within_errors(report, truth, sigmas=3.0):
    for name, value in truth.items():
        entry = report["parameters"][name]
        assert entry["stderr"] is not None and entry["stderr"] > 0
        assert abs(entry["value"] - value) <= sigmas * entry["stderr"], (name, entry, value)


def test_table_with_noise_gives_kt_and_alpha_back(tmp_path):
    truth = {"kt": 8e4, "alpha": 1.5}
    noise = 1e-4  # N, about 1 % of FT_mean
    vcs = [0.08, 0.11, 0.14, 0.17, 0.20, 0.23, 0.26, 0.30]
    rng = np.random.default_rng(1)
    exact = [ft_mean(vc, **truth) for vc in vcs]
    measured = [v + noise * rng.standard_normal() for v in exact]
    data = write_csv(tmp_path / "synthetic.csv", ["vc", "FT_mean"], zip(vcs, measured))
    # alpha != 1 runs from rest: the periodic start is not set for them (and falls back)
    status, report, rows = run_fit(tmp_path, data, "--set", "law=dahl", "--set", "initial=rest",
                                   "--stop-time", "20/f", "--fit", "kt=5e4", "--fit",
                                   "alpha=1:0.2:5")
    assert status == 0 and report["converged"]
    within_errors(report, truth)
    # the estimates are informative: a few percent, not the whole range
    assert report["parameters"]["kt"]["stderr"] < 0.2 * truth["kt"]
    assert report["parameters"]["alpha"]["stderr"] < 0.2 * truth["alpha"]
    # the residuals are the noise: rms within a factor 2 of it (8 values, 6 degrees of freedom)
    rms = report["residuals"]["FT_mean"]["rms"]
    assert noise / 2 < rms < 2 * noise
    assert report["degrees_of_freedom"] == len(vcs) - 2
    correlation = np.array(report["correlation"]["matrix"])
    assert correlation.shape == (2, 2) and np.allclose(np.diag(correlation), 1.0)
    assert -1 < correlation[0, 1] < 1
    # the CSV: measured as given, fitted as a direct run at the fitted values
    fitted = {n: report["parameters"][n]["value"] for n in truth}
    assert [float(r["FT_mean"]) for r in rows] == measured
    for row, vc in zip(rows, vcs):
        assert float(row["vc"]) == vc
        assert float(row["FT_mean:fitted"]) == pytest.approx(ft_mean(vc, **fitted), rel=1e-9)
        assert float(row["FT_mean:residual"]) == pytest.approx(
            float(row["FT_mean:fitted"]) - float(row["FT_mean"]), abs=1e-15)
    assert report["fmu_runs"] >= report["evaluations"] * len(vcs)


def test_table_without_noise_gives_kt_to_the_solvers_accuracy(tmp_path):
    vcs = [0.1, 0.15, 0.2, 0.25]
    measured = [ft_mean(vc, kt=3e4) for vc in vcs]
    data = write_csv(tmp_path / "exact.csv", ["vc", "FT_mean"], zip(vcs, measured))
    status, report, _ = run_fit(tmp_path, data, "--set", "law=dahl", "--stop-time", "1/f",
                                "--fit", "kt=6e4")
    assert status == 0
    # FT_mean is a period's mean: the runs start on the periodic orbit, one period each
    assert report["fixed"]["initial"] == "periodic"
    assert report["parameters"]["kt"]["value"] == pytest.approx(3e4, rel=1e-5)
    assert report["residuals"]["FT_mean"]["max_abs"] < 1e-8


def test_time_series_with_an_input_gives_kt_back(tmp_path):
    """FT over the first two periods from rest, the sliding velocity an input column."""
    truth, noise = 8e4, 2e-4
    times = np.arange(81) / (40 * F)
    vr = 0.146 + 0.264 * np.cos(2 * math.pi * F * times)
    signal = np.array(list(zip(times, vr)), dtype=[("time", float), ("vr_in", float)])
    start = {"law": enum_value(MODEL, "law", "dahl"), "kt": truth,
             "velocity_source": enum_value(MODEL, "velocity_source", "input")}
    exact = simulate(MODEL, start, stop_time=times[-1], step=times[1], outputs=["FT"],
                     input=signal)
    assert np.allclose(exact["time"], times, rtol=0, atol=1e-15)
    measured = exact["FT"] + noise * np.random.default_rng(2).standard_normal(len(times))
    data = write_csv(tmp_path / "series.csv", ["time", "vr_in", "FT"],
                     zip(times.tolist(), vr.tolist(), measured.tolist()))
    status, report, rows = run_fit(tmp_path, data, "--set", "law=dahl", "--set",
                                   "velocity_source=input", "--fit", "kt=3e4")
    assert status == 0 and report["form"] == "series"
    within_errors(report, {"kt": truth})
    assert report["parameters"]["kt"]["stderr"] < 0.05 * truth
    assert noise / 2 < report["residuals"]["FT"]["rms"] < 2 * noise
    assert len(rows) == len(times) and float(rows[-1]["time"]) == times[-1]
    # series runs once an evaluation and 2 per parameter a Jacobian
    assert report["fmu_runs"] == report["evaluations"] + 2 * report["jacobians"]


@pytest.fixture(scope="module")
def table1(tmp_path_factory):
    directory = tmp_path_factory.mktemp("table1")
    data = write_csv(directory / "table1.csv", ["vc", "FT_mean"],
                     zip(TABLE1_VC, TABLE1_EXPERIMENT),
                     comment="Paper L, Table 1, experiment column (Littmann et al. 2001a)")
    return directory, data


def cost(values, **parameters):
    return sum((ft_mean(vc, **parameters) - m) ** 2 for vc, m in zip(TABLE1_VC, values))


@pytest.mark.parametrize("law", ["dahl", "lugre"])
def test_paper_l_table1_kt(table1, law):
    directory, data = table1
    status, report, _ = run_fit(directory, data, "--set", f"law={law}", "--stop-time", "1/f",
                                "--fit", f"kt={PAPER_KT}", name=f"{law}-kt")
    assert status == 0 and report["converged"]
    if law == "dahl":
        # at the start, the paper's kt: the residuals of the paper's Dahl column (3 digits)
        paper = np.array(TABLE1_DAHL) - TABLE1_EXPERIMENT
        at_start = report["residuals_at_start"]["FT_mean"]
        assert at_start["rms"] == pytest.approx(np.sqrt(np.mean(paper**2)), abs=5e-5)
    kt = report["parameters"]["kt"]["value"]
    assert report["residuals"]["FT_mean"]["rms"] < report["residuals_at_start"]["FT_mean"]["rms"]
    # a minimum: direct runs 5 % either side cost more
    best = cost(TABLE1_EXPERIMENT, kt=kt, law=law)
    assert best < cost(TABLE1_EXPERIMENT, kt=0.95 * kt, law=law)
    assert best < cost(TABLE1_EXPERIMENT, kt=1.05 * kt, law=law)
    # the paper's hand-picked kt is not within the fit's standard error of its best kt
    stderr = report["parameters"]["kt"]["stderr"]
    assert 0 < stderr < abs(PAPER_KT - kt)


def test_paper_l_table1_kt_and_alpha(table1):
    directory, data = table1
    _, kt_only, _ = run_fit(directory, data, "--set", "law=dahl", "--stop-time", "1/f",
                            "--fit", f"kt={PAPER_KT}", name="dahl-kt-only")
    status, report, _ = run_fit(directory, data, "--set", "law=dahl", "--set", "initial=rest",
                                "--stop-time", "20/f", "--fit", f"kt={PAPER_KT}",
                                "--fit", "alpha=1:0.2:5", name="dahl-kt-alpha")
    assert status == 0 and report["converged"]
    # alpha = 1 is Dahl's kt alone: freeing alpha fits at least as well
    assert report["residual_norm"] <= kt_only["residual_norm"] * (1 + 1e-6)
    # six values hardly tell kt and alpha apart: strongly correlated, alpha loosely known
    correlation = report["correlation"]["matrix"][0][1]
    assert abs(correlation) > 0.5
    assert report["parameters"]["alpha"]["stderr"] > 0.1


def refused(capsys, monkeypatch, argv, *words):
    """Exit status 2 and one line on stderr holding `words`, with no executor started."""
    def no_runs(*args, **kwargs):
        raise AssertionError("an executor started: the refusal came after runs")

    monkeypatch.setattr(fit, "local_executor", no_runs)
    monkeypatch.setattr(fit, "dask_executor", no_runs)
    capsys.readouterr()
    assert fit.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: "), err
    for word in words:
        assert word in err, err
    return err


@pytest.fixture
def table(tmp_path):
    return write_csv(tmp_path / "t.csv", ["vc", "FT_mean"], [[0.1, 0.008], [0.2, 0.016]])


def base(data, tmp_path):
    return ["--fmu", fmu_path(MODEL), "--data", data, "--out", str(tmp_path / "r")]


def test_refusals_before_any_run(tmp_path, capsys, monkeypatch, table):
    args = base(table, tmp_path)
    refused(capsys, monkeypatch, [*args, "--fit", "ktt=1"], "no variable 'ktt'")
    refused(capsys, monkeypatch, [*args, "--fit", "FT=1"], "FT is an output",
            "Real parameters")
    refused(capsys, monkeypatch, [*args, "--fit", "law=2"], "law is an Integer parameter")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=-5"], "start -5 is outside the range",
            "kt")
    refused(capsys, monkeypatch, [*args, "--fit", "alpha=7:0.5:5"], "start 7", "alpha <= 5")
    refused(capsys, monkeypatch, [*args, "--fit", "va=0.2:-1:1"], "declared range")
    refused(capsys, monkeypatch, [*args, "--fit", "vc=0.2"], "vc is also given by")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=5e4", "--fit", "alpha=1", "--fit",
                                  "mu=0.1"], "3 parameters to fit from 2 measured values")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=1", "--set", "lw=dahl"], "'lw'")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=1", "--set", "law=stribeck"],
            "law = 'stribeck'", "dahl (2)")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=1", "--stop-time", "1/FT"],
            "FT is an output")
    refused(capsys, monkeypatch, [*args, "--fit", "kt=1", "--workers", "2",
                                  "--scheduler", "local:2"], "--workers")


@pytest.mark.parametrize("content, words", [
    ("", ["empty"]),
    ("# only a comment\n\n", ["empty"]),
    ("vc,FT_mean\n", ["no data rows"]),
    ("vc,FT_mean\n0.1,abc\n", ["line 2", "FT_mean", "'abc' is not a number"]),
    ("vc,FT_mean\n0.1,0.008\n0.2,nan\n", ["line 3", "FT_mean", "nan is not a finite number"]),
    ("vc,FT_mean\n0.1,\n", ["line 2", "FT_mean", "empty"]),
    ("vc,FT_mean\n0.1,0.008,3\n", ["line 2", "3 values for 2 columns"]),
    ("vc,FT_man\n0.1,0.008\n", ["'FT_man' is not a variable"]),
    ("vc,kt\n0.1,5e4\n", ["no measured output", "FT_mean"]),
    ("vc,vc\n0.1,0.2\n", ["vc appears twice"]),
    ("va,FT_mean\n-1,0.008\n", ["va = -1.0 is outside the declared range"]),
    ("time,kt,FT\n0,5e4,0\n1e-6,5e4,0.001\n", ["column kt is a parameter", "--set"]),
    ("time,FT\n0,0\n0,0.001\n", ["line 3", "not after"]),
])
def test_bad_data_is_refused(tmp_path, capsys, monkeypatch, content, words):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    argv = [*base(str(path), tmp_path), "--fit", "kt=5e4"]
    refused(capsys, monkeypatch, argv, str(path), *words)


def test_singular_jacobian_is_refused_after_the_first(tmp_path, capsys, table):
    # Dahl's law has no Stribeck velocity: FT_mean does not depend on vs
    status = fit.main([*base(table, tmp_path), "--set", "law=dahl", "--stop-time", "1/f",
                       "--fit", "kt=5e4", "--fit", "vs=0.01", "--quiet"])
    err = capsys.readouterr().err
    assert status == 2
    assert err.count("\n") == 1 and "do not depend on vs" in err and "Jacobian" in err
    assert not (tmp_path / "r.json").exists()


def test_parameters_acting_together_are_refused(tmp_path, capsys, table):
    # with the normal force its weight, FC = mu m g: mu and g act only as their product
    status = fit.main([*base(table, tmp_path), "--set", "law=coulomb", "--stop-time", "1/f",
                       "--fit", "mu=0.1", "--fit", "g=9.81", "--quiet"])
    err = capsys.readouterr().err
    assert status == 2 and err.count("\n") == 1
    assert "singular" in err and "mu and g" in err


def test_a_failed_run_stops_the_fit_with_the_fmus_words(tmp_path, capsys, table):
    # rk4 at 4 steps a period is unstable at this kt: the FMU discards the step and says why
    status = fit.main([*base(table, tmp_path), "--set", "law=dahl", "--set", "initial=rest",
                       "--set", "solver=rk4", "--set", "steps_per_period=4",
                       "--stop-time", "3/f", "--fit", "kt=5e6"])
    err = capsys.readouterr().err
    assert status == 1
    line = next(x for x in err.splitlines() if x.startswith("error: "))
    assert "experiment 1 at vc = 0.1, kt = 5e+06 failed (discard)" in line
    assert "fmi2DoStep" in line and "unstable" in line and "nothing written" in line
    assert not (tmp_path / "r.json").exists()


def test_start_line_and_progress(tmp_path, capsys, table):
    status = fit.main([*base(table, tmp_path), "--set", "law=dahl", "--stop-time", "1/f",
                       "--fit", "kt=5e4"])
    err = capsys.readouterr().err.splitlines()
    assert status == 0
    assert err[0].startswith(f"fitting kt of {MODEL} to 2 experiments (FT_mean)")
    assert "initial = periodic" in err[0]
    # not a terminal: plain lines, the last one the final count
    assert err[-1].startswith("Jacobian ") and " runs, residual norm " in err[-1]


# Paper L, Table 2 (vc = 0.230 m/s, va = 0.264 m/s): Dahl's FT_mean (N) at kt = 0.056 and
# 0.120 N/um; the variant Table2 keeps kt alone.
TABLE2_KT = [5.6e4, 1.2e5]
TABLE2_DAHL = [0.0181, 0.0172]


def fit_variant(tmp_path, *options):
    data = write_csv(tmp_path / "table2.csv", ["FT_mean"], [[TABLE2_DAHL[1]]])
    out = tmp_path / "table2-fit"
    status = fit.main(["--fmu", str(ROOT / "fmu-out" / "variants" / "Table2.fmu"),
                       "--data", data, "--fit", "kt=3e4", "--out", str(out), "--quiet",
                       *options])
    assert status == 0
    return json.loads(out.with_suffix(".json").read_text())


@pytest.fixture(scope="module")
def variant_local(tmp_path_factory):
    return fit_variant(tmp_path_factory.mktemp("local"), "--workers", "2")


def test_a_variant_inverts_paper_l_table2(variant_local):
    """One value, one parameter: kt is where the variant gives Table 2's FT_mean."""
    report = variant_local
    entry = report["parameters"]["kt"]
    assert report["degrees_of_freedom"] == 0 and entry["stderr"] is None
    assert report["residuals"]["FT_mean"]["max_abs"] < 1e-9
    # within what the table's three digits (0.05 mN) and the FMU's 0.4 % from the paper's
    # values allow, along the table's own slope between its two rows
    slope = (TABLE2_DAHL[1] - TABLE2_DAHL[0]) / (TABLE2_KT[1] - TABLE2_KT[0])
    allowed = (0.05e-3 + 0.004 * TABLE2_DAHL[1]) / abs(slope)
    assert abs(entry["value"] - TABLE2_KT[1]) < allowed


def test_dask_fits_as_local_processes(tmp_path, variant_local):
    import distributed  # noqa: F401  in tests/python/requirements.txt: missing is a failure

    report = fit_variant(tmp_path, "--scheduler", "local:2")
    assert report["executor"] == "a Dask LocalCluster of 2 workers"
    assert report["parameters"] == variant_local["parameters"]
    assert report["fmu_runs"] == variant_local["fmu_runs"]


def test_a_fit_stopped_by_max_evaluations_is_written_and_exits_1(tmp_path, capsys, table):
    status = fit.main([*base(table, tmp_path), "--set", "law=dahl", "--stop-time", "1/f",
                       "--fit", "kt=5e4", "--max-evaluations", "1", "--quiet"])
    err = capsys.readouterr().err
    assert status == 1 and "did not converge" in err
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["converged"] is False and report["evaluations"] == 1
