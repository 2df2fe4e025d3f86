"""Reference solutions of the exact dry-friction oscillator (switch model), written independently
of the Rust code: scipy's DOP853 at rtol = atol = 1e-12 with event location, phase by phase.

    m u'' + c u' + k u = P sin(w t) - s h      sliding, s = sgn(u')
    u' = 0                                      stuck, while |P sin(w t) - k u| <= hs

hs = h (exact) or h + ha (exact_stiction). A slide ends where u' returns to 0; the mass then
sticks if |P sin(w t) - k u| <= hs, else it slides on in the direction of that force. A stuck
phase ends where |P sin(w t) - k u| reaches hs (an event on the constant state, found by the same
event machinery, not by a closed form).

Writes next to this file (the tests read these and never run scipy):
  cases.csv            one row per case: parameters, amplitude max|u| over the last period
                       [(N-1)T, NT] and over the one before it, max|u'| over the last period,
                       u and u' at t = NT
  stick_intervals.csv  case, start, end of every stuck phase that ends in the last two periods
Run: python make_reference.py
"""
import csv
import math
import pathlib

import numpy as np
from scipy.integrate import solve_ivp

RTOL = ATOL = 1e-12
HERE = pathlib.Path(__file__).resolve().parent

# name, law, P, w, h, hs, c, k, m, periods
CASES = [
    ("paper", "exact", 4.0, 1.0, 1.6, 1.6, 0.1, 1.0, 1.0, 60),
    ("low_w", "exact", 1.0, 0.5, 0.5, 0.5, 0.1, 1.0, 1.0, 30),
    ("high_w", "exact", 1.5, 2.0, 1.0, 1.0, 0.1, 1.0, 1.0, 80),
    ("paper_stiction", "exact_stiction", 4.0, 1.0, 1.6, 3.2, 0.1, 1.0, 1.0, 60),
    ("stiction_low_w", "exact_stiction", 3.0, 0.5, 1.0, 2.0, 0.1, 1.0, 1.0, 30),
]


def simulate(P, w, h, hs, c, k, m, t_stop):
    """Returns (events, dense pieces). events: list of (t, u, mode) at every mode change."""
    force = lambda t: P * math.sin(w * t)
    t, u, v = 0.0, 0.0, 0.0
    f0 = force(t) - k * u
    mode = 0 if abs(f0) <= hs else math.copysign(1.0, f0)
    events, pieces = [(t, u, mode)], []
    while t < t_stop:
        if mode == 0:
            def up(t, y):
                return force(t) - k * y[0] - hs
            def down(t, y):
                return force(t) - k * y[0] + hs
            up.terminal, up.direction = True, 1
            down.terminal, down.direction = True, -1
            sol = solve_ivp(lambda t, y: [0.0, 0.0], (t, t_stop), [u, 0.0], method="DOP853",
                            events=[up, down], rtol=RTOL, atol=ATOL, dense_output=True,
                            max_step=0.01 * 2 * math.pi / w)
            pieces.append((t, sol.t[-1], sol.sol))
            if sol.status == 1:
                hit = 0 if sol.t_events[0].size else 1
                t = sol.t_events[hit][0]
                mode = 1.0 if hit == 0 else -1.0
                events.append((t, u, mode))
            else:
                t = t_stop
        else:
            s = mode
            def rhs(t, y):
                return [y[1], (force(t) - c * y[1] - k * y[0] - s * h) / m]
            def stop(t, y):
                return y[1]
            stop.terminal, stop.direction = True, -s
            sol = solve_ivp(rhs, (t, t_stop), [u, v], method="DOP853", events=[stop],
                            rtol=RTOL, atol=ATOL, dense_output=True,
                            max_step=0.01 * 2 * math.pi / w)
            pieces.append((t, sol.t[-1], sol.sol))
            if sol.status == 1:
                t = sol.t_events[0][0]
                u = sol.y_events[0][0][0]
                v = 0.0
                f = force(t) - k * u
                mode = 0 if abs(f) <= hs else math.copysign(1.0, f)
                events.append((t, u, mode))
            else:
                t, u, v = sol.t[-1], sol.y[0, -1], sol.y[1, -1]
    return events, pieces


def state_at(pieces, t):
    for a, b, sol in pieces:
        if a <= t <= b:
            return sol(t)
    raise ValueError(t)


def amplitude(events, pieces, a, b):
    """max |u| over [a, b]: u has its extremes where u' = 0 (events) or at the ends."""
    values = [abs(state_at(pieces, a)[0]), abs(state_at(pieces, b)[0])]
    values += [abs(u) for t, u, _ in events if a <= t <= b]
    return max(values)


def velocity_amplitude(pieces, a, b, samples=200_001):
    """max |u'| over [a, b], sampled on the dense output (u' is smooth where it is largest)."""
    return max(abs(state_at(pieces, t)[1]) for t in np.linspace(a, b, samples))


def main():
    case_rows, stick_rows = [], []
    for name, law, P, w, h, hs, c, k, m, periods in CASES:
        T = 2 * math.pi / w
        t_stop = periods * T
        events, pieces = simulate(P, w, h, hs, c, k, m, t_stop)
        last = amplitude(events, pieces, (periods - 1) * T, t_stop)
        before = amplitude(events, pieces, (periods - 2) * T, (periods - 1) * T)
        u_end, v_end = state_at(pieces, t_stop)
        v_amplitude = velocity_amplitude(pieces, (periods - 1) * T, t_stop)
        case_rows.append(dict(case=name, law=law, P=P, w=w, h=h, hs=hs, c=c, k=k, m=m,
                              periods=periods, stop_time=repr(float(t_stop)), amplitude=repr(float(last)),
                              amplitude_previous=repr(float(before)),
                              velocity_amplitude=repr(float(v_amplitude)), u_end=repr(float(u_end)),
                              v_end=repr(float(v_end))))
        for (t0, _, m0), (t1, _, _) in zip(events, events[1:]):
            if m0 == 0 and t1 >= (periods - 2) * T:
                stick_rows.append(dict(case=name, start=repr(float(t0)), end=repr(float(t1))))
        print(f"{name}: amplitude {last:.12g} (previous period {before:.12g}), "
              f"{sum(1 for r in stick_rows if r['case'] == name)} stuck phases in the last two periods")
    with open(HERE / "cases.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(case_rows[0]))
        writer.writeheader()
        writer.writerows(case_rows)
    with open(HERE / "stick_intervals.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["case", "start", "end"])
        writer.writeheader()
        writer.writerows(stick_rows)


if __name__ == "__main__":
    main()
