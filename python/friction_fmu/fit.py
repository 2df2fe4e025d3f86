"""Fits named parameters of an FMU to measured data: nonlinear least squares over the FMU.

    python -m friction_fmu.fit --fmu fmu-out/LongitudinalFriction.fmu --data table1.csv \\
        --set law=dahl --fit kt=5.6e4 --stop-time 1/f --out fmu-out/fits/dahl-kt
    python -m friction_fmu.fit ... --fit kt=5.6e4:1e3:1e7 --fit alpha=1   # bounds LO:HI
    python -m friction_fmu.fit ... --scheduler local:4    # the runs on a Dask LocalCluster

The data (--data, a CSV; friction_fmu.fit_data) is a table of experiments (one row each: the
parameters or inputs it set, the outputs measured at the end of its run) or a time series (a
`time` column, the measured outputs and the inputs at those times). Each evaluation of the
residuals runs every experiment of the table (or the series once) with the parameters' current
values, in parallel on the sweep tool's executors (local processes or Dask); the Jacobian is
central differences, every perturbed run of it in one parallel batch. The optimiser is
scipy.optimize.least_squares (trust region reflective, within each parameter's bounds).

Where a table's outputs are a period's summary (FT_mean, S, FFx_mean, u_amplitude) and the FMU
has a periodic start, every run starts on its periodic orbit (`initial = periodic`) unless
--set initial says otherwise, and reads its outputs in one communication step at the stop time.

Writes PREFIX.json (the parameters with their standard errors, the correlation matrix, residual
norms at the start and at the fit, the number of FMU runs), PREFIX.csv (measured beside fitted)
and PREFIX.png/.svg (measured and fitted against the experiment variable, residuals below).
Exit status: 0 the fit converged, 1 a run failed (the FMU's words on stderr) or the fit stopped
at --max-evaluations, 2 the arguments or the data were refused (before any run; a singular
Jacobian, after the first).
"""
import argparse
import concurrent.futures as cf
import csv
import json
import math
import os
import pathlib
import re
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from . import check, fit_data, switches
from .grid import Output, Plan, Point, Span, parse_assignment
from .progress import _clock
from .runner import RAN, FmuSource, Series, experiment_times, run_point, run_series, start_values
from .sweep import (CONNECT_TIMEOUT, _workers, dask_executor, executor_label, local_cluster_size,
                    local_executor, writable)

SUFFIXES = (".csv", ".png", ".svg", ".json")
SHOWN_WARNINGS = 3  # on stderr; the JSON has them all
DIFF_STEP = 1e-3  # relative step of the central differences: far above the solvers' 1e-8 noise
# A Jacobian whose smallest singular value is below this fraction of its largest has directions
# the outputs cannot tell apart (parameters that act only together, or not at all).
SINGULAR = 1e-8
# Outputs that are a period's summary, by their description (FT_mean, S, FFx_mean, u_amplitude)
PERIOD_SUMMARY = re.compile(r"\bmean\b|last complete .*period")


class Refused(ValueError):
    """Arguments or data the fit cannot start from: exit status 2."""


class RunFailed(Exception):
    """A run the FMU refused during the fit: exit status 1, with the FMU's words."""


@dataclass
class Parameter:
    name: str
    start: float
    low: float
    high: float
    unit: str | None = None

    @property
    def scale(self):
        """The optimiser works on value / scale: parameters of any magnitude (kt ~ 1e4 N/m,
        alpha ~ 1) are of order one to it."""
        return abs(self.start) or 1.0


