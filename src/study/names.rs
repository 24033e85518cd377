//! The names of the study's enumerated settings, one table per enum: the CLI's value parser
//! (`--solver dense`), its `--help`, the Python package's keyword values (`solver="dense"`)
//! and the advice spelling ([`super::python_spelling`]) all read these tables, so the
//! front ends cannot drift apart (issue 31: six CLI mirror enums and Python's own string
//! matching had).

use crate::eigen::EigenRoute;
use crate::element::BeamUpdate;
use crate::input::mbdyn::BeamUpdateChoice;
use crate::rom::Ranking;

use super::{BelowBand, RomForm, Setting, Solver, StudyError};

/// A library enum a front end names by word.
pub trait Named: Copy + PartialEq + Send + Sync + 'static {
    /// The setting whose values these are (its errors name it).
    const SETTING: Setting;
    /// Every value: its name, the value, what it does (the CLI's `--help` line).
    const NAMES: &'static [(&'static str, Self, &'static str)];

    /// The value's name.
    fn name(self) -> &'static str {
        Self::NAMES.iter().find(|(_, v, _)| *v == self).map_or("", |(n, _, _)| n)
    }

    /// The value named `word`; else an error naming the setting and the names it takes.
    fn from_name(word: &str) -> Result<Self, StudyError> {
        match Self::NAMES.iter().find(|(n, _, _)| *n == word) {
            Some((_, v, _)) => Ok(*v),
            None => Err(StudyError::Option { option: Self::SETTING, message: format!("'{word}': expected {}", quoted_list(Self::NAMES.iter().map(|(n, _, _)| *n))) }),
        }
    }
}

/// `"a", "b" or "c"`.
fn quoted_list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<String> = names.map(|n| format!("\"{n}\"")).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// The names `setting` takes, when it is an enumerated one.
pub fn value_names(setting: Setting) -> Option<Vec<&'static str>> {
    fn names<T: Named>() -> Option<Vec<&'static str>> {
        Some(T::NAMES.iter().map(|(n, _, _)| *n).collect())
    }
    match setting {
        Setting::Route => names::<EigenRoute>(),
        Setting::Solver => names::<Solver>(),
        Setting::Ranking => names::<Ranking>(),
        Setting::BelowBand => names::<BelowBand>(),
        Setting::Form => names::<RomForm>(),
        Setting::BeamUpdate => names::<BeamUpdateChoice>(),
        Setting::Discretize => Some(super::control::DISCRETIZATIONS.iter().map(|(n, _)| *n).collect()),
        _ => None,
    }
}

impl Named for EigenRoute {
    const SETTING: Setting = Setting::Route;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("direct", EigenRoute::Direct, "QZ on (λ F_yd + F_y) Y = 0 (paper eq. 10)"),
        ("lambda", EigenRoute::Lambda, "QZ on (Λ J + J*) Y = 0, λ = (1/c)(Λ+1)/(Λ−1) (paper eqs. 18–23)"),
    ];
}

impl Named for Solver {
    const SETTING: Setting = Setting::Solver;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("auto", Solver::Auto, "Sparse from 400 equations on, dense below (where the complete dense spectrum costs about a second or less) and for --count with --by dominance (a --band ranked by dominance stays sparse)"),
        ("dense", Solver::Dense, "QZ on the whole (deflated) pencil: every eigenvalue, zero and infinite ones labelled; n x n matrices"),
        ("sparse", Solver::Sparse, "Shift-invert Krylov–Schur on the sparse linearization: only the modes asked for (--count, --band, --modes; else the 10 lowest; --count N --by dominance: ranked among the 3N lowest), certified or warned about; memory grows with the non-zeros"),
    ];
}

impl Named for Ranking {
    const SETTING: Setting = Setting::Ranking;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("frequency", Ranking::Frequency, "Natural frequency, lowest first (every mode of a band is kept)"),
        ("dominance", Ranking::Dominance, "Dominance for the chosen inputs and outputs, ‖C v‖ ‖uᵀ B‖ / |λ| (a mode's share of the low-frequency response), largest first; modes that contribute nothing are never kept"),
    ];
}

impl Named for BelowBand {
    const SETTING: Setting = Setting::BelowBand;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("keep", BelowBand::Keep, "Keep it as a dynamic mode (warning)"),
        ("drop", BelowBand::Drop, "Leave it out of the ROM (warning)"),
        ("refuse", BelowBand::Refuse, "Stop with an error"),
    ];
}

impl Named for RomForm {
    const SETTING: Setting = Setting::Form;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("ordinary", RomForm::Ordinary, "x' = A x + B u, z = C x + D u (E = I), after SVD residualization (eqs. 51–63)"),
        ("descriptor", RomForm::Descriptor, "E x' = A x + B u, z = C x (eqs. 47–50)"),
    ];
}

impl Named for BeamUpdateChoice {
    const SETTING: Setting = Setting::BeamUpdate;
    const NAMES: &'static [(&'static str, Self, &'static str)] = &[
        ("auto", BeamUpdateChoice::Auto, "MBDyn's incremental update where the result comes from a time integration (`run`, a reference at a time), path independent for a static equilibrium or the initial configuration (in sweeps too); beams the incremental update cannot take (viscoelastic, driven sections) stay path independent with a warning (default)"),
        ("path-independent", BeamUpdateChoice::Every(BeamUpdate::PathIndependent), "Total rotations interpolated relative to the middle node: the beam is a function of the state, and a static equilibrium does not depend on load steps"),
        ("incremental", BeamUpdateChoice::Every(BeamUpdate::Incremental), "MBDyn 1.7.3's beam.cc: rotation increments interpolated per time step, section frames and curvatures accumulated (MBDyn's numbers; path dependent; elastic section laws only)"),
    ];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_back_to_its_value_and_a_bad_one_names_the_setting() {
        fn round_trip<T: Named + std::fmt::Debug>() {
            for (n, v, _) in T::NAMES {
                assert_eq!(T::from_name(n).unwrap(), *v);
                assert_eq!(v.name(), *n);
            }
            match T::from_name("nonsense") {
                Err(StudyError::Option { option, message }) => {
                    assert_eq!(option, T::SETTING);
                    assert!(message.starts_with("'nonsense': expected \""), "{message}");
                }
                other => panic!("{other:?}"),
            }
        }
        round_trip::<EigenRoute>();
        round_trip::<Solver>();
        round_trip::<Ranking>();
        round_trip::<BelowBand>();
        round_trip::<RomForm>();
        round_trip::<BeamUpdateChoice>();
        assert_eq!(Solver::from_name("x").unwrap_err().to_string(), "--solver: 'x': expected \"auto\", \"dense\" or \"sparse\"");
    }
}
