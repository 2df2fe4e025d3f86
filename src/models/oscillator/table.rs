// `DryFrictionOscillator`: `m u'' + c u' + H(u') + k u = F(t)` with regularised dry friction
// (paper O, eq. 1-9) or the exact non-smooth switch model, `F = P sin(w t)` or an input.

use crate::variables::declare::{
    enum_parameter, integer_parameter, real_input, real_output, real_parameter, POSITIVE,
};
use crate::variables::variable::{DefaultExperiment, EnumType, InputSwitch, ModelTable, Variable};

/// Value references.
pub mod vr {
    pub const LAW: u32 = 1;
    pub const FORCE_SOURCE: u32 = 2;
    pub const SOLVER: u32 = 3;
    pub const STEPS_PER_PERIOD: u32 = 4;
    pub const RTOL: u32 = 5;
    pub const ATOL: u32 = 6;
    pub const INITIAL: u32 = 7;
    pub const M: u32 = 10;
    pub const C: u32 = 11;
    pub const K: u32 = 12;
    pub const P: u32 = 13;
    pub const W: u32 = 14;
    pub const H: u32 = 15;
    pub const D: u32 = 16;
    pub const DA: u32 = 17;
    pub const U0: u32 = 18;
    pub const V0: u32 = 19;
    pub const P_IN: u32 = 30;
    pub const U: u32 = 40;
    pub const V: u32 = 41;
    pub const A: u32 = 42;
    pub const H_OUT: u32 = 43;
    pub const C_OUT: u32 = 44;
    pub const U_AMPLITUDE: u32 = 45;
    pub const W_DISS: u32 = 46;
}

const INF: f64 = f64::INFINITY;

pub const LAW: EnumType = EnumType {
    name: "OscillatorLaw",
    items: &[
        ("linear", "H = h clamp(u'/D, -1, 1) (eq. 4)"),
        (
            "trigonometric",
            "H = h sin(pi/2 u'/D) for |u'| < D, else h sgn(u') (eq. 5)",
        ),
        (
            "linear_stiction",
            "Slope h/D up to |u'| = D + Da (H = h + ha, ha = h Da/D), slope -h/D back to h (eq. 8)",
        ),
        (
            "trigonometric_stiction",
            "(h + ha) sin(pi/2 u'/(D + Da)), then a half sine down to h over Da (eq. 9)",
        ),
        (
            "exact",
            "Switch model: H = h sgn(u') sliding, stuck while |F - k u| <= h, events located exactly",
        ),
        (
            "exact_stiction",
            "Switch model with breakaway force h + ha (ha = h Da/D) and sliding force h",
        ),
    ],
};

pub const FORCE_SOURCE: EnumType = EnumType {
    name: "ForceSource",
    items: &[
        ("prescribed", "F = P sin(w t)"),
        ("input", "F = P_in, held over each communication step"),
    ],
};

pub const SOLVER: EnumType = EnumType {
    name: "OscillatorSolver",
    items: &[
        (
            "radau5",
            "Adaptive 3-stage Radau IIA (order 5, L-stable) for the regularised laws; the exact laws are solved in closed form whatever this says",
        ),
        (
            "dopri5",
            "Adaptive Dormand-Prince 5(4), steps ending where |u'| crosses D (and D + Da, D + 2 Da with stiction), the kinks of H",
        ),
        (
            "rk4",
            "Classical Runge-Kutta, steps_per_period fixed steps per forcing period",
        ),
        (
            "piecewise",
            "Outside the band of H (|u'| beyond D, or D + 2 Da with stiction) the motion is linear and taken in closed form to where |u'| comes back to the band; inside it dopri5",
        ),
    ],
};

pub const INITIAL: EnumType = EnumType {
    name: "OscillatorInitialState",
    items: &[
        ("given", "u = u0 and u' = v0 at the start"),
        (
            "periodic",
            "The periodic steady state under the prescribed force, found at initialization by shooting on the one-period map from (u0, v0): u_amplitude is the steady value from the first period on; where no period-1 orbit is found, (u0, v0), with a warning",
        ),
    ],
};

