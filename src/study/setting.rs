//! The settings of a study, named as each front end spells them: an error about a setting
//! carries the [`Setting`], and the CLI prints its flag (`--dcoef`), the Python package its
//! keyword (`dcoef`), so a Python user is not told about a flag they never wrote.

/// One setting of a study, a ROM request or a response grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The reference time (`--at`, `reference=`).
    ReferenceTime,
    /// A static equilibrium as the reference (`--static`, `reference="static"`).
    StaticEquilibrium,
    LoadSteps,
    Inputs,
    Outputs,
    Imposed,
    /// Dummy springs removed from the linear model (`--remove-spring`, `remove_springs=`).
    RemoveSprings,
    /// The eigenanalysis route (`--route`, `route=`).
    Route,
    Dcoef,
    Solver,
    Tolerance,
    /// The number of modes a ROM keeps or the sparse route computes (`--count`, `count=`).
    Count,
    /// A band of natural frequencies [Hz] (`--band FMIN:FMAX`, `band=(FMIN, FMAX)`).
    Band,
    /// Modes kept by index (`--modes`, `modes=`).
    Modes,
    /// Every dropped mode above the band statically residualized (`--residualize`).
    Residualize,
    /// Chosen dropped modes statically residualized (`--residualize-modes`, `residualize=[…]`).
    ResidualizeModes,
    /// How a `count` ranks the modes (`--by`, `by=`).
    Ranking,
    /// What residualization does with a mode below the band (`--below-band`, `below_band=`).
    BelowBand,
    Form,
    Fmin,
    Fmax,
    Points,
    BeamUpdate,
    /// A `set:` variable of the file given another value (`--set NAME=VALUE`, `set={…}`).
    Set,
    /// A discrete-time ROM's sample rate [Hz] (`--sample-rate`, `sample_rate=`).
    SampleRate,
    /// Its discretization method (`--discretize zoh|tustin|matched`).
    Discretize,
    /// Tustin's prewarping frequency [Hz].
    Prewarp,
    /// Balanced reduction to a number of states (`--balanced`, `balanced=`).
    Balanced,
    /// Balanced reduction by a Hankel singular value tolerance.
    HankelTol,
    /// Singular perturbation approximation instead of truncation.
    Spa,
    /// Minimal realization's tolerance.
    Minimal,
    /// A control loop cut open at a genel or an abstract force (`--cut genel:4`, `cut=[…]`).
    Cut,
    /// Modal damping ratios added to the ROM (`--damping`, `damping=`).
    Damping,
    /// The number of lowest modes a sweep tracks (`--lowest`, `lowest=`).
    Lowest,
    /// A validation's excitation (`--signal`, `signal=`).
    Signal,
    /// A validation's input RMS values [N or N m].
    Amplitudes,
    /// A validation's excited and compared band [Hz].
    ValidationBand,
    /// A validation's frequency resolution [Hz].
    Resolution,
    /// A validation's number of Welch segments.
    Averages,
    /// A validation's integration step and sampling period [s].
    TimeStep,
    /// A validation's coherence threshold.
    Coherence,
    /// A validation's time-domain fit threshold.
    Fit,
    /// A measured frequency response to compare with (a CSV file).
    Measured,
}

impl Setting {
    /// Every setting.
    pub const ALL: [Setting; 43] = [
        Setting::ReferenceTime,
        Setting::StaticEquilibrium,
        Setting::LoadSteps,
        Setting::Inputs,
        Setting::Outputs,
        Setting::Imposed,
        Setting::RemoveSprings,
        Setting::Route,
        Setting::BelowBand,
        Setting::Dcoef,
        Setting::Solver,
        Setting::Tolerance,
        Setting::Count,
        Setting::Band,
        Setting::Modes,
        Setting::Residualize,
        Setting::ResidualizeModes,
        Setting::Ranking,
        Setting::Form,
        Setting::Fmin,
        Setting::Fmax,
        Setting::Points,
        Setting::BeamUpdate,
        Setting::Set,
        Setting::SampleRate,
        Setting::Discretize,
        Setting::Prewarp,
        Setting::Balanced,
        Setting::HankelTol,
        Setting::Spa,
        Setting::Minimal,
        Setting::Cut,
        Setting::Damping,
        Setting::Lowest,
        Setting::Signal,
        Setting::Amplitudes,
        Setting::ValidationBand,
        Setting::Resolution,
        Setting::Averages,
        Setting::TimeStep,
        Setting::Coherence,
        Setting::Fit,
        Setting::Measured,
    ];

