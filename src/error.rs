//! The errors of the models, their solvers and their saved states: what kind of thing went
//! wrong, what was found and what was expected. They stay values through every layer; the
//! instance (src/instance) turns one into a status and a logged message, once, where it meets
//! the importer, and tests match their kind, not their words.

use std::fmt;

/// What went wrong: its [`Kind`], what was found and what was expected instead. Shown as
/// "found: expected expected".
#[derive(Clone, Debug, PartialEq)]
pub struct Error {
    pub kind: Kind,
    /// What was found, with where: the value, the combination, the step that failed.
    pub found: String,
    /// What was expected instead, or what would have worked.
    pub expected: String,
}

/// The kinds of error, for the code that decides what follows from one and for the tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A value the model cannot take: a parameter, an input (`name` as the table spells it), a
    /// switch's number, a start time.
    Value { name: &'static str },
    /// Values acceptable each alone but not together (a solver and a law, an initial state and
    /// an input).
    Combination,
    /// A request this simulation does not serve: an input's derivative where inputs are held,
    /// an output's derivative, a value reference that is not an input.
    Refused,
    /// A saved state that does not fit the simulation it is restored into.
    State,
    /// A step `solver` could not complete: the instance discards it and rolls back.
    Step {
        solver: &'static str,
        failure: Failure,
    },
}

/// Why a step could not be completed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Failure {
    /// More steps or right-hand sides than one call may take.
    TooManySteps,
    /// The step fell below what the clock resolves.
    StepTooShort,
    /// A Newton iteration did not converge.
    NoConvergence,
    /// The state (or an integrand) left the finite numbers.
    NotFinite,
    /// A fixed step beyond the solver's stability bound, refused before it is taken.
    BeyondStability,
    /// The contact created energy: an unstable integration caught while still finite.
    CreatedEnergy,
    /// The motion switches between sticking and sliding faster than can be resolved.
    Chatter,
    /// The solver was asked for what it cannot do (an interval, a state size, a reading).
    Misuse,
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    fn new(kind: Kind, found: impl Into<String>, expected: impl Into<String>) -> Self {
        Error {
            kind,
            found: found.into(),
            expected: expected.into(),
        }
    }

    /// `name = value` out of range, where `expected` says the range.
    pub fn value(
        name: &'static str,
        value: impl fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        Self::new(
            Kind::Value { name },
            format!("{name} = {value} is out of range"),
            expected,
        )
    }

    /// A value described by `found` (several numbers, or one with context).
    pub fn value_found(
        name: &'static str,
        found: impl Into<String>,
        expected: impl Into<String>,
    ) -> Self {
        Self::new(Kind::Value { name }, found, expected)
    }

    pub fn combination(found: impl Into<String>, expected: impl Into<String>) -> Self {
        Self::new(Kind::Combination, found, expected)
    }

    pub fn refused(found: impl Into<String>, expected: impl Into<String>) -> Self {
        Self::new(Kind::Refused, found, expected)
    }

    pub fn state(found: impl Into<String>, expected: impl Into<String>) -> Self {
        Self::new(Kind::State, found, expected)
    }

    /// A step of `solver` that failed for `failure`; `found` says what happened and where.
    pub fn step(
        solver: &'static str,
        failure: Failure,
        found: impl Into<String>,
        expected: impl Into<String>,
    ) -> Self {
        Self::new(Kind::Step { solver, failure }, found, expected)
    }

    /// The failure of a step, if this is one.
    pub fn failure(&self) -> Option<Failure> {
        match self.kind {
            Kind::Step { failure, .. } => Some(failure),
            _ => None,
        }
    }

    /// The variable a value error names, if this is one.
    pub fn value_name(&self) -> Option<&'static str> {
        match self.kind {
            Kind::Value { name } => Some(name),
            _ => None,
        }
    }

    /// Says that the times in `found` count from `start`, the communication step's start (the
    /// equations' time starts there, so the clock's round-off does not cut the steps).
    pub fn counted_from(mut self, start: f64) -> Self {
        self.found.push_str(&format!(
            " (the solver's times count from the communication step's start, t = {start} s)"
        ));
        self
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Kind::Step { solver, .. } = self.kind {
            write!(f, "{solver}: ")?;
        }
        write!(f, "{}: expected {}", self.found, self.expected)
    }
}

impl std::error::Error for Error {}

/// The command line and the report say an error as its message.
#[cfg(feature = "tools")]
impl From<Error> for String {
    fn from(error: Error) -> Self {
        error.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::{Error, Failure, Kind};

    #[test]
    fn an_error_says_what_was_found_and_what_was_expected() {
        let e = Error::value("kt", -1.0, "kt > 0");
        assert_eq!(e.kind, Kind::Value { name: "kt" });
        assert_eq!(e.to_string(), "kt = -1 is out of range: expected kt > 0");
        let e = Error::step(
            "rk4",
            Failure::NotFinite,
            "the state became non-finite by t = 1",
            "a shorter step",
        )
        .counted_from(2.0);
        assert_eq!(e.failure(), Some(Failure::NotFinite));
        assert_eq!(
            e.to_string(),
            "rk4: the state became non-finite by t = 1 (the solver's times count from the communication step's start, t = 2 s): expected a shorter step"
        );
    }
}
