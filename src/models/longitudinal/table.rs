// `LongitudinalFriction`: a body sliding on a base that vibrates along the sliding direction
// (Leus & Gutowski 2008, JTAM 46(1)); Coulomb, Dahl or LuGre friction.

use crate::variables::declare::{
    body_mass, contact_stiffness, enum_parameter, gravity, input_scheme, integer_parameter,
    real_input, real_output, real_parameter, tolerance, INPUT_SCHEME, POSITIVE,
};
use crate::variables::variable::{DefaultExperiment, EnumType, InputSwitch, ModelTable, Variable};

/// Value references, named so the simulation code reads like the paper.
pub mod vr {
    pub const LAW: u32 = 1;
    pub const VELOCITY_SOURCE: u32 = 2;
    pub const NORMAL_FORCE_SOURCE: u32 = 6;
    pub const INITIAL: u32 = 7;
    pub const INPUT_SCHEME: u32 = 8;
    pub const SOLVER: u32 = 3;
    pub const STEPS_PER_PERIOD: u32 = 4;
    pub const TOLERANCE: u32 = 5;
    pub const M: u32 = 10;
    pub const MU: u32 = 11;
    pub const G: u32 = 12;
    pub const KT: u32 = 13;
    pub const ALPHA: u32 = 14;
    pub const VC: u32 = 15;
    pub const VA: u32 = 16;
    pub const F: u32 = 17;
    pub const FS: u32 = 18;
    pub const VS: u32 = 19;
    pub const SIGMA1: u32 = 20;
    pub const SIGMA2: u32 = 21;
    pub const VR_IN: u32 = 30;
    pub const FN_IN: u32 = 31;
    pub const FT: u32 = 40;
    pub const Z: u32 = 41;
    pub const VR: u32 = 42;
    pub const FT_MEAN: u32 = 43;
    pub const S: u32 = 44;
    pub const W_DISS: u32 = 45;
}

const INF: f64 = f64::INFINITY;

pub const LAW: EnumType = EnumType {
    name: "LongitudinalLaw",
    items: &[
        ("coulomb", "FT = FC sgn(vr), rigid contact"),
        (
            "dahl",
            "FT = kt z, dz/dt = vr (1 - kt/FC sgn(vr) z)^alpha (eq. 2.8-2.9)",
        ),
        (
            "lugre",
            "FT = kt z + sigma1 dz/dt + sigma2 vr, dz/dt = vr - kt |vr|/g(vr) z",
        ),
    ],
};

pub const VELOCITY_SOURCE: EnumType = EnumType {
    name: "VelocitySource",
    items: &[
        ("prescribed", "vr = vc + va cos(2 pi f t) (eq. 2.4)"),
        (
            "input",
            "vr = vr_in, moving at the derivative set for a communication step, else as input_scheme says",
        ),
    ],
};

pub const NORMAL_FORCE_SOURCE: EnumType = EnumType {
    name: "NormalForceSource",
    items: &[
        ("weight", "FN = m g: FC = mu m g and the LuGre FS as given"),
        (
            "input",
            "FN = FN_in, moving at the derivative set for a communication step, else as input_scheme says; FC = mu FN, and FS scales with FN / (m g)",
        ),
    ],
};

pub const INITIAL: EnumType = EnumType {
    name: "LongitudinalInitialState",
    items: &[
        ("rest", "Bristle undeflected at the start"),
        (
            "periodic",
            "The periodic steady state under the prescribed velocity, found at initialization by shooting on the one-period map: FT_mean and S are the steady values from the first period on",
        ),
    ],
};

pub const SOLVER: EnumType = EnumType {
    name: "LongitudinalSolver",
    items: &[
        (
            "exponential",
            "Exact bristle update for the velocity frozen at each sub-step's midpoint, sub-steps split where vr changes sign",
        ),
        (
            "rk4",
            "Classical Runge-Kutta on the bristle ODE and the force integral, one step per sub-step",
        ),
        (
            "dopri5",
            "Adaptive Dormand-Prince 5(4) to `tolerance` on the bristle ODE, restarted where vr changes sign and at period boundaries",
        ),
        (
            "radau5",
            "Adaptive 3-stage Radau IIA (order 5, L-stable) to `tolerance`, restarted where vr changes sign and at period boundaries",
        ),
        (
            "closed_form",
            "Dahl at alpha = 1 (and Coulomb) with the weight as the normal force: the bristle in closed form along vr itself, the force integral by adaptive Gauss-Kronrod quadrature to `tolerance`",
        ),
        (
            "auto",
            "closed_form where the law has one (Coulomb, or Dahl at alpha = 1 with the weight as the normal force), dopri5 otherwise",
        ),
    ],
};

