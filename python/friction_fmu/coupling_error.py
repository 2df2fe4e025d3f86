"""How far a coupled run (friction_fmu.couple) is from a monolithic reference of the same case.

The reference is a CSV with the columns t, v_nut, x_nut, Fd and x, sampled on a grid that holds
every communication point of the runs compared with it (tests/reference/drive/reference.csv:
both models in one ODE, scipy Radau at rtol 1e-11).
"""
import csv
import math


def reference(path):
    """The reference as {t: (v_nut, x_nut, Fd, x)}, t rounded to 12 digits so that a run's
    k * H finds its sample whatever the last bit of either time."""
    with open(path) as f:
        return {
            round(float(r["t"]), 12): (float(r["v_nut"]), float(r["x_nut"]), float(r["Fd"]),
                                       float(r["x"]))
            for r in csv.DictReader(f)
        }


def at(ref, t):
    """The reference (v_nut, x_nut, Fd, x) at any t inside it, for a run whose points are off its
    grid (a variable-step algorithm): the cubic through the four samples around t (within 5e-7 N
    of Fd on the 5e-5 s grid; linear interpolation would be off by more than the coupling
    errors compared)."""
    times = sorted(ref)
    h = times[1] - times[0]
    k = min(max(int(t / h) - 1, 0), len(times) - 4)
    nodes = times[k:k + 4]
    weights = [math.prod((t - b) / (a - b) for b in nodes if b != a) for a in nodes]
    return tuple(sum(w * ref[n][i] for w, n in zip(weights, nodes)) for i in range(4))


def coupling_error(rows, ref):
    """Largest difference from the reference over the communication points, per quantity:
    (v_nut in m/s, Fd in N, x in m). `rows` are couple.couple's (t, v_nut, x_nut, Fd, x)."""
    errors = [0.0, 0.0, 0.0]
    for t, v_nut, _, fd, x in rows:
        want = ref[round(t, 12)]
        for i, (got, exact) in enumerate([(v_nut, want[0]), (fd, want[2]), (x, want[3])]):
            errors[i] = max(errors[i], abs(got - exact))
    return errors


def slope(steps, errors):
    """Least-squares slope of log(error) against log(step): the observed order of the error."""
    xs = [math.log(h) for h in steps]
    ys = [math.log(e) for e in errors]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
