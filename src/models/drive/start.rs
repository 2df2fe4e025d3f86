//! How a DriveTrain run starts: the parameters read and checked, and the state at the startn//! time.

use super::equations::Params;
use super::switches::{DriveSolver, VoltageSource};
use super::table::vr;
use super::Drive;
use crate::error::Error;
use crate::models::input_scheme::{Extrapolator, InputScheme};
use crate::models::switch::Switch;
use crate::models::{require_finite_start, require_non_negative, require_positive, Scope};
use crate::solve::expm::Propagators;
use crate::variables::values::ValueSet;
use std::f64::consts::TAU;

impl Drive {
    /// The full model.
    pub fn new(values: &ValueSet, start_time: f64) -> Result<Self, Error> {
        Drive::with_scope(values, start_time, &Scope::full())
    }

    /// The simulation for any interface: the drive has nothing a scope lets it skip, and no
    /// periodic start to settle on (it starts at rest).
    pub fn with_scope(values: &ValueSet, start_time: f64, scope: &Scope) -> Result<Self, Error> {
        Drive::starting_from(values, start_time, scope)
    }

    /// The simulation at `start_time` with the drive at rest (i = omega = x_nut = 0).
    fn starting_from(values: &ValueSet, start_time: f64, _scope: &Scope) -> Result<Self, Error> {
        require_finite_start(start_time)?;
        let resistance = require_positive(values, vr::R)?;
        let inductance = require_positive(values, vr::L)?;
        let kt = require_positive(values, vr::KT_M)?;
        let ke = require_non_negative(values, vr::KE)?;
        let j = require_positive(values, vr::J)?;
        let b = require_non_negative(values, vr::B)?;
        let n = require_positive(values, vr::N)?;
        let efficiency = require_positive(values, vr::EFFICIENCY)?;
        if efficiency > 1.0 {
            return Err(Error::value(
                "efficiency",
                efficiency,
                "0 < efficiency <= 1",
            ));
        }
        let lead = require_positive(values, vr::LEAD)?;
        let m_nut = require_non_negative(values, vr::M_NUT)?;
        // One scheme: the matrix exponential (an unknown number is still refused).
        let DriveSolver::Exponential = DriveSolver::read(values, vr::SOLVER)?;
        let voltage = match VoltageSource::read(values, vr::VOLTAGE_SOURCE)? {
            VoltageSource::Input => None,
            VoltageSource::Parameter => Some(crate::models::require_finite(values, vr::V)?),
        };
        let r = lead / (TAU * n);
        let p = Params {
            resistance,
            inductance,
            kt,
            ke,
            j_eff: j + m_nut * r * r / efficiency,
            b,
            r,
            efficiency,
            voltage,
        };
        if !p.r.is_finite() || !p.j_eff.is_finite() {
            return Err(Error::combination(
                format!(
                    "lead / (2 pi n) = {} and J + m_nut r^2 / efficiency = {}",
                    p.r, p.j_eff
                ),
                "finite numbers",
            ));
        }
        Ok(Drive {
            p,
            t: start_time,
            y: [0.0; 3],
            inputs: [Extrapolator::default(); 2],
            input_scheme: InputScheme::read(values, vr::INPUT_SCHEME)?,
            propagators: Propagators::default(),
        })
    }
}
