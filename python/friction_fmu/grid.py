"""What a sweep runs: the grid axes, the fixed values, the outputs and how each is collected.

Everything here is plain data that pickles, so the same `Plan` and `Point` go to a local process
or to a Dask worker unchanged.
"""
import itertools
import json
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
        if isinstance(text, (int, float)):
            return Span(float(text))
        number, slash, per = str(text).partition("/")
        try:
            value = float(number)
        except ValueError:
            value = None
        if value is None or (slash and not per.strip()):
            raise ValueError(f"time {text!r}: expected seconds or N/PARAM, e.g. 0.05 or 150/f")
        return Span(value, per.strip() or None)

    def at(self, values):
        if self.per is None:
            return self.value
        if self.per not in values:
            raise ValueError(f"time {self} refers to {self.per!r}, which is not set")
        return self.value / float(values[self.per])

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
        return Output(variable.strip(), Span.parse(window))

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
    data = tomllib.loads(text) if path.suffix == ".toml" else json.loads(text)
    unknown = set(data) - {"grid", "set", "outputs", "stop_time", "step"}
    if unknown:
        raise ValueError(f"{path}: unknown keys {sorted(unknown)}")
    return Plan(
        grid={k: [parse_value(v) for v in vs] for k, vs in data.get("grid", {}).items()},
        fixed={k: parse_value(v) for k, v in data.get("set", {}).items()},
        outputs=[Output.parse(o) for o in data.get("outputs", [])],
        stop_time=Span.parse(data.get("stop_time")),
        step=Span.parse(data.get("step")),
    )