def parse_fit(text, md, taken):
    """`NAME=START` or `NAME=START:LO:HI` (LO or HI empty: the declared bound) -> Parameter.
    `taken`: names the data or --set already give a value."""
    name, eq, spec = text.partition("=")
    name = name.strip()
    if not eq or not name or not spec.strip():
        raise Refused(f"--fit {text}: expected NAME=START or NAME=START:LO:HI")
    variables = {v.name: v for v in md.modelVariables}
    var = variables.get(name)
    if var is None:
        real = [n for n, v in variables.items() if v.causality == "parameter" and v.type == "Real"]
        raise Refused(f"--fit {text}: the FMU has no variable {name!r} (its Real parameters: "
                      f"{', '.join(real)})")
    if var.causality != "parameter" or var.type != "Real":
        kind = f"{'an' if var.causality[0] in 'aeiou' else 'a'} {var.causality}"
        what = kind if var.causality != "parameter" else f"an {var.type} parameter"
        raise Refused(f"--fit {text}: {name} is {what}; a fit varies Real parameters")
    if name in taken:
        raise Refused(f"--fit {text}: {name} is also given by {taken[name]}: a fitted "
                      "parameter takes its values from the fit")
    parts = spec.split(":")
    if len(parts) not in (1, 3):
        raise Refused(f"--fit {text}: expected NAME=START or NAME=START:LO:HI")
    declared = [_float(check._bound(var, "min"), -math.inf),
                _float(check._bound(var, "max"), math.inf)]
    numbers = []
    for k, part in enumerate(parts):
        if k > 0 and not part.strip():
            numbers.append(declared[k - 1])
            continue
        try:
            number = float(part)
        except ValueError:
            number = math.nan
        if not math.isfinite(number):
            raise Refused(f"--fit {text}: {part.strip()!r} is not a finite number")
        numbers.append(number)
    start, low, high = (numbers + declared)[:3]
    unit = check._unit(var)
    unit_text = f" ({unit})" if unit else ""
    if low < declared[0] or high > declared[1]:
        raise Refused(f"--fit {text}: the bounds {low:g}:{high:g} reach outside {name}'s "
                      f"declared range {_range(name, *declared)}{unit_text}")
    if not low < high:
        raise Refused(f"--fit {text}: the lower bound {low:g} is not below the upper {high:g}")
    if not low <= start <= high:
        raise Refused(f"--fit {text}: the start {start:g} is outside the range: expected "
                      f"{_range(name, low, high)}{unit_text}")
    return Parameter(name, start, low, high, unit)


def _float(text, default):
    return default if text is None else float(text)


def _range(name, low, high):
    return " <= ".join([*([f"{low:g}"] if low > -math.inf else []), name,
                        *([f"{high:g}"] if high < math.inf else [])])


@dataclass
class Problem:
    """What one evaluation runs: the FMU (`shipped` to the workers), the data, the fixed
    values, and the plan of a table's runs (outputs, stop time, step)."""

    data: fit_data.Data
    parameters: list
    fixed: dict
    plan: Plan | None  # a table's runs; None for a series
    weights: dict = field(default_factory=dict)  # output -> the scale its residuals divide by

    def tasks(self, shipped, values):
        """The runs of one evaluation at the parameter `values` (name -> float): (function,
        arguments) each."""
        data = self.data
        if data.form == "series":
            inputs = {n: tuple(vs) for n, vs in data.settings.items()}
            series = Series(tuple(data.times), inputs, {**self.fixed, **values},
                            tuple(data.measured))
            return [(run_series, (shipped, series))]
        return [(run_point, (shipped, self.plan,
                             Point(i, {**{n: vs[i] for n, vs in data.settings.items()}, **values})))
                for i in range(data.rows)]

    def outputs(self, rows):
        """{output: array over the data's rows} from the rows of one evaluation's runs."""
        if self.data.form == "series":
            return {o: np.array(rows[0][o], dtype=float) for o in self.data.measured}
        return {o: np.array([row[o] for row in rows], dtype=float) for o in self.data.measured}

    def residuals(self, outputs):
        """(fitted - measured) / weight, the outputs one after the other."""
        return np.concatenate([(outputs[o] - np.asarray(m)) / self.weights[o]
                               for o, m in self.data.measured.items()])


def weights(measured):
    """Each output's residuals divide by the root mean square of its measured values, so outputs
    in different units (N and %) weigh alike; one output's scale changes no estimate."""
    result = {}
    for name, values in measured.items():
        rms = math.sqrt(sum(v * v for v in values) / len(values))
        result[name] = rms or 1.0
    return result


