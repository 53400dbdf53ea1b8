//! The list of normal laws by name: one list for the command line, the serde tags
//! of [`AnyNormalLaw`](super::AnyNormalLaw) and the catalogue `hcm laws` prints.

use super::{parameters::index_of, ParameterInfo};
use super::{Flores, Hertz, HuntCrossley, Impact, LankaraniNikravesh, VariableStiffness};
use core::fmt;

/// Which normal law, without its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LawKind {
    /// Hertz, Eq 2.
    Hertz,
    /// Lankarani–Nikravesh, Eq 4–5.
    LankaraniNikravesh,
    /// Variable stiffness, Eq 6–7.
    VariableStiffness,
    /// MSC ADAMS IMPACT, Eq 8–9.
    Impact,
    /// Hunt–Crossley.
    HuntCrossley,
    /// Flores et al.
    Flores,
}

impl LawKind {
    /// Every law, in catalogue order.
    pub const ALL: [LawKind; 6] = [
        LawKind::Hertz,
        LawKind::LankaraniNikravesh,
        LawKind::VariableStiffness,
        LawKind::Impact,
        LawKind::HuntCrossley,
        LawKind::Flores,
    ];

    /// The name used in scenario files, on the command line and as the serde tag.
    pub const fn name(self) -> &'static str {
        match self {
            LawKind::Hertz => "hertz",
            LawKind::LankaraniNikravesh => "lankarani_nikravesh",
            LawKind::VariableStiffness => "variable_stiffness",
            LawKind::Impact => "impact",
            LawKind::HuntCrossley => "hunt_crossley",
            LawKind::Flores => "flores",
        }
    }

    /// The law called `name`; `None` if no law has that name.
    pub fn from_name(name: &str) -> Option<LawKind> {
        LawKind::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// Where the formula comes from (the paper's equation or the original article).
    pub const fn source(self) -> &'static str {
        match self {
            LawKind::Hertz => "Eq 2 (k from Eq 3)",
            LawKind::LankaraniNikravesh => "Eq 4–5",
            LawKind::VariableStiffness => "Eq 6–7 (as printed)",
            LawKind::Impact => "Eq 8–9 (MSC ADAMS)",
            LawKind::HuntCrossley => "Hunt & Crossley 1975",
            LawKind::Flores => "Flores et al. 2011",
        }
    }

    /// The formula f_n (N) for δ > 0, in plain text.
    pub const fn formula(self) -> &'static str {
        match self {
            LawKind::Hertz => "k·δ^n",
            LawKind::LankaraniNikravesh => "k·δ^n + 3k(1−ce²)δ^n/(4δ̇0)·δ̇",
            LawKind::VariableStiffness => "k(δ)·δ + 2λ·√(k(δ)·m_e)·δ·δ̇, k(δ) = c·E*·√(2rδ−δ²)",
            LawKind::Impact => "max(0, k·δ^e + step(δ, 0, 0, δ_max, d_max)·δ̇)",
            LawKind::HuntCrossley => "k·δ^n·(1 + χ·δ̇)",
            LawKind::Flores => "k·δ^n·(1 + 8(1−ce)/(5·ce·δ̇0)·δ̇)",
        }
    }

    /// The law's parameters in field order (the order of `values` and `from_values`
    /// of [`AnyNormalLaw`](super::AnyNormalLaw)).
    pub const fn parameters(self) -> &'static [ParameterInfo] {
        match self {
            LawKind::Hertz => Hertz::<f64>::PARAMETERS,
            LawKind::LankaraniNikravesh => LankaraniNikravesh::<f64>::PARAMETERS,
            LawKind::VariableStiffness => VariableStiffness::<f64>::PARAMETERS,
            LawKind::Impact => Impact::<f64>::PARAMETERS,
            LawKind::HuntCrossley => HuntCrossley::<f64>::PARAMETERS,
            LawKind::Flores => Flores::<f64>::PARAMETERS,
        }
    }

    /// Position of parameter `name` in [`LawKind::parameters`]; `None` if the law
    /// has no parameter of that name.
    pub fn parameter_index(self, name: &str) -> Option<usize> {
        index_of(self.parameters(), name)
    }
}

impl fmt::Display for LawKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::LawKind;

    /// Position in [`LawKind::ALL`]; the exhaustive match fails to compile when a
    /// law is added, pointing here.
    fn position(kind: LawKind) -> usize {
        match kind {
            LawKind::Hertz => 0,
            LawKind::LankaraniNikravesh => 1,
            LawKind::VariableStiffness => 2,
            LawKind::Impact => 3,
            LawKind::HuntCrossley => 4,
            LawKind::Flores => 5,
        }
    }

    #[test]
    fn all_lists_every_law_once() {
        for (i, kind) in LawKind::ALL.into_iter().enumerate() {
            assert_eq!(position(kind), i, "{kind}");
        }
    }

    #[test]
    fn names_are_found_and_distinct() {
        for kind in LawKind::ALL {
            assert_eq!(LawKind::from_name(kind.name()), Some(kind));
            let same = LawKind::ALL.iter().filter(|k| k.name() == kind.name());
            assert_eq!(same.count(), 1, "{kind}");
        }
        assert_eq!(LawKind::from_name("Hertz"), None);
        assert_eq!(LawKind::from_name(""), None);
    }

    #[test]
    fn every_parameter_has_a_unit_and_a_meaning() {
        for kind in LawKind::ALL {
            assert!(!kind.parameters().is_empty(), "{kind}");
            for p in kind.parameters() {
                assert!(
                    !p.unit.is_empty() && !p.meaning.is_empty(),
                    "{kind}.{}",
                    p.name
                );
                assert_eq!(
                    kind.parameter_index(p.name).map(|i| kind.parameters()[i]),
                    Some(*p)
                );
            }
        }
    }
}
