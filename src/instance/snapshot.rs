//! FMU states: a full copy of an instance's dynamic data, and its byte form.
//!
//! The bytes carry a magic word, a format version, their own length, the model's GUID and a
//! checksum, so truncated, corrupted or foreign data is refused with a message instead of being
//! loaded. The length comes right after the magic word: deserialization compares it with
//! the size it is given before reading further, so a size larger than the data is refused
//! without reading past the data's end.

use super::calls::Call;
use super::phase::Phase;
use super::Instance;
use crate::error::Error;
use crate::models::Simulation;
use crate::variables::values::check_value;
use crate::variables::variable::{Causality, Kind};

const MAGIC: &[u8; 8] = b"FRICFMU\x02";

/// The magic word and the length: what [`declared_length`] reads.
pub const HEADER: usize = MAGIC.len() + 8;

/// The length the bytes of an FMU state say they have, from their first [`HEADER`] bytes; None
/// when those are not this FMU's header.
pub fn declared_length(header: &[u8]) -> Option<u64> {
    let length = header.get(MAGIC.len()..HEADER)?;
    (header[..MAGIC.len()] == *MAGIC)
        .then(|| u64::from_le_bytes(length.try_into().unwrap_or([0; 8])))
}

#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    /// The instance that took it: a state is restored only into its own instance.
    pub owner: u64,
    pub guid: String,
    pub phase: Phase,
    pub start_time: f64,
    pub stop_time: Option<f64>,
    pub time: f64,
    pub last_successful_time: f64,
    pub values: Vec<f64>,
    /// None before initialisation has finished.
    pub sim: Option<Vec<f64>>,
}

impl Snapshot {
    pub fn take(instance: &Instance) -> Snapshot {
        Snapshot {
            owner: instance.id,
            guid: instance.guid().to_string(),
            phase: instance.phase,
            start_time: instance.start_time,
            stop_time: instance.stop_time,
            time: instance.time,
            last_successful_time: instance.last_successful_time,
            values: instance.values.as_slice().to_vec(),
            sim: instance.sim.as_ref().map(|s| s.save()),
        }
    }

    /// Puts the instance back to this state; the error says why it cannot.
    pub fn restore(&self, instance: &mut Instance) -> Result<(), Error> {
        if self.owner != instance.id {
            return Err(Error::state(
                "the FMU state was taken from another instance",
                "a state of this instance",
            ));
        }
        if self.values.len() != instance.values.as_slice().len() {
            return Err(Error::state(
                format!("the FMU state holds {} values", self.values.len()),
                format!("{}", instance.values.as_slice().len()),
            ));
        }
        // Only values the setters would accept (outputs are recomputed from the simulation). An
        // Integer or Enumeration arrives through an integer setter, so it is a whole number;
        // check that here, as check_value lets NaN and fractions through for those kinds. The
        // values are in the table's order. The values the instance holds passed those checks
        // when they were set, so a state that holds the same ones (a master retrying a step)
        // needs none of them again.
        let table = instance.model.table;
        let given = || {
            table
                .variables
                .iter()
                .zip(&self.values)
                .filter(|(var, _)| var.causality != Causality::Output)
        };
        let current = instance.values.as_slice();
        let same_values = table
            .variables
            .iter()
            .zip(self.values.iter().zip(current))
            .filter(|(var, _)| var.causality != Causality::Output)
            .all(|(_, (then, now))| then.to_bits() == now.to_bits());
        if !same_values {
            for (var, &value) in given() {
                let whole = matches!(var.kind, Kind::Real { .. }) || value.fract() == 0.0;
                if !whole {
                    return Err(Error::state(
                        format!("the FMU state holds {} = {value}", var.name),
                        "a whole number",
                    ));
                }
                check_value(table, var, value).map_err(|e| {
                    Error::state(format!("the FMU state holds {}", e.found), e.expected)
                })?;
            }
        }
        // The simulation the instance has can take the state as it is when it was built from
        // the same values and start time: no build, and no periodic start computed again.
        let same_build = same_values && self.start_time == instance.start_time;
        // A model exists from the end of initialization on, and only then.
        let needs_simulation =
            !matches!(self.phase, Phase::Instantiated | Phase::InitializationMode);
        if needs_simulation != self.sim.is_some() {
            return Err(Error::state(
                format!(
                    "the FMU state is in phase {} {} a model state",
                    instance.phase_name(self.phase),
                    if needs_simulation { "without" } else { "with" },
                ),
                if needs_simulation {
                    format!(
                        "one with it after {}",
                        instance.function(Call::ExitInitializationMode)
                    )
                } else {
                    "one without it before".to_string()
                },
            ));
        }
        // A simulation whose clock is not the instance's would step from another time (a forged
        // state could make a step that never ends). A failed step is rolled back, so this holds
        // in StepFailed too.
        let same_time = |sim: &dyn Simulation| {
            if sim.time() == self.time {
                Ok(())
            } else {
                Err(Error::state(
                    format!(
                        "the FMU state's model is at t = {} but the state says t = {}",
                        sim.time(),
                        self.time
                    ),
                    "the same time",
                ))
            }
        };
        let sim = match &self.sim {
            None => None,
            Some(state) => match instance.sim.take() {
                Some(mut sim) if same_build => {
                    sim.save_into(&mut instance.rollback);
                    if let Err(why) = sim.restore(state).and_then(|()| same_time(&*sim)) {
                        // A refused state leaves the instance as it was.
                        let _ = sim.restore(&instance.rollback);
                        instance.sim = Some(sim);
                        return Err(why);
                    }
                    Some(sim)
                }
                other => {
                    instance.sim = other;
                    let mut values = instance.values.clone();
                    values.load(&self.values);
                    let mut sim =
                        (instance.model.build)(&values, self.start_time, &instance.scope)?;
                    sim.restore(state)?;
                    same_time(&*sim)?;
                    Some(sim)
                }
            },
        };
        instance.values.load(&self.values);
        instance.sim = sim;
        instance.outputs_current = false;
        instance.phase = self.phase;
        instance.start_time = self.start_time;
        instance.stop_time = self.stop_time;
        instance.time = self.time;
        instance.last_successful_time = self.last_successful_time;
        Ok(())
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let mut numbers = vec![
            self.phase.code(),
            self.start_time,
            self.stop_time.unwrap_or(f64::NAN),
            self.time,
            self.last_successful_time,
            self.values.len() as f64,
        ];
        numbers.extend(&self.values);
        if let Some(sim) = &self.sim {
            numbers.push(sim.len() as f64);
            numbers.extend(sim);
        } else {
            numbers.push(-1.0);
        }
        let length = HEADER + 4 + self.guid.len() + 8 * numbers.len() + 8;
        let mut bytes = Vec::with_capacity(length);
        bytes.extend(MAGIC);
        bytes.extend((length as u64).to_le_bytes());
        bytes.extend((self.guid.len() as u32).to_le_bytes());
        bytes.extend(self.guid.as_bytes());
        for x in numbers {
            bytes.extend(x.to_le_bytes());
        }
        let sum = checksum(&bytes);
        bytes.extend(sum.to_le_bytes());
        bytes
    }

