//! The `control data` block (input manual, "Control Data"): the model counters romdyn
//! checks against the model, as MBDyn does; settings of MBDyn's initial assembly and
//! output, accepted and ignored (romdyn assembles nothing: the initial configuration is
//! taken as given); and the statements that would change the physics, which are errors.

use std::collections::HashMap;

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Sources, Span};
use super::parser::{known, Block};

/// Entity kinds counted in control data and found in the model.
pub const COUNTED: [&str; 7] = ["structural nodes", "rigid bodies", "joints", "forces", "beams", "gravity", "automatic structural elements"];

/// Counters of entities romdyn does not support: a non-zero count is an error.
const UNSUPPORTED_COUNTERS: [&str; 18] = [
    "abstract nodes", "electric nodes", "hydraulic nodes", "parameter nodes", "thermal nodes", "file drivers", "aerodynamic elements", "aeromodals",
    "air properties", "bulk elements", "electric bulk elements", "electric elements", "external elements", "genels", "hydraulic elements",
    "loadable elements", "output elements", "induced velocity elements",
];

/// Settings of MBDyn's initial assembly and output: accepted, ignored.
const IGNORED: [&str; 24] = [
    "skip initial joint assembly", "use", "initial stiffness", "omega rotates", "tolerance", "initial tolerance", "max iterations",
    "max initial iterations", "title", "print", "make restart file", "select timeout", "default output", "output units", "output frequency",
    "output meter", "output precision", "output results", "default orientation", "default aerodynamic output", "default beam output",
    "default scale", "finite difference jacobian meter", "loadable path",
];

/// Declared counts by kind, with the statement that declares them.
pub type Counts = HashMap<&'static str, (usize, Span)>;

/// Reads the `control data` block.
pub fn control_data(block: Option<&Block>, sources: &Sources) -> Result<Counts, MbdynError> {
    let mut counts = Counts::new();
    let Some(cd) = block else { return Ok(counts) };
    let mut seen: HashMap<String, Span> = HashMap::new();
    for st in &cd.statements {
        let mut c = Cursor::new(st, sources);
        if let Some(prev) = seen.insert(st.keyword.replace(' ', ""), st.span) {
            return Err(c.error_at(st.span, format!("'{}' appears twice in control data (first at line {})", st.keyword, prev.line)));
        }
        if let Some(kind) = known(&st.keyword, &COUNTED) {
            let n = if kind == "gravity" { 1 } else { c.count(&format!("number of {kind}"))? };
            counts.insert(kind, (n, st.span));
        } else if let Some(kind) = known(&st.keyword, &UNSUPPORTED_COUNTERS) {
            let span = c.here();
            if c.count(&format!("number of {kind}"))? > 0 {
                return Err(c.error_at(span, format!("control data declares {kind}, which romdyn does not support")));
            }
        } else if known(&st.keyword, &IGNORED).is_some() {
            // MBDyn's assembly and output settings: romdyn uses its own.
            c.skip_rest();
        } else if let Some(kind) = known(&st.keyword, &["model", "rigid body kinematics"]) {
            let what = if kind == "model" { "'model: static' (dynamic nodes treated as static)" } else { "'rigid body kinematics' (a moving reference frame)" };
            return Err(c.error_at(st.span, format!("{what} changes the physics and is not supported by romdyn")));
        } else {
            return Err(c.error_at(st.span, format!("statement '{}' in control data is not supported by romdyn", st.keyword)));
        }
        c.finish()?;
    }
    Ok(counts)
}
