#!/usr/bin/env python3
"""The largest stable communication step of DriveTrain coupled to TransverseFriction by a Jacobi
master that holds nothing back (every input set at every communication point, no derivatives:
libcosim and ecos), for each input scheme, against the drive spring's stiffness kd.

An independent linear analysis (it does not read the crate): with the body held (x = 0, the
drive spring tied to the ground, as before break-away) both models are linear, so one
communication step is a linear map of [i, w, x_nut] (the drive), the spring's far end x_d (the
friction model, Fd = kd x_d), and each input's memory (its two earlier values, what the last
step's input integrated to, the integral still owed), each model stepped exactly (a matrix
exponential of its equations with the input as the scheme moves it). The coupling is stable
while the map's spectral radius is below 1; the largest such step is found by bisection.

Run:    python3 tests/reference/drive/stability.py     (needs numpy)
Prints: the table of docs/coupling.md, "Stability": kd, then the largest stable step of each
        scheme, in seconds.
"""
import math

import numpy as np

# DriveTrain defaults (as tests/reference/drive/make_reference.py).
R_ARM, L_ARM, KT_M, KE, J, B, N, EFF, LEAD, M_NUT = 5.0, 1e-3, 0.01, 0.01, 2e-7, 1e-7, 50.0, 0.9, 1e-3, 0.05
R_SCREW = LEAD / (2.0 * math.pi * N)
J_EFF = J + M_NUT * R_SCREW**2 / EFF
KD = 9.2e5  # TransverseFriction's default drive stiffness
SCHEMES = ("held", "extrapolated", "corrected")


def expm(a):
    """exp(a) by scaling and squaring of the Taylor series (small, well-scaled matrices)."""
    norm = np.linalg.norm(a, 1)
    s = max(0, int(math.ceil(math.log2(norm))) + 1) if norm > 0.5 else 0
    b, term, total = a / 2**s, np.eye(len(a)), np.eye(len(a))
    for k in range(1, 30):
        term = term @ b / k
        total = total + term
    for _ in range(s):
        total = total @ total
    return total


def drive_propagator(h):
    """One step of [i, w, x_nut, F_load, F_load'] (the load moving linearly over the step)."""
    a = np.zeros((5, 5))
    a[0, 0], a[0, 1] = -R_ARM / L_ARM, -KE / L_ARM
    a[1, 0], a[1, 1], a[1, 3] = KT_M / J_EFF, -B / J_EFF, -R_SCREW / (EFF * J_EFF)
    a[2, 1] = R_SCREW
    a[3, 4] = 1.0
    return expm(a * h)


def scheme_ramp(scheme, memory, u, h):
    """(value, rate) of the input over the coming step and the memory after it, as the FMUs'
    input scheme makes them at steady state (uniform steps, three values known). memory: the
    values one and two steps back, what the last step's input integrated to, the debt."""
    u1, u0, used, debt = memory
    if scheme == "held":
        return (u, 0.0), [u, u1, h * u, 0.0]
    # The last step's integral of the quadratic through the three values, less what was given.
    debt = debt + h / 12.0 * (-u0 + 8.0 * u1 + 5.0 * u) - used
    rate = (u - u1) / h
    value = u + (debt / h if scheme == "corrected" else 0.0)
    return (value, rate), [u, u1, h * (value + 0.5 * rate * h), debt if scheme == "corrected" else 0.0]


def step_matrix(h, kd, scheme):
    drive = drive_propagator(h)

    def step(state):
        d, x_d, mv, mf = state[0:3], state[3], list(state[4:8]), list(state[8:12])
        v_nut, fd = R_SCREW * d[1], kd * x_d
        (v, v_rate), mv = scheme_ramp(scheme, mv, v_nut, h)
        (f, f_rate), mf = scheme_ramp(scheme, mf, fd, h)
        d = drive @ np.r_[d, f, f_rate]
        return np.r_[d[:3], x_d + h * (v + 0.5 * v_rate * h), mv, mf]

    return np.column_stack([step(e) for e in np.eye(12)])


def spectral_radius(h, kd, scheme):
    return max(abs(np.linalg.eigvals(step_matrix(h, kd, scheme))))


def largest_stable_step(kd, scheme, low=1e-8, high=10.0):
    """The bisection's lower end after it closes to 1e-6 relative (high when stable there)."""
    if spectral_radius(high, kd, scheme) <= 1.0:
        return high
    while high / low > 1.0 + 1e-6:
        middle = math.sqrt(low * high)
        if spectral_radius(middle, kd, scheme) > 1.0:
            high = middle
        else:
            low = middle
    return low


def main():
    print("kd (N/m)   " + "".join(f"{s:>14}" for s in SCHEMES))
    for factor in (1, 1e2, 1e4, 1e6):
        kd = KD * factor
        print(f"{kd:9.1e}  " + "".join(f"{largest_stable_step(kd, s):14.3e}" for s in SCHEMES))


if __name__ == "__main__":
    main()
