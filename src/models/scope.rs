//! What a simulation's interface leaves out. A full model exposes every variable; a simulation
//! built from a variant (`friction-fmu build <file>`) hides the parameters it fixes and the outputs
//! it does not expose, and a simulation may then skip the state and work those would need (the y
//! axis when va is fixed at 0, the bristle when the law is fixed to Coulomb, the force mean when
//! FFx_mean is not read). The full model keeps one general path, so every trimmed model can be
//! checked against it.

/// The value references an instance hides; empty for the full model.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scope {
    hidden: Vec<u32>,
}

impl Scope {
    /// The full model: nothing hidden.
    pub fn full() -> Self {
        Scope::default()
    }

    /// A trimmed model hiding `hidden` (parameters fixed by the variant, outputs not exposed).
    pub fn hiding(mut hidden: Vec<u32>) -> Self {
        hidden.sort_unstable();
        hidden.dedup();
        Scope { hidden }
    }

    pub fn is_full(&self) -> bool {
        self.hidden.is_empty()
    }

    /// Whether `value_reference` is part of the interface (always, for the full model).
    pub fn exposes(&self, value_reference: u32) -> bool {
        self.hidden.binary_search(&value_reference).is_err()
    }

    /// Whether a parameter is fixed for good by the variant (hidden, so no setter reaches
    /// it): only then may a simulation specialise on its value.
    pub fn fixes(&self, value_reference: u32) -> bool {
        !self.exposes(value_reference)
    }

    pub fn hidden(&self) -> &[u32] {
        &self.hidden
    }
}

#[cfg(test)]
mod tests {
    use super::Scope;

    #[test]
    fn full_exposes_everything_and_trimmed_hides_what_it_lists() {
        assert!(Scope::full().exposes(7) && !Scope::full().fixes(7));
        let s = Scope::hiding(vec![9, 3, 9]);
        assert_eq!(s.hidden(), &[3, 9]);
        assert!(s.fixes(3) && s.fixes(9) && s.exposes(4) && !s.is_full());
    }
}
