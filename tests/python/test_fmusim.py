"""The FMUs in fmusim, the Reference FMUs' command-line simulator, against fmpy: every full FMU and
every shipped variant, its default experiment, every Real output to round-off (both step to
start + n h, so they take the same steps); and a start value set on fmusim's command line.

fmusim ends a run once it is within 1e-5 s of the stop time, an absolute margin longer than these
FMUs' experiments' last steps (at a step of 1 us it drops the last ten points), so it is given a
stop time of one step and 1e-5 s more, and the rows past the real stop time are dropped.

The test command does not install fmusim: it is built from the Reference FMUs' sources, which no
registry the test command installs from carries (docs/interoperability.md says how it was built).
These tests run where the executable is found (the FMUSIM environment variable, else `fmusim` on
PATH) and are skipped otherwise, saying so.
"""
import os
import shutil
import subprocess

import fmpy
import numpy as np
import pytest

from conftest import FMU_DIR, assert_default_experiment_matches_fmpy

FMUSIM = os.environ.get("FMUSIM") or shutil.which("fmusim")
pytestmark = pytest.mark.skipif(
    not FMUSIM, reason="fmusim not found (set FMUSIM; docs/interoperability.md, \"fmusim\")")

FMUS = sorted(FMU_DIR.glob("*.fmu")) + sorted((FMU_DIR / "variants").glob("*.fmu"))
# fmusim's margin on the stop time (FMIIsClose in its sources).
MARGIN = 1e-5


def fmusim(fmu, tmp_path, step, stop, *start_values):
    """fmusim's recording up to `stop`, every `step`, as a NumPy record array."""
    out, log = tmp_path / "out.csv", tmp_path / "fmusim.log"
    command = [FMUSIM, "--interface-type", "cs", "--output-interval", repr(step),
               "--stop-time", repr(stop + step + MARGIN), "--log-file", str(log),
               "--output-file", str(out)]
    for name, value in start_values:
        command += ["--start-value", name, value]
    done = subprocess.run(command + [str(fmu)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, (done.stdout + done.stderr)[-2000:]
    result = np.genfromtxt(out, delimiter=",", names=True)
    return result[result["time"] <= stop * (1 + 1e-12)]


@pytest.mark.parametrize("fmu", FMUS, ids=[f.stem for f in FMUS])
def test_the_default_experiment_matches_fmpy(fmu, tmp_path):
    assert_default_experiment_matches_fmpy(
        fmu, lambda step, stop: fmusim(fmu, tmp_path, step, stop), 1e-12)


def test_a_start_value_from_the_command_line(tmp_path):
    """Oracle: paper L, Table 1 (vc = 0.146 m/s, Dahl): FT_mean 0.0109 N to its three digits, and
    S 44.4 % within 0.4 percentage points."""
    fmu = FMU_DIR / "variants" / "Table1Dahl.fmu"
    md = fmpy.read_model_description(str(fmu))
    step, stop = float(md.defaultExperiment.stepSize), float(md.defaultExperiment.stopTime)
    result = fmusim(fmu, tmp_path, step, stop, ("vc", "0.146"))
    assert result["time"][-1] == pytest.approx(stop, rel=1e-12)
    assert 0.01085 <= result["FT_mean"][-1] < 0.01095
    assert result["S"][-1] == pytest.approx(44.4, abs=0.4)
