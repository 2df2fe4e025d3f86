"""Runs one FMU or one SSP system in a co-simulation engine, in a process of its own.

    python engine_run.py ENGINE SPEC.json OUT.npz      ENGINE: libcosim or ecos

SPEC: as friction_fmu.engines says (python/friction_fmu/engines.py). Writes OUT.npz with "time"
and each recorded variable, and prints one JSON line: {"ok": whether every step completed,
"time": the engine's time at the end}.

A process of its own because libcosim ends its process (std::terminate) on some FMU errors; the
tests assert what the engines do from the exit status and the log.
"""
import json
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "python"))
from friction_fmu.engines import run_ecos, run_libcosim  # noqa: E402


def main():
    engine, spec_path, out = sys.argv[1:4]
    with open(spec_path) as f:
        spec = json.load(f)
    ok, end, result = {"libcosim": run_libcosim, "ecos": run_ecos}[engine](spec)
    np.savez(out, **result)
    print(json.dumps({"ok": bool(ok), "time": end}), flush=True)


if __name__ == "__main__":
    main()