class Runner:
    """Runs batches of FMU runs on an executor, in parallel; counts them; shows progress."""

    def __init__(self, executor, shipped, problem, progress):
        self.executor, self.shipped, self.problem = executor, shipped, problem
        self.progress = progress
        self.runs = 0
        self.warnings = []

    def evaluate(self, value_sets, phase):
        """The outputs at each of `value_sets` (a list of {name: value}); raises RunFailed
        naming the run and with the FMU's words when any run fails."""
        batches = [self.problem.tasks(self.shipped, values) for values in value_sets]
        futures = [[self.executor.submit(fn, *args) for fn, args in batch] for batch in batches]
        self.progress.phase(phase)
        results = []
        for values, batch in zip(value_sets, futures):
            rows = []
            for future in batch:
                row = future.result()
                self.runs += 1
                self.progress.ran(self.runs)
                if row["status"] not in RAN:
                    for other in (f for b in futures for f in b):
                        other.cancel()
                    raise RunFailed(self.describe(row, values))
                if row["status"] == "warning" and row["message"] not in self.warnings:
                    self.warnings.append(row["message"])
                rows.append(row)
            results.append(self.problem.outputs(rows))
        return results

    def describe(self, row, values):
        settings = {k: v for k, v in row.items() if k in self.problem.data.settings}
        at = ", ".join(f"{k} = {v:g}" if isinstance(v, float) else f"{k} = {v}"
                       for k, v in {**settings, **values}.items())
        what = "the run" if self.problem.data.form == "series" else f"experiment {row['point'] + 1}"
        return f"{what} at {at} failed ({row['status']}): {row['message']}"


class Line:
    """The progress line on stderr: the phase, runs so far, the residual norm, elapsed time.
    Redrawn in place on a terminal; elsewhere a plain line at most every `every` seconds."""

    def __init__(self, enabled=True, stream=None, every=5.0):
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.live = self.stream.isatty()
        self.every = 0.2 if self.live else every
        self.began = time.monotonic()
        self._shown = -math.inf
        self.text, self.runs, self.norm = "", 0, None

    def phase(self, text):
        self.text = text
        self._draw()

    def ran(self, runs):
        self.runs = runs
        self._draw()

    def residual(self, norm):
        self.norm = norm

    def _draw(self, force=False):
        now = time.monotonic()
        if not self.enabled or (not force and now - self._shown < self.every):
            return
        self._shown = now
        norm = f", residual norm {self.norm:.4g}" if self.norm is not None else ""
        line = (f"{self.text}: {self.runs} runs{norm}, elapsed "
                f"{_clock(now - self.began)}")
        if self.live:
            self.stream.write(f"\r{line}\033[K")
        else:
            self.stream.write(line + "\n")
        self.stream.flush()

    def close(self):
        self._draw(force=True)
        if self.enabled and self.live:
            self.stream.write("\n")
            self.stream.flush()


class Objective:
    """The residuals and their Jacobian for scipy.optimize.least_squares, in the scaled
    variables u = value / scale. The residuals at the last point are kept: least_squares asks
    for the Jacobian where it has just evaluated them, and the central differences need no
    run there."""

    def __init__(self, problem, runner, diff_step):
        self.problem, self.runner, self.diff_step = problem, runner, diff_step
        self.parameters = problem.parameters
        self.scale = np.array([p.scale for p in self.parameters])
        self.low = np.array([p.low for p in self.parameters])
        self.high = np.array([p.high for p in self.parameters])
        self.evaluations = self.jacobians = 0
        self._last = None
        self.first_jacobian_checked = False

    def values(self, x):
        return {p.name: float(v) for p, v in zip(self.parameters, x)}

    def residuals(self, u):
        x = np.clip(u * self.scale, self.low, self.high)
        key = x.tobytes()
        if self._last is None or self._last[0] != key:
            self.evaluations += 1
            outputs, = self.runner.evaluate([self.values(x)],
                                            f"evaluation {self.evaluations}")
            self._last = (key, self.problem.residuals(outputs), outputs)
            self.runner.progress.residual(float(np.linalg.norm(self._last[1])))
        return self._last[1]

    def outputs(self, x):
        self.residuals(np.asarray(x) / self.scale)
        return self._last[2]

    def jacobian(self, u):
        x = np.clip(u * self.scale, self.low, self.high)
        r0 = self.residuals(u)
        steps, sets = [], []
        for j, p in enumerate(self.parameters):
            h = self.diff_step * (abs(x[j]) or self.scale[j])
            up, down = x[j] + h, x[j] - h
            # central where both sides are within bounds, else one-sided, inwards
            if up > p.high:
                up = x[j]
            elif down < p.low:
                down = x[j]
            steps.append((up, down))
            for v in (up, down):
                if v != x[j]:
                    sets.append(self.values(np.where(np.arange(len(x)) == j, v, x)))
        self.jacobians += 1
        results = iter(self.runner.evaluate(sets, f"Jacobian {self.jacobians}"))
        columns = []
        for j, (up, down) in enumerate(steps):
            r_up = self.problem.residuals(next(results)) if up != x[j] else r0
            r_down = self.problem.residuals(next(results)) if down != x[j] else r0
            columns.append((r_up - r_down) / (up - down) * self.scale[j])
        jac = np.column_stack(columns)
        if not self.first_jacobian_checked:
            self.first_jacobian_checked = True
            singular(jac, [p.name for p in self.parameters], self.values(x))
        return jac