    /// The setting's two spellings: the command line's flag and the Python package's
    /// keyword argument. The one table both front ends' names come from.
    fn spellings(self) -> (&'static str, &'static str) {
        match self {
            Setting::ReferenceTime => ("--at", "reference"),
            Setting::StaticEquilibrium => ("--static", "reference"),
            Setting::LoadSteps => ("--load-steps", "load_steps"),
            Setting::Inputs => ("--input", "inputs"),
            Setting::Outputs => ("--output", "outputs"),
            Setting::Imposed => ("--imposed", "imposed"),
            Setting::RemoveSprings => ("--remove-spring", "remove_springs"),
            Setting::Route => ("--route", "route"),
            Setting::BelowBand => ("--below-band", "below_band"),
            Setting::Dcoef => ("--dcoef", "dcoef"),
            Setting::Solver => ("--solver", "solver"),
            Setting::Tolerance => ("--tolerance", "tolerance"),
            Setting::Count => ("--count", "count"),
            Setting::Band => ("--band", "band"),
            Setting::Modes => ("--modes", "modes"),
            Setting::Residualize => ("--residualize", "residualize"),
            Setting::ResidualizeModes => ("--residualize-modes", "residualize"),
            Setting::Ranking => ("--by", "by"),
            Setting::Form => ("--form", "form"),
            Setting::Fmin => ("--fmin", "fmin"),
            Setting::Fmax => ("--fmax", "fmax"),
            Setting::Points => ("--points", "points"),
            Setting::BeamUpdate => ("--beam-update", "beam_update"),
            Setting::Set => ("--set", "set"),
            Setting::SampleRate => ("--sample-rate", "sample_rate"),
            Setting::Discretize => ("--discretize", "discretize"),
            Setting::Prewarp => ("--prewarp", "prewarp"),
            Setting::Balanced => ("--balanced", "balanced"),
            Setting::HankelTol => ("--hankel-tol", "hankel_tol"),
            Setting::Spa => ("--spa", "spa"),
            Setting::Minimal => ("--minimal", "minimal"),
            Setting::Cut => ("--cut", "cut"),
            Setting::Damping => ("--damping", "damping"),
            Setting::Lowest => ("--lowest", "lowest"),
            Setting::Signal => ("--signal", "signal"),
            Setting::Amplitudes => ("--amplitudes", "amplitudes"),
            Setting::ValidationBand => ("--validation-band", "validation_band"),
            Setting::Resolution => ("--resolution", "resolution"),
            Setting::Averages => ("--averages", "averages"),
            Setting::TimeStep => ("--time-step", "time_step"),
            Setting::Coherence => ("--coherence", "coherence"),
            Setting::Fit => ("--fit", "fit"),
            Setting::Measured => ("--measured", "measured"),
        }
    }

    /// The command line's flag.
    pub fn cli_flag(self) -> &'static str {
        self.spellings().0
    }

    /// The Python package's keyword argument.
    pub fn python_name(self) -> &'static str {
        self.spellings().1
    }

    /// The setting a command-line flag (`--dcoef`) sets, if it is one of the library's.
    pub fn from_cli_flag(flag: &str) -> Option<Setting> {
        Self::ALL.into_iter().find(|s| s.cli_flag() == flag)
    }
}

/// Command-line flags the library's messages may name that have no Python counterpart: the
/// advice keeps them, marked as the command line's ([`python_spelling`]).
pub const COMMAND_LINE_ONLY: [&str; 6] = ["--pencil", "--input-row", "--output-col", "--all", "--against", "--report"];

/// The command line's spelling, as the library's messages print it.
impl std::fmt::Display for Setting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.cli_flag())
    }
}

/// A library message's advice, spelled as the Python package takes it: every command-line
/// flag in `text` (`--by dominance`, `--dcoef`, `--below-band keep`) becomes the keyword
/// argument of the same setting (`by="dominance"`, `dcoef=`, `below_band="keep"`), so a
/// Python user is not sent to flags they never wrote (issue 30 point 7, issue 31). Flags
/// with no Python counterpart keep their spelling and say so.
pub fn python_spelling(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("--") {
        let (before, from) = rest.split_at(at);
        out.push_str(before);
        let name_len = from[2..].find(|c: char| !(c.is_ascii_alphanumeric() || c == '-')).unwrap_or(from.len() - 2);
        let name = from[2..2 + name_len].trim_end_matches('-');
        if name.is_empty() {
            out.push_str("--");
            rest = &from[2..];
            continue;
        }
        let after = &from[2 + name.len()..];
        // A value the flag takes, when the next word is one of its known values.
        let next = after.strip_prefix(' ').map(|s| s.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == ':' || c == '_' || c == '-')).next().unwrap_or("").trim_end_matches(['.', '-']));
        let word = next.filter(|w| flag_value(name, w));
        let keyword = python_keyword(name);
        match (keyword, word) {
            (Some(k), Some(w)) if w.contains(':') => out.push_str(&format!("{k}=({})", w.replace(':', ", "))),
            (Some(k), Some(w)) if w.parse::<f64>().is_ok() => out.push_str(&format!("{k}={w}")),
            (Some(k), Some(w)) => out.push_str(&format!("{k}=\"{w}\"")),
            (Some(k), None) => out.push_str(&format!("{k}=…")),
            (None, _) => {
                out.push_str(&format!("--{name} (romdyn's command line)"));
                rest = after;
                continue;
            }
        }
        rest = match word {
            Some(w) => &after[1 + w.len()..],
            None => after,
        };
    }
    out.push_str(rest);
    out
}

