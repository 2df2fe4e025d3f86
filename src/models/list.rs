// The models this crate exports, in the order the CLI builds them: each model's folder under
// src/models and the name of its `Model` constant. Adding a model is a line here and its
// `pub mod` in src/models/mod.rs. The crate (src/models/mod.rs) and build.rs each read this list
// with a `models!` of their own.
models! {
    longitudinal => LONGITUDINAL,
    transverse => TRANSVERSE,
    oscillator => OSCILLATOR,
    drive => DRIVE,
}
