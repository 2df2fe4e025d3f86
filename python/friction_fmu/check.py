"""Up-front checks of a sweep against the FMU's modelDescription, before any point runs.

A misspelt name, switch item or number would fail every point the same way (or, for a
plot's axis, fail after the whole sweep has run): each is refused here with a one-line
ValueError saying what was given and what was expected.
"""
import argparse
import math
import zipfile

import fmpy

from . import switches
from .runner import experiment_times, start_values

# Communication steps of one point at most: more is a mistyped time (1e300 s, a 1e-300 s step),
# not a sweep anyone waits for.
MAX_STEPS = 10**8
SETTABLE = ("parameter", "input")


def model_description(fmu):
    """fmpy's reading of the .fmu at `fmu`, refusing a file that is not an FMU in one line."""
    try:
        with zipfile.ZipFile(fmu) as archive:
            archive.getinfo("modelDescription.xml")
    except zipfile.BadZipFile:
        raise ValueError(f"{fmu}: not an FMU (not a zip archive)") from None
    except KeyError:
        raise ValueError(f"{fmu}: not an FMU (no modelDescription.xml in the archive)") from None
    try:
        return fmpy.read_model_description(fmu)
    except Exception as error:  # fmpy's XML and schema errors span several lines
        said = "; ".join(line.strip() for line in str(error).splitlines() if line.strip())
        raise ValueError(f"{fmu}: modelDescription.xml: {said}") from None


def plan(md, plan):
    """Names, values and time references of `plan` against the modelDescription `md`."""
    variables = {v.name: v for v in md.modelVariables}
    names = [*plan.grid, *plan.fixed, *(o.variable for o in plan.outputs)]
    unknown = [n for n in names if n not in variables]
    if unknown:
        raise ValueError(f"the FMU has no variable {', '.join(map(repr, unknown))}")
    for name in [*plan.grid, *plan.fixed]:
        if variables[name].causality not in SETTABLE:
            settable = [n for n, v in variables.items() if v.causality in SETTABLE]
            raise ValueError(f"{name} is {_kind(variables[name])}; --grid and --set take "
                             f"parameters and inputs: {', '.join(settable)}")
    for name, values in plan.grid.items():
        for value in values:
            _value(variables[name], value)
    for name, value in plan.fixed.items():
        _value(variables[name], value)
    # a time N/PARAM is divided by the point's PARAM, or by its start value when not set
    spans = [(f"stop time {plan.stop_time}", plan.stop_time), (f"step {plan.step}", plan.step),
             *((f"output {o.column}", o.window) for o in plan.outputs)]
    for what, span in spans:
        if span is None or span.per is None:
            continue
        if span.per not in variables:
            raise ValueError(f"{what}: {span.per!r} is not a variable of the FMU")
        if variables[span.per].causality not in SETTABLE:
            raise ValueError(f"{what}: {span.per} is {_kind(variables[span.per])}; N/PARAM "
                             "divides by a parameter")


def ranges(md, plan):
    """Every number of the grid and --set within its variable's declared min and max. Not a
    part of `plan`: such a value fails only its own points, each refused by the FMU with its
    own message; the command line refuses it before a sweep that would waste those runs."""
    variables = {v.name: v for v in md.modelVariables}
    for name, values in [*plan.grid.items(), *((n, [v]) for n, v in plan.fixed.items())]:
        var = variables[name]
        low, high = _bound(var, "min"), _bound(var, "max")
        for value in values:
            if _is_number(value) and not _within(value, low, high):
                bounds = " <= ".join(b for b in (low, name, high) if b is not None)
                unit = _unit(var)
                raise ValueError(f"{name} = {value!r} is outside the declared range: expected "
                                 f"{bounds}" + (f" ({unit})" if unit else ""))


