//! Why a variant file is refused: which file, which key, and the error (what was found, what
//! was expected).

use crate::error::Error;
use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub struct Refused {
    pub file: String,
    /// The key the refusal is about (`parameters.va`); None for the file as a whole.
    pub key: Option<String>,
    pub error: Error,
}

impl Refused {
    /// `error` about `key` of `file`.
    pub fn at(file: &str, key: &str, error: Error) -> Self {
        Refused {
            file: file.to_string(),
            key: Some(key.to_string()),
            error,
        }
    }

    /// `error` about `file` as a whole.
    pub fn file(file: &str, error: Error) -> Self {
        Refused {
            file: file.to_string(),
            key: None,
            error,
        }
    }

    /// Where: the file, and the key if one.
    fn place(&self) -> String {
        match &self.key {
            Some(key) => format!("{}: key `{key}`", self.file),
            None => self.file.clone(),
        }
    }
}

impl fmt::Display for Refused {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.place(), self.error)
    }
}

/// The error, its place said in what was found (for fmi2Instantiate's log).
impl From<Refused> for Error {
    fn from(refused: Refused) -> Self {
        Error {
            found: format!("{}: {}", refused.place(), refused.error.found),
            ..refused.error
        }
    }
}

/// The command line says a refusal as its message.
#[cfg(feature = "tools")]
impl From<Refused> for String {
    fn from(refused: Refused) -> Self {
        refused.to_string()
    }
}