const VARIABLES: &[Variable] = &[
    enum_parameter("law", vr::LAW, "Dry-friction law", LAW.name, 2),
    enum_parameter(
        "force_source",
        vr::FORCE_SOURCE,
        "Where the excitation force comes from",
        FORCE_SOURCE.name,
        1,
    ),
    enum_parameter("solver", vr::SOLVER, "Integration scheme", SOLVER.name, 1),
    enum_parameter("initial", vr::INITIAL, "Initial state", INITIAL.name, 1),
    integer_parameter(
        "steps_per_period",
        vr::STEPS_PER_PERIOD,
        "Sub-steps per forcing period 2 pi/w: longest solver step (regularised laws), event-scan grid (exact laws)",
        128,
        8,
        1_000_000,
    ),
    real_parameter(
        "rtol",
        vr::RTOL,
        "Relative tolerance of the adaptive solver",
        1e-9,
        "",
        1e-13,
        1e-2,
    ),
    real_parameter(
        "atol",
        vr::ATOL,
        "Absolute tolerance of the adaptive solver on u (m) and u' (m/s)",
        1e-9,
        "",
        1e-300,
        INF,
    ),
    real_parameter("m", vr::M, "Mass (> 0)", 1.0, "kg", POSITIVE, INF),
    real_parameter("c", vr::C, "Viscous damping coefficient", 0.1, "N.s/m", 0.0, INF),
    real_parameter("k", vr::K, "Stiffness", 1.0, "N/m", 0.0, INF),
    real_parameter(
        "P",
        vr::P,
        "Amplitude of the exciting force P sin(w t)",
        4.0,
        "N",
        0.0,
        INF,
    ),
    real_parameter(
        "w",
        vr::W,
        "Excitation frequency; also sets the period 2 pi/w of u_amplitude (> 0)",
        1.0,
        "rad/s",
        POSITIVE,
        INF,
    ),
    real_parameter("h", vr::H, "Dry-friction force", 1.6, "N", 0.0, INF),
    real_parameter(
        "D",
        vr::D,
        "Width of the transition region around u' = 0 (> 0)",
        0.8,
        "m/s",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "Da",
        vr::DA,
        "Width of the stiction bump; ha = h Da/D (stiction laws only)",
        0.8,
        "m/s",
        0.0,
        INF,
    ),
    real_parameter("u0", vr::U0, "Initial displacement", 0.0, "m", -INF, INF),
    real_parameter("v0", vr::V0, "Initial velocity", 0.0, "m/s", -INF, INF),
    real_input(
        "P_in",
        vr::P_IN,
        "Excitation force when force_source = input",
        0.0,
        "N",
    ),
    real_output("u", vr::U, "Displacement", "m", &[]),
    real_output("v", vr::V, "Velocity u'", "m/s", &[]),
    real_output("a", vr::A, "Acceleration u''", "m/s2", &[vr::P_IN]),
    real_output(
        "H",
        vr::H_OUT,
        "Dry-friction force, positive when it resists +u motion",
        "N",
        &[vr::P_IN],
    ),
    real_output(
        "C",
        vr::C_OUT,
        "Slope dH/du' of the friction law (the paper's C); 0 for the exact laws",
        "N.s/m",
        &[],
    ),
    real_output(
        "u_amplitude",
        vr::U_AMPLITUDE,
        "max |u| over the last complete forcing period 2 pi/w (so far, before the first)",
        "m",
        &[],
    ),
    real_output(
        "W_diss",
        vr::W_DISS,
        "Energy dissipated by friction since the start, the integral of H u' (H stores no energy)",
        "J",
        &[],
    ),
];

pub const TABLE: ModelTable = ModelTable {
    model_identifier: "DryFrictionOscillator",
    description: "Forced oscillator with dry friction: regularised laws (paper O, eq. 4-9) and the exact switch model",
    variables: VARIABLES,
    enum_types: &[LAW, FORCE_SOURCE, SOLVER, INITIAL],
    input_switches: &[InputSwitch {
        switch: "force_source",
        item: "input",
        input: "P_in",
    }],
    interpolates_inputs: false,
    law_parameter: Some("law"),
    tolerance_parameter: Some("rtol"),
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        // 60 forcing periods at w = 1 (377 s): with c = 0.1 the free response decays as
        // e^(-0.05 t), so the last periods are steady to about 1e-8; output every 1/16 s, about
        // 100 times a period (2 pi s is no whole number of nanoseconds, as engines' clocks need).
        stop_time: 377.0,
        tolerance: 1e-9,
        step_size: 0.0625,
    },
};

#[cfg(test)]
mod tests {
    use super::TABLE;

    #[test]
    fn value_references_and_names_are_unique() {
        let vars = TABLE.variables;
        for (i, a) in vars.iter().enumerate() {
            for b in &vars[i + 1..] {
                assert_ne!(a.value_reference, b.value_reference, "{}", a.name);
                assert_ne!(a.name, b.name);
            }
        }
    }
}