    /// Reads bytes written by [`Snapshot::to_bytes`] for the model with `guid`, owned by `owner`;
    /// `sizes` names the function that gives the bytes' size.
    pub fn from_bytes(
        bytes: &[u8],
        guid: &str,
        owner: u64,
        sizes: &str,
    ) -> Result<Snapshot, Error> {
        let corrupt = |what: &str| {
            Error::state(
                format!("the serialized FMU state is not valid: {what}"),
                "the bytes this FMU serialized, whole",
            )
        };
        let Some(length) = declared_length(bytes) else {
            return Err(corrupt(
                "it does not start with this FMU's header (truncated or foreign data)",
            ));
        };
        if length != bytes.len() as u64 || bytes.len() < HEADER + 4 + 8 {
            return Err(corrupt(&format!(
                "it says it is {length} bytes long but {} were given (truncated, or a size other than {sizes}'s)",
                bytes.len()
            )));
        }
        let (body, sum) = bytes.split_at(bytes.len() - 8);
        if checksum(body).to_le_bytes() != sum {
            return Err(corrupt(
                "its checksum does not match (truncated or corrupted)",
            ));
        }
        let mut rest = &body[HEADER..];
        let guid_len =
            u32::from_le_bytes(rest[..4].try_into().map_err(|_| corrupt("short header"))?) as usize;
        rest = &rest[4..];
        if rest.len() < guid_len || &rest[..guid_len] != guid.as_bytes() {
            return Err(corrupt(&format!(
                "it belongs to another model: expected GUID {guid}"
            )));
        }
        rest = &rest[guid_len..];
        if rest.len() % 8 != 0 {
            return Err(corrupt("its length is not a whole number of values"));
        }
        let numbers: Vec<f64> = rest
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        let mut it = numbers.into_iter();
        let mut next = |what: &str| {
            it.next()
                .ok_or_else(|| corrupt(&format!("it ends before {what}")))
        };
        // No state is taken between a step's internal steps.
        let phase = Phase::from_code(next("the state")?)
            .filter(|&phase| phase != Phase::IntermediateUpdate)
            .ok_or_else(|| corrupt("unknown state code"))?;
        let start_time = next("the start time")?;
        let stop = next("the stop time")?;
        let time = next("the time")?;
        let last_successful_time = next("the last successful time")?;
        let count = |n: f64| (n >= 0.0 && n.fract() == 0.0 && n < 1e6).then_some(n as usize);
        let n_values = count(next("the value count")?).ok_or_else(|| corrupt("bad value count"))?;
        let values = (0..n_values)
            .map(|_| next("the values"))
            .collect::<Result<Vec<_>, _>>()?;
        let n_simulation = next("the simulation state")?;
        let sim = if n_simulation == -1.0 {
            None
        } else {
            let n = count(n_simulation).ok_or_else(|| corrupt("bad state length"))?;
            Some(
                (0..n)
                    .map(|_| next("the simulation state"))
                    .collect::<Result<Vec<_>, _>>()?,
            )
        };
        if next("its end").is_ok() {
            return Err(corrupt("it has trailing data"));
        }
        // Times the setters would refuse must not come in this way either: a simulation built at a
        // start time of -inf never finishes a step.
        let finite_times = [start_time, time, last_successful_time]
            .iter()
            .all(|t| t.is_finite());
        let ordered = start_time <= last_successful_time && last_successful_time <= time;
        if !finite_times || !ordered || stop < start_time {
            return Err(corrupt(&format!(
                "its times (start {start_time}, last successful {last_successful_time}, now {time}, stop {stop}) are not finite and in that order"
            )));
        }
        Ok(Snapshot {
            owner,
            guid: guid.to_string(),
            phase,
            start_time,
            stop_time: (!stop.is_nan()).then_some(stop),
            time,
            last_successful_time,
            values,
            sim,
        })
    }
}

/// FNV-1a 64: enough to catch truncation and bit flips, not meant against forgery.
fn checksum(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