const VARIABLES: &[Variable] = &[
    enum_parameter("law", vr::LAW, "Friction law", LAW.name, 2),
    enum_parameter(
        "velocity_source",
        vr::VELOCITY_SOURCE,
        "Where the sliding velocity comes from",
        VELOCITY_SOURCE.name,
        1,
    ),
    enum_parameter(
        "normal_force_source",
        vr::NORMAL_FORCE_SOURCE,
        "Where the normal force comes from",
        NORMAL_FORCE_SOURCE.name,
        1,
    ),
    input_scheme(vr::INPUT_SCHEME),
    enum_parameter(
        "initial",
        vr::INITIAL,
        "Initial state",
        INITIAL.name,
        1,
    ),
    // auto (item 6): closed_form, exact and the cheapest per call, where the law has a closed
    // form; else dopri5, the fastest to reach a relative error of 1e-6 in the work-precision
    // report (`friction-fmu report`, report/longitudinal.md).
    enum_parameter("solver", vr::SOLVER, "Integration scheme", SOLVER.name, 6),
    integer_parameter(
        "steps_per_period",
        vr::STEPS_PER_PERIOD,
        "Sub-steps per vibration period 1/f of the fixed-step solvers (exponential, rk4) over a prescribed or moving input",
        2000,
        4,
        10_000_000,
    ),
    tolerance(vr::TOLERANCE, 1e-8),
    body_mass(vr::M, 0.02),
    real_parameter(
        "mu",
        vr::MU,
        "Kinetic friction coefficient (> 0)",
        0.1,
        "",
        POSITIVE,
        INF,
    ),
    gravity(vr::G),
    contact_stiffness(vr::KT, 5.6e4),
    real_parameter(
        "alpha",
        vr::ALPHA,
        "Dahl shape exponent (> 0)",
        1.0,
        "",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "vc",
        vr::VC,
        "Constant sliding velocity",
        0.23,
        "m/s",
        -INF,
        INF,
    ),
    real_parameter(
        "va",
        vr::VA,
        "Vibration velocity amplitude xa*w",
        0.264,
        "m/s",
        0.0,
        INF,
    ),
    real_parameter(
        "f",
        vr::F,
        "Vibration frequency; also the averaging period 1/f of FT_mean (> 0)",
        60_000.0,
        "Hz",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "FS",
        vr::FS,
        "LuGre static (breakaway) force (> 0)",
        0.021_582,
        "N",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "vs",
        vr::VS,
        "LuGre Stribeck velocity (> 0)",
        0.01,
        "m/s",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "sigma1",
        vr::SIGMA1,
        "LuGre bristle damping",
        0.0,
        "N.s/m",
        0.0,
        INF,
    ),
    real_parameter(
        "sigma2",
        vr::SIGMA2,
        "LuGre viscous coefficient",
        0.0,
        "N.s/m",
        0.0,
        INF,
    ),
    real_input(
        "vr_in",
        vr::VR_IN,
        "Sliding velocity when velocity_source = input",
        0.0,
        "m/s",
    ),
    real_input(
        "FN_in",
        vr::FN_IN,
        "Normal force when normal_force_source = input (> 0)",
        0.1962,
        "N",
    ),
    real_output(
        "FT",
        vr::FT,
        "Friction force, positive when it resists +x sliding",
        "N",
        &[vr::VR_IN, vr::FN_IN],
    ),
    real_output(
        "z",
        vr::Z,
        "Bristle (asperity) deflection; 0 for Coulomb",
        "m",
        &[],
    ),
    real_output("vr", vr::VR, "Sliding velocity", "m/s", &[vr::VR_IN]),
    real_output(
        "FT_mean",
        vr::FT_MEAN,
        "Mean of FT over the last complete period 1/f (eq. 3.1, as an integral)",
        "N",
        &[],
    ),
    real_output(
        "S",
        vr::S,
        "Reduction of the mean friction force, (1 - FT_mean/FC)*100 (eq. 3.3); with the normal force an input, FC is mu times its mean over the same period",
        "%",
        &[],
    ),
    real_output(
        "W_diss",
        vr::W_DISS,
        "Energy dissipated by the contact since the start: the integral of FT vr minus the energy kt z^2/2 stored in the deflection (never negative: the contact is passive)",
        "J",
        &[],
    ),
];

pub const TABLE: ModelTable = ModelTable {
    model_identifier: "LongitudinalFriction",
    description: "Sliding friction under longitudinal tangential contact vibration: Coulomb, Dahl and LuGre (Leus & Gutowski 2008)",
    variables: VARIABLES,
    enum_types: &[LAW, VELOCITY_SOURCE, NORMAL_FORCE_SOURCE, INITIAL, SOLVER, INPUT_SCHEME],
    input_switches: &[
        InputSwitch {
            switch: "velocity_source",
            item: "input",
            input: "vr_in",
        },
        InputSwitch {
            switch: "normal_force_source",
            item: "input",
            input: "FN_in",
        },
    ],
    interpolates_inputs: true,
    law_parameter: Some("law"),
    tolerance_parameter: Some("tolerance"),
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        // 42 vibration periods at 60 kHz, reported every microsecond (a whole number of
        // nanoseconds, as co-simulation engines' clocks need; 1/60 kHz is not).
        stop_time: 7e-4,
        tolerance: 1e-8,
        step_size: 1e-6,
    },
};
