// `TransverseFriction`: a body pulled over a support that vibrates across the sliding direction,
// with a 2D LuGre contact (paper T, eq. 1-30).

use crate::variables::declare::{
    body_mass, contact_stiffness, enum_parameter, gravity, input_scheme, integer_parameter,
    real_input, real_output, real_parameter, tolerance, INPUT_SCHEME, POSITIVE,
};
use crate::variables::variable::{DefaultExperiment, EnumType, InputSwitch, ModelTable, Variable};

/// Value references, named so the simulation code reads like the paper.
pub mod vr {
    pub const SLIP_LAW: u32 = 1;
    pub const SOLVER: u32 = 2;
    pub const DRIVE_SOURCE: u32 = 3;
    pub const BODY: u32 = 4;
    pub const INITIAL: u32 = 5;
    pub const STEPS_PER_PERIOD: u32 = 6;
    pub const TOLERANCE: u32 = 7;
    pub const INPUT_SCHEME: u32 = 8;
    pub const M: u32 = 10;
    pub const MU: u32 = 11;
    pub const G: u32 = 12;
    pub const FS_RATIO: u32 = 13;
    pub const VS: u32 = 14;
    pub const KT: u32 = 15;
    pub const ZETA: u32 = 16;
    pub const HV: u32 = 17;
    pub const KD: u32 = 18;
    pub const HD: u32 = 19;
    pub const ETA: u32 = 20;
    pub const VD: u32 = 21;
    pub const VA: u32 = 22;
    pub const F: u32 = 23;
    pub const VD_IN: u32 = 30;
    pub const FF: u32 = 40;
    pub const FFX: u32 = 41;
    pub const FFY: u32 = 42;
    pub const FD: u32 = 43;
    pub const FFX_MEAN: u32 = 44;
    pub const X: u32 = 45;
    pub const Y: u32 = 46;
    pub const S: u32 = 47;
    pub const BETA: u32 = 48;
    pub const W_DISS: u32 = 49;
}

const INF: f64 = f64::INFINITY;

pub const SLIP_LAW: EnumType = EnumType {
    name: "SlipLaw",
    items: &[
        (
            "split",
            "z' = vr - (|v1|/g(v1) + |v2|/g(v2)) z: body and support slip the contact separately, the limit of the paper's two-phase step",
        ),
        ("total", "z' = vr - |v1 + v2|/g(v1 + v2) z: slip on the total radial rate"),
    ],
};

pub const SOLVER: EnumType = EnumType {
    name: "TransverseSolver",
    items: &[
        (
            "dopri5",
            "Adaptive Dormand-Prince 5(4) to `tolerance`; steps end where v1, v2 (split) or v1 + v2 (total) change sign and at the edges of the Stribeck band |v1 + v2| < 4 vs",
        ),
        ("rk4", "Classical Runge-Kutta, steps_per_period fixed steps per vibration period"),
        (
            "two_phase",
            "The paper's scheme (eq. 11-29): body step, then support step, steps_per_period steps per vibration period; first order; slip_law is split by construction",
        ),
        (
            "radau5",
            "Adaptive 3-stage Radau IIA (order 5, L-stable) to `tolerance`, for stiff contacts (large kt); steps end at the same kinks as dopri5",
        ),
        (
            "exponential",
            "steps_per_period fixed steps per vibration period, cut where v1, v2 (split) or v1 + v2 (total) change sign: exact exponential bristle update for frozen velocities (stable at any kt) around an explicit midpoint step of the body; second order; for stiff contacts; needs h sqrt(kt/m) < 2",
        ),
        (
            "dop853",
            "Adaptive Dormand-Prince 8(5,3) to `tolerance`, for tight tolerances (1e-7 and below) on smooth motion, as the total slip law's steady vibration; steps end at the same kinks as dopri5; no integrating factor, so at loose tolerances and on stiff contacts dopri5 or radau5 take fewer steps",
        ),
    ],
};