def singular(jac, names, values):
    """Refuses a Jacobian with a zero column (an output that does not depend on a parameter) or
    of deficient rank (parameters whose effects cannot be told apart)."""
    norms = np.linalg.norm(jac, axis=0)
    at = ", ".join(f"{n} = {v:g}" for n, v in values.items())
    top = norms.max() if norms.size else 0.0
    for name, norm in zip(names, norms):
        if norm == 0.0 or norm < SINGULAR * top:
            raise Refused(f"the outputs do not depend on {name} (the Jacobian at {at} has a zero "
                          f"column for it: changing {name} by {DIFF_STEP:g} of its value changed "
                          "no measured output); fit other parameters, or data that depend on "
                          f"{name}")
    s = np.linalg.svd(jac, compute_uv=False)
    if s[-1] < SINGULAR * s[0]:
        _, _, vt = np.linalg.svd(jac)
        together = [n for n, c in zip(names, vt[-1]) if abs(c) > 0.1]
        raise Refused(f"the Jacobian at {at} is singular (condition number {s[0] / s[-1]:.3g}):"
                      f" the outputs cannot tell {' and '.join(together)} apart; fit fewer "
                      "parameters or add data that separate them")


def statistics(result, objective, measured_count):
    """Standard errors and correlations of the parameters from the Jacobian at the fit: the
    covariance s^2 (J^T J)^-1, s^2 the residuals' sum of squares over the degrees of freedom."""
    n = len(objective.parameters)
    dof = measured_count - n
    jac = result.jac
    _, s, vt = np.linalg.svd(jac, full_matrices=False)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        # a direction the data no longer fix at the fit (s = 0) has an infinite error
        inverse = (vt.T / s**2) @ vt
        s2 = 2 * result.cost / dof if dof > 0 else math.nan
        covariance = s2 * inverse * np.outer(objective.scale, objective.scale)
        stderr = np.sqrt(np.diag(covariance))
        d = np.sqrt(np.diag(inverse))
        correlation = inverse / np.outer(d, d)
    return stderr, correlation, dof


def out_paths(out, model):
    """As the sweep tool's --out: a directory holds MODEL-fit.*; a final .csv (.png, .svg,
    .json) is dropped and any other dot kept."""
    prefix = pathlib.Path(out)
    if out.endswith(("/", os.sep)) or prefix.is_dir():
        prefix = prefix / f"{model}-fit"
    elif prefix.suffix in SUFFIXES:
        prefix = prefix.with_suffix("")
    return {suffix: prefix.with_name(prefix.name + suffix) for suffix in SUFFIXES}


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise Refused(f"{message} (see --help)")


def _positive(text):
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and 0 < value < 1):
        raise argparse.ArgumentTypeError(f"{text!r}: expected a number between 0 and 1")
    return value


def _count(text):
    if not text.strip().isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a whole number >= 1")
    return int(text)


def parse_args(argv):
    p = _Parser(prog="python -m friction_fmu.fit", description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--fmu", required=True, help="the .fmu (full model or variant)")
    p.add_argument("--data", required=True, help="CSV: a table of experiments, or a time "
                                                 "series with a `time` column")
    p.add_argument("--fit", action="append", required=True, metavar="NAME=START[:LO:HI]",
                   help="a Real parameter to fit, from START, within LO..HI (default: its "
                        "declared range); repeat for more")
    p.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                   help="a fixed parameter or input (switch items by name or number)")
    p.add_argument("--stop-time", help="a table's run length: seconds or N/PARAM, e.g. 40/f "
                                       "(default: DefaultExperiment)")
    p.add_argument("--step", help="a table's communication step, seconds or N/PARAM (default: "
                                  "the stop time, one step: only the end is read)")
    p.add_argument("--workers", type=_workers, help="local processes (default: os.cpu_count())")
    p.add_argument("--scheduler", help="Dask: local[:N] or a scheduler address, as the sweep")
    p.add_argument("--connect-timeout", type=check.positive_seconds, default=CONNECT_TIMEOUT,
                   metavar="SECONDS")
    p.add_argument("--ship", choices=["bytes", "path"],
                   help="send the FMU as bytes or by path (default: path locally, bytes on Dask)")
    p.add_argument("--diff-step", type=_positive, default=DIFF_STEP,
                   help=f"relative step of the Jacobian's differences (default {DIFF_STEP:g})")
    p.add_argument("--max-evaluations", type=_count,
                   help="evaluations of the residuals at most (default: 100 per parameter)")
    p.add_argument("--out", default="fmu-out/fits/fit",
                   help="output prefix, or a directory (DIR/ writes DIR/MODEL-fit.*)")
    p.add_argument("--quiet", action="store_true", help="no start line or progress")
    return p.parse_args(argv)


