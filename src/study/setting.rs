//! The settings of a study, named as each front end spells them: an error about a setting
//! carries the [`Setting`], and the CLI prints its flag (`--dcoef`), the Python package its
//! keyword (`dcoef`), so a Python user is not told about a flag they never wrote.

/// One setting of a study, a ROM request or a response grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The reference time (`--at`, `reference=`).
    ReferenceTime,
    LoadSteps,
    Inputs,
    Outputs,
    Imposed,
    /// The eigenanalysis route (`--route`, `route=`).
    Route,
    Dcoef,
    Solver,
    Tolerance,
    /// The number of modes a ROM keeps or the sparse route computes (`--count`, `count=`).
    Count,
    /// A band of natural frequencies [Hz] (`--band FMIN:FMAX`, `band=(FMIN, FMAX)`).
    Band,
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
}

impl Setting {
    /// Every setting.
    pub const ALL: [Setting; 27] = [
        Setting::Route,
        Setting::BelowBand,
        Setting::Count,
        Setting::Band,
        Setting::ReferenceTime,
        Setting::LoadSteps,
        Setting::Inputs,
        Setting::Outputs,
        Setting::Imposed,
        Setting::Dcoef,
        Setting::Solver,
        Setting::Tolerance,
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
    ];

    /// The command line's flag.
    pub fn cli_flag(self) -> &'static str {
        match self {
            Setting::ReferenceTime => "--at",
            Setting::LoadSteps => "--load-steps",
            Setting::Inputs => "--input",
            Setting::Outputs => "--output",
            Setting::Imposed => "--imposed",
            Setting::Route => "--route",
            Setting::BelowBand => "--below-band",
            Setting::Dcoef => "--dcoef",
            Setting::Solver => "--solver",
            Setting::Tolerance => "--tolerance",
            Setting::Count => "--count",
            Setting::Band => "--band",
            Setting::Ranking => "--by",
            Setting::Form => "--form",
            Setting::Fmin => "--fmin",
            Setting::Fmax => "--fmax",
            Setting::Points => "--points",
            Setting::BeamUpdate => "--beam-update",
            Setting::Set => "--set",
            Setting::SampleRate => "--sample-rate",
            Setting::Discretize => "--discretize",
            Setting::Prewarp => "--prewarp",
            Setting::Balanced => "--balanced",
            Setting::HankelTol => "--hankel-tol",
            Setting::Spa => "--spa",
            Setting::Minimal => "--minimal",
            Setting::Cut => "--cut",
        }
    }

    /// The Python package's keyword argument.
    pub fn python_name(self) -> &'static str {
        match self {
            Setting::ReferenceTime => "reference",
            Setting::LoadSteps => "load_steps",
            Setting::Inputs => "inputs",
            Setting::Outputs => "outputs",
            Setting::Imposed => "imposed",
            Setting::Route => "route",
            Setting::BelowBand => "below_band",
            Setting::Dcoef => "dcoef",
            Setting::Solver => "solver",
            Setting::Tolerance => "tolerance",
            Setting::Count => "count",
            Setting::Band => "band",
            Setting::Ranking => "by",
            Setting::Form => "form",
            Setting::Fmin => "fmin",
            Setting::Fmax => "fmax",
            Setting::Points => "points",
            Setting::BeamUpdate => "beam_update",
            Setting::Set => "set",
            Setting::SampleRate => "sample_rate",
            Setting::Discretize => "discretize",
            Setting::Prewarp => "prewarp",
            Setting::Balanced => "balanced",
            Setting::HankelTol => "hankel_tol",
            Setting::Spa => "spa",
            Setting::Minimal => "minimal",
            Setting::Cut => "cut",
        }
    }
}

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

/// The Python keyword of a command-line flag's setting, if the package has one: the study's
/// settings by [`Setting`]'s own two spellings, the ROM request's and `validate`'s here.
fn python_keyword(flag: &str) -> Option<&'static str> {
    if let Some(s) = Setting::ALL.iter().find(|s| s.cli_flag().strip_prefix("--") == Some(flag)) {
        return Some(s.python_name());
    }
    Some(match flag {
        "static" => "reference",
        "remove-spring" => "remove_springs",
        "modes" => "modes",
        "residualize" | "residualize-modes" => "residualize",
        "amplitudes" => "amplitudes",
        "validation-band" => "validation_band",
        "resolution" => "resolution",
        "averages" => "averages",
        "time-step" => "time_step",
        "measured" => "measured",
        _ => return None,
    })
}

/// Whether `word` is a value `--flag` takes (so it is part of the advice, not prose): an
/// enumerated setting's names from its one table ([`super::names::value_names`]).
fn flag_value(flag: &str, word: &str) -> bool {
    let setting = Setting::ALL.iter().find(|s| s.cli_flag().strip_prefix("--") == Some(flag));
    if let Some(names) = setting.and_then(|s| super::names::value_names(*s)) {
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
    use super::python_spelling;

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