pub const DRIVE_SOURCE: EnumType = EnumType {
    name: "DriveSource",
    items: &[
        ("prescribed", "The drive's far end moves at vd"),
        (
            "input",
            "The drive's far end moves at vd_in, moving linearly over the next step when the master sets its derivative (fmi2SetRealInputDerivatives), else as input_scheme says",
        ),
    ],
};

pub const BODY: EnumType = EnumType {
    name: "Body",
    items: &[
        ("free", "The body moves under the drive and contact forces (eq. 7-8)"),
        (
            "held",
            "The body is held at x = y = 0 (the paper's Fig. 4b check); Fd is the drive spring's pull on the holder",
        ),
    ],
};

pub const INITIAL: EnumType = EnumType {
    name: "InitialState",
    items: &[
        ("rest", "Body at rest, drive and contact unloaded"),
        (
            "sliding",
            "Steady 1D sliding at the drive velocity (vd, or vd_in at the start): body at that velocity, drive stretched to pull FC, contact deflected by g(vd) along x; only the vibration's transient remains (body free only)",
        ),
        (
            "periodic",
            "The periodic steady state under the vibration, found at initialization by shooting on the one-period map (body free, drive prescribed): FFx_mean is the steady value from the first period on; where no period-1 orbit is found, steady sliding, with a warning",
        ),
    ],
};

const VARIABLES: &[Variable] = &[
    enum_parameter(
        "slip_law",
        vr::SLIP_LAW,
        "Bristle slip law",
        SLIP_LAW.name,
        1,
    ),
    enum_parameter("solver", vr::SOLVER, "Integration scheme", SOLVER.name, 1),
    enum_parameter(
        "drive_source",
        vr::DRIVE_SOURCE,
        "Where the drive velocity comes from",
        DRIVE_SOURCE.name,
        1,
    ),
    enum_parameter("body", vr::BODY, "Free body, or held still", BODY.name, 1),
    enum_parameter("initial", vr::INITIAL, "Initial state", INITIAL.name, 1),
    input_scheme(vr::INPUT_SCHEME),
    integer_parameter(
        "steps_per_period",
        vr::STEPS_PER_PERIOD,
        "Fixed steps per vibration period (rk4, two_phase, exponential)",
        2000,
        1,
        100_000_000,
    ),
    // As scene L's (what it gives and costs: docs/performance.md, "Cost per call").
    tolerance(vr::TOLERANCE, 1e-8),
    body_mass(vr::M, 0.56),
    real_parameter(
        "mu",
        vr::MU,
        "Friction coefficient, FC = mu m g (> 0)",
        0.178,
        "",
        POSITIVE,
        INF,
    ),
    gravity(vr::G),
    real_parameter(
        "FS_ratio",
        vr::FS_RATIO,
        "Static to Coulomb force FS/FC (> 0)",
        1.1,
        "",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "vs",
        vr::VS,
        "Stribeck velocity, also the damping cut-off ve (> 0)",
        1e-6,
        "m/s",
        POSITIVE,
        INF,
    ),
    contact_stiffness(vr::KT, 6.286e7),
    real_parameter(
        "zeta",
        vr::ZETA,
        "Critical damping ratio of the contact, ht = 2 zeta sqrt(m kt) exp(-(v/vs)^2)",
        1.0,
        "",
        0.0,
        INF,
    ),
    real_parameter(
        "hv",
        vr::HV,
        "Viscous friction coefficient",
        0.0,
        "N.s/m",
        0.0,
        INF,
    ),
    real_parameter("kd", vr::KD, "Drive stiffness", 9.2e5, "N/m", 0.0, INF),
    real_parameter("hd", vr::HD, "Drive damping", 0.0, "N.s/m", 0.0, INF),
    real_parameter(
        "eta",
        vr::ETA,
        "Fraction of the support motion reaching the contact point M (eq. 21)",
        0.71,
        "",
        0.0,
        1.0,
    ),
    real_parameter(
        "vd",
        vr::VD,
        "Drive velocity when drive_source = prescribed",
        5e-4,
        "m/s",
        -INF,
        INF,
    ),
    real_parameter(
        "va",
        vr::VA,
        "Vibration velocity amplitude u0*w of the support, yp = u0 sin(w t)",
        2e-3,
        "m/s",
        0.0,
        INF,
    ),
    real_parameter(
        "f",
        vr::F,
        "Vibration frequency; also the averaging period 1/f of FFx_mean (> 0)",
        3000.0,
        "Hz",
        POSITIVE,
        INF,
    ),
    real_input(
        "vd_in",
        vr::VD_IN,
        "Drive velocity when drive_source = input",
        5e-4,
        "m/s",
    ),
    real_output(
        "FF",
        vr::FF,
        "Friction force magnitude kt s + ht sdot + hv vr (eq. 2)",
        "N",
        &[],
    ),
    real_output(
        "FFx",
        vr::FFX,
        "FF cos(beta), positive when it resists +x sliding (eq. 26)",
        "N",
        &[],
    ),
    real_output(
        "FFy",
        vr::FFY,
        "FF sin(beta), the y-force on the body (eq. 27)",
        "N",
        &[],
    ),
    real_output(
        "Fd",
        vr::FD,
        "Drive force kd (vd t - x) + hd (vd - x') (eq. 9-10)",
        "N",
        &[vr::VD_IN],
    ),
    real_output(
        "FFx_mean",
        vr::FFX_MEAN,
        "Mean of FFx over the last complete vibration period (eq. 30, as an integral)",
        "N",
        &[],
    ),
    real_output("x", vr::X, "Body displacement along the drive", "m", &[]),
    real_output("y", vr::Y, "Body displacement across the drive", "m", &[]),
    real_output("s", vr::S, "Contact deflection |N - M| (eq. 1)", "m", &[]),
    real_output(
        "beta",
        vr::BETA,
        "Direction of the deflection: N - M = s (cos beta, -sin beta)",
        "rad",
        &[],
    ),
    real_output(
        "W_diss",
        vr::W_DISS,
        "Energy dissipated by the contact since the start: the work FF (v1 + v2) the body and the support do on it, minus the energy kt s^2/2 stored in the deflection",
        "J",
        &[],
    ),
];

