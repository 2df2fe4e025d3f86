//! DriveTrain's equations: the motor, gear and screw ([`Params`]), the matrix of the linear
//! system on the state augmented with the inputs and their rates, and the rates of the current
//! and the speed.

use crate::solve::expm::Matrix;

pub(super) const DIM: usize = 7;
pub(super) const I: usize = 0;
pub(super) const OMEGA: usize = 1;
pub(super) const X: usize = 2;
const VOLTAGE: usize = 3;
const FORCE: usize = 4;
const VOLTAGE_RATE: usize = 5;
const FORCE_RATE: usize = 6;

/// The motor, gear and screw, fixed at build time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub resistance: f64,
    pub inductance: f64,
    pub kt: f64,
    pub ke: f64,
    /// Inertia at the motor shaft including the nut's mass reflected through gear and screw.
    pub j_eff: f64,
    pub b: f64,
    /// Nut travel per motor radian, lead / (2 pi n).
    pub r: f64,
    pub efficiency: f64,
    /// The constant armature voltage; None when it comes from V_in.
    pub voltage: Option<f64>,
}

impl Params {
    /// The matrix A of `z' = A z` for the augmented state (module comment).
    pub(super) fn system(&self) -> Matrix<DIM> {
        let mut a = [[0.0; DIM]; DIM];
        a[I][I] = -self.resistance / self.inductance;
        a[I][OMEGA] = -self.ke / self.inductance;
        a[I][VOLTAGE] = 1.0 / self.inductance;
        a[OMEGA][I] = self.kt / self.j_eff;
        a[OMEGA][OMEGA] = -self.b / self.j_eff;
        a[OMEGA][FORCE] = -self.r / (self.efficiency * self.j_eff);
        a[X][OMEGA] = self.r;
        a[VOLTAGE][VOLTAGE_RATE] = 1.0;
        a[FORCE][FORCE_RATE] = 1.0;
        a
    }

    /// (i', omega') at current `i`, speed `omega`, voltage and load.
    pub fn rates(&self, i: f64, omega: f64, voltage: f64, force: f64) -> (f64, f64) {
        (
            (voltage - self.resistance * i - self.ke * omega) / self.inductance,
            (self.kt * i - self.b * omega - self.r * force / self.efficiency) / self.j_eff,
        )
    }
}
