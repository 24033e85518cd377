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
    Dcoef,
    Solver,
    Tolerance,
    /// How a `count` ranks the modes (`--by`, `by=`).
    Ranking,
    Form,
    Fmin,
    Fmax,
    Points,
    BeamUpdate,
    /// A `set:` variable of the file given another value (`--set NAME=VALUE`, `set={…}`).
    Set,
}

impl Setting {
    /// The command line's flag.
    pub fn cli_flag(self) -> &'static str {
        match self {
            Setting::ReferenceTime => "--at",
            Setting::LoadSteps => "--load-steps",
            Setting::Inputs => "--input",
            Setting::Outputs => "--output",
            Setting::Imposed => "--imposed",
            Setting::Dcoef => "--dcoef",
            Setting::Solver => "--solver",
            Setting::Tolerance => "--tolerance",
            Setting::Ranking => "--by",
            Setting::Form => "--form",
            Setting::Fmin => "--fmin",
            Setting::Fmax => "--fmax",
            Setting::Points => "--points",
            Setting::BeamUpdate => "--beam-update",
            Setting::Set => "--set",
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
            Setting::Dcoef => "dcoef",
            Setting::Solver => "solver",
            Setting::Tolerance => "tolerance",
            Setting::Ranking => "by",
            Setting::Form => "form",
            Setting::Fmin => "fmin",
            Setting::Fmax => "fmax",
            Setting::Points => "points",
            Setting::BeamUpdate => "beam_update",
            Setting::Set => "set",
        }
    }
}

/// The command line's spelling, as the library's messages print it.
impl std::fmt::Display for Setting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.cli_flag())
    }
}
