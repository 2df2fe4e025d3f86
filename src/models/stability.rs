//! What a model is run at in the stability matrix (src/report/stability.rs), as data: each
//! model's folder holds its own cases (`<model>/stability.rs`), and its [`super::Model`] names
//! them.

/// A parameter value as the FMU takes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Real(f64),
    Integer(i32),
    /// An enumeration item, by name.
    Item(&'static str),
}

/// One extreme of a model: what it is called in the matrix, its parameters, the communication
/// step and the number of steps.
pub type Extreme = (&'static str, &'static [(&'static str, Value)], f64, u64);

/// A model's cases: every solver item runs every extreme.
pub struct Cases {
    /// Parameters every case starts from.
    pub base: &'static [(&'static str, Value)],
    pub extremes: &'static [Extreme],
    /// A friction law with no solver (a closed form, the exact switch model), which runs every
    /// extreme as a row of its own: the switch and its item.
    pub fixed_law: Option<(&'static str, &'static str)>,
}