@dataclass
class Command:
    args: argparse.Namespace
    md: object
    data: fit_data.Data
    problem: Problem
    paths: dict
    workers: int
    notes: list


def prepare(argv):
    """The command line and the data, checked before any run; raises Refused (ValueError) or
    OSError for the first thing wrong."""
    args = parse_args(argv)
    try:
        import scipy.optimize  # noqa: F401
    except ImportError:
        raise Refused("the fit needs scipy: pip install -e 'python[fit]'") from None
    md = check.model_description(args.fmu)
    data = fit_data.read(args.data, md)
    fixed = {}
    for text in args.set:
        name, values = parse_assignment(text)
        if len(values) != 1:
            raise Refused(f"--set {text}: one value expected")
        if name in data.settings or name in data.measured:
            raise Refused(f"--set {text}: {name} is a column of {data.path}")
        fixed[name] = values[0]
    taken = {**{n: data.path for n in [*data.settings, *data.measured]},
             **{n: "--set" for n in fixed}}
    parameters = []
    for text in args.fit:
        parameter = parse_fit(text, md, taken)
        taken[parameter.name] = "another --fit"
        parameters.append(parameter)
    count = sum(len(vs) for vs in data.measured.values())
    if len(parameters) > count:
        raise Refused(f"{len(parameters)} parameters to fit from {count} measured value"
                      f"{'s' * (count != 1)} in {data.path}: give more data or fewer --fit")
    stop, step = Span.parse(args.stop_time), Span.parse(args.step)
    notes = []
    outputs = [Output(o) for o in data.measured]
    grid = {n: list(vs) for n, vs in data.settings.items()}
    try:  # the data's settings: their values and declared ranges, the file named
        check.plan(md, Plan(grid=grid))
        check.ranges(md, Plan(grid=grid))
    except ValueError as error:
        raise Refused(f"{data.path}: {error}") from None
    check.plan(md, Plan(fixed=fixed, outputs=outputs, stop_time=stop, step=step))
    check.ranges(md, Plan(fixed=fixed))
    plan = None
    if data.form == "series":
        if stop is not None or step is not None:
            raise Refused("--stop-time and --step are a table's: a time series runs along its "
                          "own times")
    else:
        variables = {v.name: v for v in md.modelVariables}
        initial = variables.get("initial")
        items = switches.items(initial) if initial is not None else None
        summaries = [o for o in data.measured
                     if PERIOD_SUMMARY.search(variables[o].description or "")]
        if items and "periodic" in items and "initial" not in fixed \
                and "initial" not in data.settings and summaries:
            fixed["initial"] = "periodic"
            notes.append(f"initial = periodic ({', '.join(summaries)}: a period's summary)")
        if stop is None:
            stop = Span(float(md.defaultExperiment.stopTime))
        plan = Plan(fixed=fixed, outputs=outputs, stop_time=stop, step=step or stop)
        _check_times(md, plan, data, parameters)
    if args.workers is not None and args.scheduler is not None:
        raise Refused("--workers sizes the local process pool: with --scheduler, give local:N "
                      "or size the cluster")
    local_cluster_size(args.scheduler)
    paths = out_paths(args.out, pathlib.Path(args.fmu).stem)
    writable(paths, args.out)
    problem = Problem(data, parameters, fixed, plan, weights(data.measured))
    batch = (2 * len(parameters)) * (data.rows if data.form == "table" else 1)
    workers = min(args.workers or os.cpu_count() or 1, batch)
    return Command(args, md, data, problem, paths, workers, notes)


