//! Nothing to link: the FMUs' libraries are this package's cdylib example targets, one per model
//! and kind (src/*.rs beside this file). A package needs a library or binary target to exist.