pub const TABLE: ModelTable = ModelTable {
    model_identifier: "TransverseFriction",
    description: "Sliding friction under transverse tangential vibration of the support: 2D LuGre contact, body on a compliant drive",
    variables: VARIABLES,
    enum_types: &[SLIP_LAW, SOLVER, DRIVE_SOURCE, BODY, INITIAL, INPUT_SCHEME],
    input_switches: &[InputSwitch {
        switch: "drive_source",
        item: "input",
        input: "vd_in",
    }],
    interpolates_inputs: true,
    law_parameter: Some("slip_law"),
    tolerance_parameter: Some("tolerance"),
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        // 150 vibration periods at 3 kHz (the drive mode, ~200 Hz, settles in a few ms),
        // reported every 10 us, about 33 times a period (a whole number of nanoseconds).
        stop_time: 0.05,
        tolerance: 1e-8,
        step_size: 1e-5,
    },
};

#[cfg(test)]
mod tests {
    use super::{vr, TABLE};

    #[test]
    fn value_references_are_unique_and_named() {
        for v in TABLE.variables {
            assert_eq!(
                TABLE
                    .variables
                    .iter()
                    .filter(|w| w.value_reference == v.value_reference)
                    .count(),
                1,
                "{}",
                v.name
            );
        }
        assert_eq!(
            TABLE.by_name("FFx_mean").unwrap().value_reference,
            vr::FFX_MEAN
        );
        assert_eq!(TABLE.by_name("vd_in").unwrap().value_reference, vr::VD_IN);
    }
}