def _check_times(md, plan, data, parameters):
    """Every experiment's stop time and step: finite, positive, at most check.MAX_STEPS."""
    starts = {**start_values(md), **plan.fixed, **{p.name: p.start for p in parameters}}
    for i in range(data.rows):
        values = {**starts, **{n: vs[i] for n, vs in data.settings.items()}}
        start, stop, step = experiment_times(md, plan, values)
        if not (math.isfinite(stop) and stop > start):
            raise Refused(f"stop time {plan.stop_time} is {stop!r} s at experiment {i + 1}: "
                          "expected a finite time after the start")
        if not (math.isfinite(step) and step > 0):
            raise Refused(f"step {plan.step} is {step!r} s at experiment {i + 1}: expected a "
                          "finite step > 0")
        if (stop - start) / step > check.MAX_STEPS:
            raise Refused(f"stop time {stop:g} s at a step of {step:g} s is more than "
                          f"{check.MAX_STEPS:.0e} communication steps a run")


def fit(command, executor, shipped, progress):
    """Runs the fit; returns the result and what it took."""
    from scipy.optimize import least_squares

    problem = command.problem
    runner = Runner(executor, shipped, problem, progress)
    objective = Objective(problem, runner, command.args.diff_step)
    u0 = np.array([p.start for p in problem.parameters]) / objective.scale
    low, high = objective.low / objective.scale, objective.high / objective.scale
    start_residuals = objective.residuals(u0)
    start_outputs = objective._last[2]
    result = least_squares(objective.residuals, u0, jac=objective.jacobian, bounds=(low, high),
                           method="trf", x_scale=1.0,
                           max_nfev=command.args.max_evaluations)
    x = np.clip(result.x * objective.scale, objective.low, objective.high)
    fitted = objective.outputs(x)
    return {"result": result, "objective": objective, "runner": runner, "x": x,
            "fitted": fitted, "start_outputs": start_outputs,
            "start_residuals": start_residuals}


def summary(command, run, wall_time, executor):
    problem, data, md = command.problem, command.data, command.md
    result, objective, runner, x = run["result"], run["objective"], run["runner"], run["x"]
    measured_count = sum(len(v) for v in data.measured.values())
    stderr, correlation, dof = statistics(result, objective, measured_count)
    names = [p.name for p in problem.parameters]
    units = _units(md)

    def norms(outputs):
        per = {}
        for o, m in data.measured.items():
            r = outputs[o] - np.asarray(m)
            per[o] = {"rms": float(np.sqrt(np.mean(r**2))), "max_abs": float(np.abs(r).max()),
                      "unit": units.get(o)}
        return per

    return {
        "parameters": {
            p.name: {"value": float(v), "stderr": _number(e), "start": p.start,
                     "bounds": [_number(p.low), _number(p.high)], "unit": p.unit,
                     "at_bound": bool(result.active_mask[k] != 0)}
            for k, (p, v, e) in enumerate(zip(problem.parameters, x, stderr))},
        "correlation": {"parameters": names,
                        "matrix": [[_number(c) for c in row] for row in correlation]},
        "residual_norm": float(np.linalg.norm(problem.residuals(run["fitted"]))),
        "residual_norm_at_start": float(np.linalg.norm(run["start_residuals"])),
        "residuals": norms(run["fitted"]),
        "residuals_at_start": norms(run["start_outputs"]),
        "residual_weights": {o: w for o, w in problem.weights.items()},
        "degrees_of_freedom": dof,
        "fmu_runs": runner.runs,
        "evaluations": objective.evaluations,
        "jacobians": objective.jacobians,
        "converged": bool(result.status > 0),
        "optimizer": f"scipy.optimize.least_squares (trf): {result.message}",
        "warnings": runner.warnings,
        "fmu": os.path.abspath(command.args.fmu),
        "data": os.path.abspath(data.path),
        "form": data.form,
        "experiments": data.rows,
        "fixed": problem.fixed,
        "stop_time": str(problem.plan.stop_time) if problem.plan else None,
        "step": str(problem.plan.step) if problem.plan else None,
        "diff_step": command.args.diff_step,
        "executor": executor,
        "wall_time_s": wall_time,
    }


def _number(value):
    """JSON has no NaN or infinity: null stands for them."""
    value = float(value)
    return value if math.isfinite(value) else None