def view(plan, x, y, column, fixed):
    """The plot's axes (`y` None: a line plot), color column and pinned axes."""
    axes = list(plan.grid)
    for flag, name in [("--x", x), ("--y", y), *(("--fix", n) for n in fixed)]:
        if name is not None and name not in plan.grid:
            raise ValueError(f"{flag} {name}: not a grid axis (axes: {', '.join(axes)})")
    if x == y:
        raise ValueError(f"--x and --y are both {x}: give two different grid axes")
    for name, value in fixed.items():
        if name in (x, y):
            raise ValueError(f"--fix {name}: it is the plot's {'x' if name == x else 'y'} "
                             "axis, so it cannot be pinned")
        if value not in plan.grid[name]:
            raise ValueError(f"--fix {name}={value}: not a value of that axis "
                             f"({', '.join(map(str, plan.grid[name]))})")
    columns = [o.column for o in plan.outputs]
    if column not in columns:
        raise ValueError(f"--color {column}: not an output column ({', '.join(columns)})")


def times(md, plan):
    """Every point's stop time and step (after `plan`): finite, in order, and at most
    MAX_STEPS apart."""
    starts = start_values(md)
    stop_text, step_text = plan.stop_time or "DefaultExperiment", plan.step or "DefaultExperiment"
    for point in plan.points():
        values = {**starts, **plan.fixed, **point.values}
        start, stop, step = experiment_times(md, plan, values)
        if not (math.isfinite(stop) and stop > start):
            raise ValueError(f"stop time {stop_text} is {stop!r} s{_at(values, plan.stop_time)}: "
                             f"expected a finite time after the start, {start:g} s")
        if not (math.isfinite(step) and step > 0):
            raise ValueError(f"step {step_text} is {step!r} s{_at(values, plan.step)}: expected "
                             "a finite step > 0")
        steps = (stop - start) / step
        if steps > MAX_STEPS:
            raise ValueError(f"stop time {stop:g} s at a step of {step:g} s"
                             f"{_at(values, plan.stop_time, plan.step)} is {steps:.3g} "
                             f"communication steps a point: at most {MAX_STEPS:.0e} are allowed "
                             "(a shorter --stop-time or a longer --step)")


def _at(values, *spans):
    """" at f = 3000.0": the values the spans N/PARAM were divided by at the point."""
    pers = sorted({s.per for s in spans if s is not None and s.per})
    return "".join(f" at {p} = {values[p]}" for p in pers)


def _value(var, value):
    """One value for `var`, by its type: Real a finite number, Integer a whole number, Boolean
    true/false/1/0, a switch an item's name or number."""
    items = switches.items(var)
    if items is not None:
        if value in items or (_is_number(value) and value in items.values()):
            return
        listed = ", ".join(f"{name} ({number})" for name, number in items.items())
        raise ValueError(f"{var.name} = {value!r}: expected one of {listed}")
    if var.type == "Boolean":
        if str(value).lower() in ("true", "false", "1", "0", "1.0", "0.0"):
            return
        raise ValueError(f"{var.name} = {value!r}: expected true or false")
    if not _is_number(value):
        raise ValueError(f"{var.name} = {value!r}: expected a number")
    if not math.isfinite(value):
        raise ValueError(f"{var.name} = {value!r}: expected a finite number")
    if var.type == "Integer" and value != int(value):
        raise ValueError(f"{var.name} = {value!r}: expected a whole number")


def _kind(var):
    """What a variable that cannot be set is, for a message: "an output", ..."""
    article = "an" if var.causality[0] in "aeiou" else "a"
    return f"{article} {var.causality}"


def _bound(var, which):
    """The variable's own min or max, else its declared type's, as written (None: none)."""
    own = getattr(var, which, None)
    return own if own is not None else getattr(var.declaredType, which, None)


def _within(value, low, high):
    return (low is None or float(low) <= value) and (high is None or value <= float(high))


def _unit(var):
    return getattr(var, "unit", None) or getattr(var.declaredType, "unit", None)


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def positive_seconds(text):
    """An argparse type: a finite number of seconds > 0, or a one-line refusal."""
    try:
        seconds = float(text)
    except ValueError:
        seconds = math.nan
    if not (math.isfinite(seconds) and seconds > 0):
        raise argparse.ArgumentTypeError(f"{text!r}: expected a finite number of seconds > 0")
    return seconds
