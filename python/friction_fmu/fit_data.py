"""Measured data for a fit (friction_fmu.fit): a CSV read and checked against the FMU.

Two forms, told apart by a `time` column:

- a table of experiments: one row per experiment; columns named after parameters or inputs
  that the experiments set (`vc`, a switch by item name or number) and after the outputs
  measured at the end of each run (`FT_mean`);
- a time series: `time` (increasing), the outputs measured at those times and the inputs the
  FMU is given at them (each held, or moved by the FMU's input scheme, over the step that
  follows).

Lines starting with `#` are comments. Every refusal is one ValueError naming the file, the line
or column and what was expected.
"""
import csv
import math
from dataclasses import dataclass

from . import switches

SETTABLE = ("parameter", "input")


@dataclass
class Data:
    path: str
    form: str  # "table" or "series"
    settings: dict  # name -> values, one a row: parameters and inputs (series: inputs only)
    measured: dict  # output name -> floats, one a row
    times: list | None  # the series' times
    rows: int

    @property
    def experiment(self):
        """The plot's x: the time of a series; in a table, the first setting that differs
        between rows (None: no column differs)."""
        if self.form == "series":
            return "time"
        return next((n for n, vs in self.settings.items() if len(set(map(str, vs))) > 1),
                    None)


def read(path, md):
    """The CSV at `path` checked against `md` (fmpy's model description)."""
    with open(path, newline="", encoding="utf-8-sig") as handle:  # -sig: a spreadsheet's BOM
        lines = list(_rows(handle))
    if not lines:
        raise ValueError(f"{path}: empty: expected a header naming the columns (parameters or "
                         "inputs the experiments set, the outputs they measured; `time` for a "
                         "time series) and one row per experiment or time")
    (_, header), body = lines[0], lines[1:]
    names = [name.strip() for name in header]
    for k, name in enumerate(names):
        if not name:
            raise ValueError(f"{path}: column {k + 1} of the header has no name")
        if names.index(name) != k:
            raise ValueError(f"{path}: column {name} appears twice in the header")
    if not body:
        raise ValueError(f"{path}: no data rows under the header ({', '.join(names)})")
    variables = {v.name: v for v in md.modelVariables}
    form = "series" if "time" in names else "table"
    roles = {name: _role(path, name, variables, form) for name in names}
    columns = {name: [] for name in names}
    for line, row in body:
        if len(row) != len(names):
            raise ValueError(f"{path} line {line}: {len(row)} values for {len(names)} columns "
                             f"({', '.join(names)})")
        for name, text in zip(names, row):
            columns[name].append(_value(path, line, name, text.strip(), variables.get(name)))
    measured = {n: columns[n] for n in names if roles[n] == "output"}
    if not measured:
        outputs = [n for n, v in variables.items() if v.causality == "output"]
        raise ValueError(f"{path}: no measured output among the columns ({', '.join(names)}): "
                         f"add one named after an output of the FMU ({', '.join(outputs)})")
    times = None
    if form == "series":
        times = columns["time"]
        if len(times) < 2:
            raise ValueError(f"{path}: a time series needs two times or more")
        for (line, _), before, now in zip(body[1:], times, times[1:]):
            if not now > before:
                raise ValueError(f"{path} line {line}: time {now!r} is not after the time "
                                 f"before it ({before!r})")
    settings = {n: columns[n] for n in names if roles[n] == "setting"}
    return Data(str(path), form, settings, measured, times, len(body))


def _rows(handle):
    """(line number, cells) of every row that is not blank or a # comment."""
    reader = csv.reader(handle)
    for row in reader:
        if not row or not "".join(row).strip() or row[0].lstrip().startswith("#"):
            continue
        yield reader.line_num, row


def _role(path, name, variables, form):
    """"time", "output" (measured), or "setting" (set on the FMU)."""
    if name == "time" and form == "series":
        return "time"
    var = variables.get(name)
    if var is None:
        raise ValueError(f"{path}: column {name!r} is not a variable of the FMU (a column is a "
                         f"parameter or input the runs set, an output they measured, or time; "
                         f"outputs: {', '.join(_named(variables, 'output'))})")
    if var.causality == "output":
        if var.type != "Real":
            raise ValueError(f"{path}: column {name} is an {var.type} output; a fit compares "
                             "Real outputs")
        return "output"
    if form == "series" and var.causality == "parameter":
        raise ValueError(f"{path}: column {name} is a parameter: a time series holds the "
                         "inputs and the measured outputs at each time (fix a parameter with "
                         "--set, or measure it in a table of experiments)")
    if var.causality not in SETTABLE:
        raise ValueError(f"{path}: column {name} is {_kind(var)}, neither an output that can be "
                         "measured nor a parameter or input that can be set")
    return "setting"


def _value(path, line, name, text, var):
    """A cell: a finite float, or for a switch column an item's name too."""
    if var is not None and switches.items(var) and text in switches.items(var):
        return text
    try:
        value = float(text)
    except ValueError:
        if not text:
            raise ValueError(f"{path} line {line}, column {name}: empty (leave a missing "
                             "measurement's row out)") from None
        raise ValueError(f"{path} line {line}, column {name}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{path} line {line}, column {name}: {text} is not a finite number "
                         "(leave a missing measurement's row out)")
    return value


def _named(variables, causality):
    return [n for n, v in variables.items() if v.causality == causality]


def _kind(var):
    article = "an" if var.causality[0] in "aeiou" else "a"
    return f"{article} {var.causality} variable"