def _units(md):
    from .sweep import units_of
    return units_of(md)


def write_csv(path, data, fitted):
    """One row per experiment (or time): its settings, then each output measured, fitted and
    their difference (fitted - measured), at full precision."""
    names = [*(["time"] if data.form == "series" else []), *data.settings]
    for o in data.measured:
        names += [o, f"{o}:fitted", f"{o}:residual"]
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(names)
        for i in range(data.rows):
            row = [*([data.times[i]] if data.form == "series" else []),
                   *(vs[i] for vs in data.settings.values())]
            for o, m in data.measured.items():
                row += [m[i], float(fitted[o][i]), float(fitted[o][i] - m[i])]
            writer.writerow([repr(v) if isinstance(v, float) else v for v in row])


def main(argv=None):
    """The command; returns its exit status: 0 converged, 1 a run failed or no convergence,
    2 refused."""
    try:
        command = prepare(sys.argv[1:] if argv is None else argv)
    except (ValueError, OSError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    args, problem = command.args, command.problem
    label = executor_label(args.scheduler, command.workers)
    if not args.quiet:
        rows = command.data.rows
        what = (f"{rows} experiment{'s' * (rows != 1)}" if command.data.form == "table"
                else f"a time series of {command.data.rows} times")
        notes = "".join(f"; {n}" for n in command.notes)
        print(f"fitting {', '.join(p.name for p in problem.parameters)} of "
              f"{command.md.modelName} to {what} ({', '.join(command.data.measured)}) on "
              f"{label}{notes}, writing {command.paths['.json']} (and .csv, .png, .svg)",
              file=sys.stderr, flush=True)
    ship = args.ship or ("bytes" if args.scheduler is not None else "path")
    source = FmuSource.by_bytes(args.fmu) if ship == "bytes" else FmuSource.by_path(args.fmu)
    progress = Line(enabled=not args.quiet)
    began = time.perf_counter()
    try:
        executor_cm = (dask_executor(args.scheduler, args.connect_timeout)
                       if args.scheduler is not None else local_executor(command.workers))
        with executor_cm as (executor, place):
            try:
                run = fit(command, executor, place(source), progress)
            finally:
                progress.close()
    except Refused as error:  # a singular Jacobian: after the first, before any step
        print(f"error: {error}", file=sys.stderr)
        return 2
    except ValueError as error:  # a Dask scheduler that does not answer
        print(f"error: {error}", file=sys.stderr)
        return 2
    except RunFailed as error:
        print(f"error: {error}; the fit stopped, nothing written", file=sys.stderr)
        return 1
    except cf.CancelledError:
        print("error: the runs were cancelled", file=sys.stderr)
        return 1
    report = summary(command, run, time.perf_counter() - began, label)
    command.paths[".json"].write_text(json.dumps(report, indent=2) + "\n")
    write_csv(command.paths[".csv"], command.data, run["fitted"])
    from . import fit_plot  # matplotlib only once there is something to draw

    fit_plot.write(command.paths[".csv"].with_suffix(""), command.data, run["fitted"], report,
                   command.md.modelName, _units(command.md))
    for name, entry in report["parameters"].items():
        unit = f" {entry['unit']}" if entry["unit"] else ""
        error = f" +- {entry['stderr']:.3g}" if entry["stderr"] is not None else ""
        bound = " (at a bound)" if entry["at_bound"] else ""
        print(f"{name} = {entry['value']:.6g}{error}{unit}{bound}")
    print(f"residual norm {report['residual_norm']:.4g} (at the start "
          f"{report['residual_norm_at_start']:.4g}); {report['fmu_runs']} FMU runs in "
          f"{report['wall_time_s']:.2f} s on {label}")
    for text in report["warnings"][:SHOWN_WARNINGS]:
        print(f"warning: the FMU said: {text}", file=sys.stderr)
    if len(report["warnings"]) > SHOWN_WARNINGS:
        print(f"warning: and {len(report['warnings']) - SHOWN_WARNINGS} more warnings, in "
              f"{command.paths['.json']}", file=sys.stderr)
    if not report["converged"]:
        print(f"error: the fit did not converge: {run['result'].message}", file=sys.stderr)
    for path in command.paths.values():
        print(f"wrote {path}")
    return 0 if report["converged"] else 1


if __name__ == "__main__":
    sys.exit(main())