/// The Python keyword of a command-line flag's setting, if the package has one.
fn python_keyword(flag: &str) -> Option<&'static str> {
    Setting::from_cli_flag(&format!("--{flag}")).map(Setting::python_name)
}

/// Whether `word` is a value `--flag` takes (so it is part of the advice, not prose): an
/// enumerated setting's names from its one table ([`super::names::value_names`]).
fn flag_value(flag: &str, word: &str) -> bool {
    let setting = Setting::from_cli_flag(&format!("--{flag}"));
    if let Some(names) = setting.and_then(super::names::value_names) {
        return names.contains(&word);
    }
    match flag {
        "count" | "dcoef" | "tolerance" | "points" | "fmin" | "fmax" | "load-steps" | "at" | "band" | "resolution" | "averages" | "time-step" | "sample-rate" | "prewarp" | "balanced" | "hankel-tol" | "minimal" => {
            !word.is_empty() && word.split(':').all(|p| p.parse::<f64>().is_ok())
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::{python_spelling, Setting};

    /// Every variant is in [`Setting::ALL`] once (the match below stops compiling when a
    /// variant is added without it), and no two settings share a flag.
    #[test]
    fn every_setting_is_listed_once() {
        let listed = |s: Setting| match s {
            Setting::ReferenceTime | Setting::StaticEquilibrium | Setting::LoadSteps | Setting::Inputs | Setting::Outputs | Setting::Imposed | Setting::RemoveSprings | Setting::Route | Setting::BelowBand | Setting::Dcoef | Setting::Solver | Setting::Tolerance | Setting::Count | Setting::Band | Setting::Modes | Setting::Residualize | Setting::ResidualizeModes | Setting::Ranking | Setting::Form | Setting::Fmin | Setting::Fmax | Setting::Points | Setting::BeamUpdate | Setting::Set | Setting::SampleRate | Setting::Discretize | Setting::Prewarp | Setting::Balanced | Setting::HankelTol | Setting::Spa | Setting::Minimal | Setting::Cut | Setting::Damping | Setting::Lowest | Setting::Signal | Setting::Amplitudes | Setting::ValidationBand | Setting::Resolution | Setting::Averages | Setting::TimeStep | Setting::Coherence | Setting::Fit | Setting::Measured => Setting::ALL.iter().filter(|t| **t == s).count(),
        };
        for s in Setting::ALL {
            assert_eq!(listed(s), 1, "{s:?}");
            assert_eq!(Setting::from_cli_flag(s.cli_flag()), Some(s), "{s:?}: its flag is another setting's");
            assert!(s.cli_flag().starts_with("--") && !s.python_name().contains('-'), "{s:?}");
        }
    }

    #[test]
    fn advice_is_spelled_as_python_takes_it() {
        assert_eq!(python_spelling("(--by dominance leaves them out)"), "(by=\"dominance\" leaves them out)");
        assert_eq!(python_spelling("give --dcoef near 1/|λ|"), "give dcoef=… near 1/|λ|");
        assert_eq!(python_spelling("--below-band keep keeps them, refuse stops"), "below_band=\"keep\" keeps them, refuse stops");
        assert_eq!(python_spelling("use --solver dense or --count 20"), "use solver=\"dense\" or count=20");
        assert_eq!(python_spelling("--band 0:30 gives"), "band=(0, 30) gives");
        assert_eq!(python_spelling("--residualize folds them into D"), "residualize=… folds them into D");
        assert_eq!(python_spelling("see --pencil"), "see --pencil (romdyn's command line)");
        assert_eq!(python_spelling("a -- b and x--"), "a -- b and x--");
        assert_eq!(python_spelling("(--beam-update path-independent silences this)"), "(beam_update=\"path-independent\" silences this)");
    }
}
