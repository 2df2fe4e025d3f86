"""DryFrictionOscillator through FMI (fmpy): the paper's set-up, the exact switch model against
an independent reference, and the regularised laws against the exact one as D shrinks.

Reference data: tests/reference/oscillator/ (make_reference.py: scipy DOP853, rtol = atol = 1e-12,
event location, written independently of the Rust code). The tests read its CSVs, never rerun it.
"""
import csv
import math
import shutil

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

import conftest

MODEL = "DryFrictionOscillator"
REFERENCE = conftest.ROOT / "tests" / "reference" / "oscillator"
REGULARISED = ["linear", "trigonometric", "linear_stiction", "trigonometric_stiction"]
WIDTHS = [0.8, 0.2, 0.05, 0.01]


def reference_cases():
    with open(REFERENCE / "cases.csv") as f:
        return {row["case"]: row for row in csv.DictReader(f)}


def reference_sticks(case):
    with open(REFERENCE / "stick_intervals.csv") as f:
        return [(float(r["start"]), float(r["end"])) for r in csv.DictReader(f) if r["case"] == case]


def law(item):
    return conftest.enum_value(MODEL, "law", item)


def case_values(row):
    """FMU start values for a reference case; ha = h Da/D sets the breakaway force hs."""
    h, hs = float(row["h"]), float(row["hs"])
    values = {"law": law(row["law"]), "P": float(row["P"]), "w": float(row["w"]), "h": h,
              "c": float(row["c"]), "k": float(row["k"]), "m": float(row["m"])}
    if h > 0:
        values["Da"] = 0.8 * (hs - h) / h
    return values


def final_amplitude(start_values, periods=60, w=1.0):
    """u_amplitude at the end of `periods` forcing periods (output once a period)."""
    T = 2 * math.pi / w
    result = conftest.simulate(MODEL, start_values=start_values, stop_time=periods * T,
                               step=T, outputs=["u_amplitude"])
    return result["u_amplitude"][-1]


def test_paper_setup_extremes():
    """Oracles: the laws' definitions (|H| <= h, or h + ha with stiction, eq. 4-9) and the exact
    reference for the steady extremes of u and u' (the regularised laws at the paper's D = 0.8
    stay within 1 % of the exact motion; the steady motion is odd-symmetric). Default
    experiment: 60 periods from rest, sampled every 1/100 period."""
    ref = reference_cases()
    T = 2 * math.pi
    print(f"\n{'law':<24}{'u min':>10}{'u max':>10}{'v min':>10}{'v max':>10}{'H min':>10}{'H max':>10}")
    for item in REGULARISED + ["exact"]:
        r = conftest.simulate(MODEL, start_values={"law": law(item)}, step=T / 100,
                              outputs=["u", "v", "H"])
        last = r[r["time"] >= r["time"][-1] - 2 * T - 1e-9]
        u, v, H = last["u"], last["v"], last["H"]
        print(f"{item:<24}{u.min():10.4f}{u.max():10.4f}{v.min():10.4f}{v.max():10.4f}"
              f"{H.min():10.4f}{H.max():10.4f}")
        bound = 1.6 * (2 if item.endswith("stiction") else 1)
        assert np.all(np.abs(H) <= bound * (1 + 1e-12)), item
        assert H.max() > 0.99 * 1.6 and H.min() < -0.99 * 1.6, item
        oracle = ref["paper_stiction" if item.endswith("stiction") else "paper"]
        for x, name in [(u, "amplitude"), (v, "velocity_amplitude")]:
            expected = float(oracle[name])
            assert abs(x.max() / expected - 1) < 1e-2, (item, name, x.max(), expected)
            assert abs(-x.min() / expected - 1) < 1e-2, (item, name, x.min(), expected)


@pytest.mark.parametrize("case", ["paper", "low_w", "high_w", "stiction_low_w"])
def test_exact_steady_amplitude_matches_reference(case):
    """Oracle: the scipy event-driven reference. u_amplitude (max |u| over the last complete
    period) to rel. 1e-6."""
    row = reference_cases()[case]
    w, periods = float(row["w"]), int(row["periods"])
    amplitude = final_amplitude(case_values(row), periods, w)
    expected = float(row["amplitude"])
    print(f"\n{case}: FMU {amplitude!r}, reference {expected!r}, rel. {amplitude / expected - 1:.2e}")
    assert abs(amplitude / expected - 1) < 1e-6


class Instance:
    """A bare FMU2Slave to step to arbitrary times."""

    def __init__(self, start_values):
        path = conftest.fmu_path(MODEL)
        self.md = read_model_description(path)
        self.dir = extract(path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.fmu = FMU2Slave(guid=self.md.guid, unzipDirectory=self.dir,
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName="oscillator")
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.enterInitializationMode()
        for name, value in start_values.items():
            if isinstance(value, int) and name == "law":
                self.fmu.setInteger([self.vr[name]], [value])
            else:
                self.fmu.setReal([self.vr[name]], [value])
        self.fmu.exitInitializationMode()
        self.t = 0.0

    def step_to(self, t, longest):
        while self.t < t:
            h = min(longest, t - self.t)
            self.fmu.doStep(currentCommunicationPoint=self.t, communicationStepSize=h)
            self.t += h

    def real(self, name):
        return self.fmu.getReal([self.vr[name]])[0]

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.dir, ignore_errors=True)


