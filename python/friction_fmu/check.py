"""Up-front checks of a sweep against the FMU's modelDescription, before any point runs.

A misspelt name, switch item or number would fail every point the same way (or, for a
heat map axis, fail after the whole sweep has run): each is refused here with a one-line
ValueError saying what was given and what was expected.
"""
import math

from . import switches


def plan(md, plan):
    """Names, values and time references of `plan` against the modelDescription `md`."""
    variables = {v.name: v for v in md.modelVariables}
    names = [*plan.grid, *plan.fixed, *(o.variable for o in plan.outputs)]
    unknown = [n for n in names if n not in variables]
    if unknown:
        raise ValueError(f"the FMU has no variable {', '.join(map(repr, unknown))}")
    for name, values in plan.grid.items():
        for value in values:
            _value(variables[name], value)
    for name, value in plan.fixed.items():
        _value(variables[name], value)
    # a time N/PARAM is divided by the point's PARAM: it must be set at every point
    known = {*plan.grid, *plan.fixed}
    spans = [(f"stop time {plan.stop_time}", plan.stop_time), (f"step {plan.step}", plan.step),
             *((f"output {o.column}", o.window) for o in plan.outputs)]
    for what, span in spans:
        if span is None or span.per is None or span.per in known:
            continue
        why = "set at every point" if span.per in variables else "a variable of the FMU"
        raise ValueError(f"{what}: {span.per!r} is not {why} (give it as a grid axis or with "
                         f"--set; set now: {', '.join(sorted(known))})")


def view(plan, x, y, column, fixed):
    """The heat map's axes (`y` None: a single row), color column and pinned axes."""
    axes = list(plan.grid)
    for flag, name in [("--x", x), ("--y", y), *(("--fix", n) for n in fixed)]:
        if name is not None and name not in plan.grid:
            raise ValueError(f"{flag} {name}: not a grid axis (axes: {', '.join(axes)})")
    if x == y:
        raise ValueError(f"--x and --y are both {x}: give two different grid axes")
    for name, value in fixed.items():
        if name in (x, y):
            raise ValueError(f"--fix {name}: it is the heat map's {'x' if name == x else 'y'} "
                             "axis, so it cannot be pinned")
        if value not in plan.grid[name]:
            raise ValueError(f"--fix {name}={value}: not a value of that axis "
                             f"({', '.join(map(str, plan.grid[name]))})")
    columns = [o.column for o in plan.outputs]
    if column not in columns:
        raise ValueError(f"--color {column}: not an output column ({', '.join(columns)})")


def _value(var, value):
    """One value for `var`, by its type: Real a finite or infinite number, Integer a whole
    number, Boolean true/false/1/0, a switch an item's name or number."""
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
    if var.type == "Integer" and not (math.isfinite(value) and value == int(value)):
        raise ValueError(f"{var.name} = {value!r}: expected a whole number")


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)
