// `DriveTrain`: a DC motor driving a lead screw through a gear; the screw's nut pulls the far
// end of TransverseFriction's drive spring (F_load in, v_nut out).
//
// The defaults are illustrative, not a catalogue part: a small permanent-magnet motor (5 ohm,
// 1 mH, 0.01 N.m/A) with a 50:1 gearhead on a 1 mm lead screw, the kind of stage that moves a
// sample at sub-millimetre speeds. At V = 1.58 V and F_load = FC of TransverseFriction's
// defaults (mu m g = 0.978 N) the nut runs at 0.4999 mm/s, the drive speed vd = 0.5 mm/s there.
// The electrical time constant L/R is 0.2 ms, the mechanical one J R/(kt_m ke) 10 ms.

use crate::variables::declare::{
    enum_parameter, input_scheme, real_input, real_output, real_parameter, INPUT_SCHEME, POSITIVE,
};
use crate::variables::variable::{DefaultExperiment, EnumType, InputSwitch, ModelTable, Variable};

/// Value references.
pub mod vr {
    pub const SOLVER: u32 = 1;
    pub const VOLTAGE_SOURCE: u32 = 2;
    pub const INPUT_SCHEME: u32 = 3;
    pub const V: u32 = 10;
    pub const R: u32 = 11;
    pub const L: u32 = 12;
    pub const KT_M: u32 = 13;
    pub const KE: u32 = 14;
    pub const J: u32 = 15;
    pub const B: u32 = 16;
    pub const N: u32 = 17;
    pub const EFFICIENCY: u32 = 18;
    pub const LEAD: u32 = 19;
    pub const M_NUT: u32 = 20;
    pub const F_LOAD: u32 = 30;
    pub const V_IN: u32 = 31;
    pub const V_NUT: u32 = 40;
    pub const X_NUT: u32 = 41;
    pub const CURRENT: u32 = 42;
    pub const OMEGA: u32 = 43;
}

const INF: f64 = f64::INFINITY;

pub const SOLVER: EnumType = EnumType {
    name: "DriveSolver",
    items: &[(
        "exponential",
        "Exact: the equations are linear, so each communication step applies the matrix exponential of the system augmented with the inputs and their first derivatives (round-off accurate at any step)",
    )],
};

pub const VOLTAGE_SOURCE: EnumType = EnumType {
    name: "VoltageSource",
    items: &[
        ("parameter", "The armature voltage is the constant V"),
        ("input", "The armature voltage is the input V_in"),
    ],
};

