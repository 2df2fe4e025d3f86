"""What a sweep runs: the grid axes, the fixed values, the outputs and how each is collected.

Everything here is plain data that pickles, so the same `Plan` and `Point` go to a local process
or to a Dask worker unchanged.
"""
import itertools
import json
import math
import pathlib
import tomllib
from dataclasses import dataclass, field


def parse_value(text):
    """A grid or --set value: a float when it reads as one, else the text (an enumeration item
    name such as `sliding`, or a boolean `true`/`false`)."""
    if isinstance(text, int) and not isinstance(text, bool):
        return float(text)  # 3000 in a grid file is the same point as 3000.0 on the CLI
    if not isinstance(text, str):
        return text
    text = text.strip()
    try:
        return float(text)
    except ValueError:
        return text


@dataclass(frozen=True)
class Span:
    """A time that may depend on the point: `value` seconds, divided by the point's parameter
    `per` when given (`150/f` is 150 vibration periods)."""

    value: float
    per: str | None = None

    @staticmethod
    def parse(text):
        if text is None or isinstance(text, Span):
            return text
        number, slash, per = str(text).partition("/")
        try:
            value = float(number)
        except ValueError:
            value = None
        if value is None or (slash and not per.strip()):
            raise ValueError(f"time {text!r}: expected seconds or N/PARAM, e.g. 0.05 or 150/f")
        if not math.isfinite(value):
            raise ValueError(f"time {text!r}: expected a finite number of seconds or periods")
        return Span(value, per.strip() or None)

    def at(self, values):
        if self.per is None:
            return self.value
        if self.per not in values:
            raise ValueError(f"time {self} refers to {self.per!r}, which is not set")
        per = float(values[self.per])
        # no time at PARAM = 0: a NaN, which check.plan refuses before the run
        return self.value / per if per else math.nan

    def __str__(self):
        return f"{self.value:g}" + (f"/{self.per}" if self.per else "")


@dataclass(frozen=True)
class Output:
    """One collected column: the variable's value at the stop time (`final`), or the mean of
    its samples at the communication points in the last `window` before the stop time."""

    variable: str
    window: Span | None = None

    @staticmethod
    def parse(text):
        """`FFx_mean` (final value) or `FFx:mean_last=1/f` (mean over the last period)."""
        variable, _, how = text.partition(":")
        if not how:
            return Output(variable.strip())
        kind, _, window = how.partition("=")
        if kind.strip() != "mean_last" or not window:
            raise ValueError(f"output {text!r}: expected NAME or NAME:mean_last=TIME")
        span = Span.parse(window)
        if not span.value > 0:
            raise ValueError(f"output {text!r}: the window mean_last={span} is not a time > 0 "
                             "before the stop time")
        return Output(variable.strip(), span)

    @property
    def column(self):
        return self.variable if self.window is None else f"{self.variable}:mean_last={self.window}"


@dataclass(frozen=True)
class Point:
    index: int
    values: dict


@dataclass
class Plan:
    """A whole sweep: the grid (ordered axes), fixed values, outputs and experiment times
    (None: the FMU's DefaultExperiment)."""

    grid: dict = field(default_factory=dict)
    fixed: dict = field(default_factory=dict)
    outputs: list = field(default_factory=list)
    stop_time: Span | None = None
    step: Span | None = None
    start_time: float = 0.0

    def points(self):
        """Every combination of the axes, the last axis varying fastest."""
        names = list(self.grid)
        combos = itertools.product(*(self.grid[n] for n in names))
        return [Point(i, dict(zip(names, c))) for i, c in enumerate(combos)]


def parse_assignment(text):
    """`name=v1,v2,...` -> (name, [values])."""
    name, eq, values = text.partition("=")
    if not eq or not name.strip() or not values.strip():
        raise ValueError(f"{text!r}: expected name=value[,value...]")
    return name.strip(), [parse_value(v) for v in values.split(",")]


def load_file(path):
    """A grid file (TOML or JSON) with the keys grid, set, outputs, stop_time, step."""
    path = pathlib.Path(path)
    text = path.read_text()
    try:
        data = tomllib.loads(text) if path.suffix == ".toml" else json.loads(text)
    except ValueError as error:  # the parsers' messages do not name the file
        raise ValueError(f"{path}: {error}") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a table with the keys grid, set, outputs, stop_time, "
                         "step")
    unknown = set(data) - {"grid", "set", "outputs", "stop_time", "step"}
    if unknown:
        raise ValueError(f"{path}: unknown keys {sorted(unknown)}")
    return Plan(
        grid={k: [parse_value(v) for v in vs] for k, vs in _grid(path, data).items()},
        fixed={k: parse_value(v) for k, v in _fixed(path, data).items()},
        outputs=[Output.parse(o) for o in _outputs(path, data)],
        stop_time=Span.parse(data.get("stop_time")),
        step=Span.parse(data.get("step")),
    )


# The shapes a grid file's keys must have: anything else would be iterated or converted into
# a different sweep than the one written (a string axis "1e-4" is four points "1", "e", ...).
_SCALAR = (str, int, float, bool)


def _grid(path, data):
    grid = data.get("grid", {})
    if not isinstance(grid, dict):
        raise ValueError(f"{path}: grid: expected a table of axes, NAME = [V1, V2, ...]; got "
                         f"{grid!r}")
    for name, values in grid.items():
        if not (isinstance(values, list) and values and all(isinstance(v, _SCALAR)
                                                            for v in values)):
            raise ValueError(f"{path}: grid.{name} = {values!r}: expected a non-empty list of "
                             "values, e.g. [1e-4, 2e-4] (one value goes under set)")
    return grid


def _fixed(path, data):
    fixed = data.get("set", {})
    if not isinstance(fixed, dict):
        raise ValueError(f"{path}: set: expected a table NAME = VALUE; got {fixed!r}")
    for name, value in fixed.items():
        if not isinstance(value, _SCALAR):
            raise ValueError(f"{path}: set.{name} = {value!r}: expected one value (a list is a "
                             "grid axis)")
    return fixed


def _outputs(path, data):
    outputs = data.get("outputs", [])
    if not (isinstance(outputs, list) and all(isinstance(o, str) for o in outputs)):
        raise ValueError(f"{path}: outputs = {outputs!r}: expected a list of NAME or "
                         "NAME:mean_last=TIME strings")
    return outputs