@pytest.mark.parametrize("case", ["low_w", "high_w", "stiction_low_w"])
def test_exact_stick_intervals_match_reference(case):
    """Oracle: the scipy reference's stuck phases in the last two periods. Each starts and ends
    within 1e-6 s of the reference: the FMU, stepped to 1e-6 before and after each reference
    event (events inside communication steps), is sliding (u' != 0) / stuck (u' == 0, |H| <= hs)
    on the right side."""
    row = reference_cases()[case]
    sticks = reference_sticks(case)
    assert len(sticks) >= 2
    T = 2 * math.pi / float(row["w"])
    delta = 1e-6
    fmu = Instance(case_values(row))
    try:
        for start, end in sticks:
            fmu.step_to(start - delta, T / 8)
            assert fmu.real("v") != 0.0, (case, "sliding before", start)
            fmu.step_to(start + delta, T / 8)
            assert fmu.real("v") == 0.0, (case, "stuck after", start)
            fmu.step_to(end - delta, T / 8)
            assert fmu.real("v") == 0.0, (case, "stuck before", end)
            assert abs(fmu.real("H")) <= float(row["hs"]) * (1 + 1e-12)
            fmu.step_to(end + delta, T / 8)
            assert fmu.real("v") != 0.0, (case, "sliding after", end)
    finally:
        fmu.close()


def test_regularised_error_shrinks_with_D():
    """Oracle: the FMU's `exact` law (itself checked against the reference above; the stiction
    laws against `exact_stiction` with Da = D, so ha = h and the limit stays fixed). The relative
    error of the steady amplitude must shrink as D shrinks, for every law. Whether the
    trigonometric forms beat the linear ones (the paper's claim) is printed, not asserted."""
    exact = {
        "exact": final_amplitude({"law": law("exact")}),
        "exact_stiction": final_amplitude({"law": law("exact_stiction"), "Da": 0.8}),
    }
    table = {}
    for item in REGULARISED:
        oracle = exact["exact_stiction" if item.endswith("stiction") else "exact"]
        table[item] = [final_amplitude({"law": law(item), "D": d, "Da": d}) / oracle - 1
                       for d in WIDTHS]
    print("\nrelative error of the steady amplitude against exact (paper's set-up, Da = D)")
    print(f"{'law / D':<24}" + "".join(f"{d:>12}" for d in WIDTHS))
    for item, errors in table.items():
        print(f"{item:<24}" + "".join(f"{e:12.3e}" for e in errors))
    for plain, trig in [("linear", "trigonometric"), ("linear_stiction", "trigonometric_stiction")]:
        wins = sum(abs(b) < abs(a) for a, b in zip(table[plain], table[trig]))
        print(f"{trig} closer than {plain} at {wins} of {len(WIDTHS)} widths")
    for item, errors in table.items():
        magnitudes = [abs(e) for e in errors]
        assert all(b < a for a, b in zip(magnitudes, magnitudes[1:])), (item, errors)


@pytest.mark.parametrize("item", ["linear", "trigonometric"])
def test_stiff_regularisation_is_stable_and_accurate(item):
    """Oracle: the scipy reference (paper case). At D = 1e-6 (slope h/D = 1.6e6) and the
    default communication step, the default solver converges to the exact amplitude."""
    expected = float(reference_cases()["paper"]["amplitude"])
    amplitude = final_amplitude({"law": law(item), "D": 1e-6})
    assert abs(amplitude / expected - 1) < 1e-6, amplitude


def test_force_from_input_matches_prescribed_force():
    """Oracle: the prescribed forcing. P_in = 4 sin(t) fed from outside (held over 0.01 s steps)
    reproduces the prescribed run to the zero-order-hold error."""
    stop = 10 * 2 * math.pi
    t = np.arange(0.0, stop + 0.01, 0.01)
    signal = np.array(list(zip(t, 4 * np.sin(t + 0.005))), dtype=[("time", float), ("P_in", float)])
    inputs = {"law": law("exact"), "force_source": conftest.enum_value(MODEL, "force_source", "input")}
    fed = conftest.simulate(MODEL, start_values=inputs, stop_time=stop, step=0.01,
                            outputs=["u"], input=signal)
    own = conftest.simulate(MODEL, start_values={"law": law("exact")}, stop_time=stop, step=0.01,
                            outputs=["u"])
    scale = np.abs(own["u"]).max()
    assert np.abs(fed["u"] - own["u"]).max() < 1e-3 * scale


def test_bad_parameter_is_refused():
    """Oracle: the interface's documented range (m > 0): the FMU refuses, it does not run."""
    with pytest.raises(Exception):
        conftest.simulate(MODEL, start_values={"m": 0.0}, stop_time=1.0, step=0.1)