const VARIABLES: &[Variable] = &[
    enum_parameter("solver", vr::SOLVER, "Integration scheme", SOLVER.name, 1),
    enum_parameter(
        "voltage_source",
        vr::VOLTAGE_SOURCE,
        "Where the armature voltage comes from",
        VOLTAGE_SOURCE.name,
        1,
    ),
    input_scheme(vr::INPUT_SCHEME),
    real_parameter(
        "V",
        vr::V,
        "Armature voltage when voltage_source = parameter (illustrative: 1.58 V runs the nut at 0.50 mm/s against 0.978 N)",
        1.58,
        "V",
        -INF,
        INF,
    ),
    real_parameter(
        "R",
        vr::R,
        "Armature resistance (> 0; illustrative small motor: 5)",
        5.0,
        "Ohm",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "L",
        vr::L,
        "Armature inductance (> 0; illustrative: 1e-3, L/R = 0.2 ms)",
        1e-3,
        "H",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "kt_m",
        vr::KT_M,
        "Motor torque constant (> 0; illustrative: 0.01)",
        0.01,
        "N.m/A",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "ke",
        vr::KE,
        "Back-emf constant (>= 0; equals kt_m in SI for an ideal motor)",
        0.01,
        "V.s/rad",
        0.0,
        INF,
    ),
    real_parameter(
        "J",
        vr::J,
        "Inertia of rotor, gear and screw at the motor shaft (> 0; illustrative: 2e-7, J R/(kt_m ke) = 10 ms)",
        2e-7,
        "kg.m2",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "b",
        vr::B,
        "Viscous loss at the motor shaft (illustrative: 1e-7)",
        1e-7,
        "N.m.s/rad",
        0.0,
        INF,
    ),
    real_parameter(
        "n",
        vr::N,
        "Gear ratio, motor speed over screw speed (> 0; illustrative: 50)",
        50.0,
        "",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "efficiency",
        vr::EFFICIENCY,
        "Efficiency of gear and screw together, 0 < efficiency <= 1 (1 = lossless); the load torque at the motor is r F_load / efficiency, r = lead/(2 pi n): the motoring quadrant, a linear model does not switch when the load drives the motor (illustrative: 0.9)",
        0.9,
        "",
        POSITIVE,
        1.0,
    ),
    real_parameter(
        "lead",
        vr::LEAD,
        "Lead of the screw: nut travel per screw revolution (> 0; illustrative: 1 mm)",
        1e-3,
        "m",
        POSITIVE,
        INF,
    ),
    real_parameter(
        "m_nut",
        vr::M_NUT,
        "Mass of nut and carriage, felt at the motor as m_nut r^2 / efficiency (illustrative: 0.05)",
        0.05,
        "kg",
        0.0,
        INF,
    ),
    real_input(
        "F_load",
        vr::F_LOAD,
        "Force resisting the nut's forward motion (TransverseFriction's Fd, the drive spring's pull)",
        0.0,
        "N",
    ),
    real_input(
        "V_in",
        vr::V_IN,
        "Armature voltage when voltage_source = input",
        1.58,
        "V",
    ),
    real_output(
        "v_nut",
        vr::V_NUT,
        "Nut velocity r omega, r = lead/(2 pi n) (TransverseFriction's vd_in)",
        "m/s",
        &[],
    ),
    real_output(
        "x_nut",
        vr::X_NUT,
        "Nut position since the start",
        "m",
        &[],
    ),
    real_output(
        "i",
        vr::CURRENT,
        "Armature current",
        "A",
        &[],
    ),
    real_output("omega", vr::OMEGA, "Motor speed", "rad/s", &[]),
];

pub const TABLE: ModelTable = ModelTable {
    model_identifier: "DriveTrain",
    description: "DC motor, gear and lead screw whose nut drives a load: a linear drive model for co-simulation with TransverseFriction",
    variables: VARIABLES,
    enum_types: &[SOLVER, VOLTAGE_SOURCE, INPUT_SCHEME],
    input_switches: &[InputSwitch {
        switch: "voltage_source",
        item: "input",
        input: "V_in",
    }],
    interpolates_inputs: true,
    law_parameter: None,
    tolerance_parameter: None,
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        // Five mechanical time constants: the start transient to steady speed.
        stop_time: 0.05,
        tolerance: 1e-10,
        step_size: 1e-4,
    },
};

#[cfg(test)]
mod tests {
    use super::{vr, TABLE};

    /// Oracle: the steady state of the defaults in closed form (the module comment's numbers):
    /// omega = (kt V - R r F/eff)/(kt ke + R b), v_nut = r omega.
    #[test]
    fn defaults_run_the_nut_at_half_a_millimetre_per_second_against_fc() {
        let start = |vr| match TABLE.variable(vr).unwrap().kind {
            crate::variables::variable::Kind::Real { start, .. } => start,
            _ => unreachable!(),
        };
        let r = start(vr::LEAD) / (std::f64::consts::TAU * start(vr::N));
        let fc = 0.178 * 0.56 * 9.81;
        let omega = (start(vr::KT_M) * start(vr::V)
            - start(vr::R) * r * fc / start(vr::EFFICIENCY))
            / (start(vr::KT_M) * start(vr::KE) + start(vr::R) * start(vr::B));
        let v_nut = r * omega;
        assert!((v_nut - 5e-4).abs() < 1e-6, "v_nut = {v_nut}");
    }
}
