#!/usr/bin/env python3
"""The drive force's coupling error against time, DriveFriction.ssp in libcosim at its 0.1 ms
step: the FMUs' input schemes (held, extrapolated, corrected; the archive ships corrected)
beside the fmpy master that passes output derivatives (friction_fmu.couple), all against the
monolithic reference (tests/reference/drive).

libcosim holds every input over a step and never passes a derivative; each run sets both
FMUs' input_scheme as an initial value over the archive's.

Run:    .venv/bin/python examples/input_schemes.py [OUT_PREFIX]   (after the main command)
Writes: OUT_PREFIX.csv (time, then |Fd - Fd_ref| of each run, N), .png and .svg; by default
        fmu-out/coupling/input_schemes. Prints each run's largest error.
"""
import csv
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))
from friction_fmu import couple, style  # noqa: E402
from friction_fmu.coupling_error import reference  # noqa: E402
from friction_fmu.engines import run_libcosim  # noqa: E402

SSP = ROOT / "fmu-out" / "DriveFriction.ssp"
REFERENCE = ROOT / "tests" / "reference" / "drive" / "reference.csv"
STEP = 1e-4
SCHEMES = {"held": 1, "extrapolated": 2, "corrected": 3}  # the input_scheme items


def errors():
    """{run: (times, |Fd - Fd_ref| at each communication point)}."""
    ref = reference(REFERENCE)
    steps = round(couple.STOP_TIME / STEP)
    runs = {}
    for scheme, number in SCHEMES.items():
        ok, _, result = run_libcosim({
            "ssp": str(SSP), "step": STEP, "steps": steps, "record": ["friction.Fd"],
            "values": {"friction.input_scheme": number, "drive.input_scheme": number}})
        if not ok:
            raise SystemExit(f"libcosim stopped the {scheme} run before {couple.STOP_TIME} s")
        times = [float(t) for t in result["time"]]
        runs[f"libcosim, {scheme}"] = (times, [abs(float(fd) - ref[round(t, 12)][2])
                                               for t, fd in zip(times, result["friction.Fd"])])
    rows = couple.couple(STEP, True, fmu_dir=ROOT / "fmu-out")
    runs["fmpy with output derivatives"] = ([t for t, *_ in rows],
                                            [abs(fd - ref[round(t, 12)][2]) for t, _, _, fd, _ in rows])
    return runs


def write(runs, prefix):
    prefix.parent.mkdir(parents=True, exist_ok=True)
    names = list(runs)
    times = runs[names[0]][0]
    with open(prefix.with_suffix(".csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["time"] + [f"Fd error, {name}" for name in names])
        for k, t in enumerate(times):
            out.writerow([repr(t)] + [repr(runs[name][1][k]) for name in names])
    with style.context():
        figure = style.figure(7.0, 4.2)
        ax = figure.subplots()
        for name, look in style.series(names).items():
            t, e = runs[name]
            # t = 0 is exact in every run: a log axis has no place for it
            ax.plot([x * 1e3 for x in t[1:]], e[1:], label=name, **look.line(markers=False))
        ax.set_yscale("log")
        ax.set_xlabel("time t (ms)")
        ax.set_ylabel("|Fd - Fd_ref| (N)")
        ax.set_title(f"DriveFriction.ssp at a {STEP * 1e3:g} ms step: the drive force's coupling error")
        style.legend(figure, ax.get_lines())
        for suffix in (".png", ".svg"):
            figure.savefig(prefix.with_suffix(suffix), dpi=style.DPI)


def main():
    prefix = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "fmu-out" / "coupling" / "input_schemes"
    runs = errors()
    for name, (_, e) in runs.items():
        print(f"{name:32s} largest |Fd - Fd_ref| {max(e):.2e} N")
    write(runs, prefix)
    print(f"wrote {prefix}.csv, .png, .svg")


if __name__ == "__main__":
    main()
