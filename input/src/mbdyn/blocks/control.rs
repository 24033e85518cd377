//! The `control data` block (input manual, "Control Data"): the model counters romdyn
//! checks against the model, as MBDyn does; the output settings romdyn honours (`default
//! output`, `output frequency`, `default orientation`); the settings of MBDyn's initial
//! assembly (`solve::initial_assembly`); MBDyn's numerics and the rest of its output,
//! accepted and ignored; and the statements that would change the physics,
//! which are errors. A statement given twice is read twice, the later value winning, as
//! MBDyn's reader does (dataman3.cc, `DataManager::ReadControl`, has no duplicate check).

use std::collections::HashMap;

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Sources, Span};
use crate::mbdyn::nodes::structural::orientation_kind;
use crate::mbdyn::syntax::parser::{known, Block};
use crate::model::{InitialAssembly, OrientationOutput};

/// Entity kinds counted in control data and found in the model.
pub const COUNTED: [&str; 17] = ["structural nodes", "abstract nodes", "electric nodes", "hydraulic nodes", "genels", "electric elements", "hydraulic elements", "parameter nodes", "rigid bodies", "joints", "joint regularizations", "forces", "beams", "plates", "gravity", "automatic structural elements", "file drivers"];

/// Counters of entities romdyn does not support: a non-zero count is an error.
const UNSUPPORTED_COUNTERS: [&str; 9] = [
    "thermal nodes", "aerodynamic elements", "aeromodals",
    "bulk elements", "electric bulk elements", "external elements",
    "loadable elements", "output elements", "induced velocity elements",
];

/// Settings of MBDyn's numerics and output: accepted, ignored.
const IGNORED: [&str; 15] = [
    // `inertia: N` counts the inertia cards, which only write output (elements.rs).
    "inertia", "use automatic differentiation", "title", "print", "make restart file", "select timeout", "output units",
    "output results", "default aerodynamic output", "default beam output", "default scale", "finite difference jacobian meter",
    "loadable path", "model name", "epsilon",
];

/// The initial assembly's statements (dataman3.cc, `DataManager::ReadControl`; input manual
/// §Assembly-Related Cards), into `a`. `use: …, in assembly` may name only beams (used by
/// default anyway): bodies, gravity and forces in the assembly are not supported, unless
/// the assembly is skipped (checked by the caller, which gets the statement back).
fn assembly_statement(keyword: &str, c: &mut Cursor, a: &mut InitialAssembly) -> Result<Option<String>, MbdynError> {
    match keyword {
        "skip initial joint assembly" => a.skip = true,
        "initial stiffness" => {
            a.position_stiffness = c.real("initial position stiffness")?;
            a.velocity_stiffness = if c.is_done() { a.position_stiffness } else { c.real("initial velocity stiffness")? };
        }
        "omega rotates" => a.omega_rotates = c.flag("omega rotates (yes or no)")?,
        "tolerance" | "initial tolerance" => {
            let span = c.here();
            a.tolerance = c.real("initial assembly tolerance")?;
            // dataman3.cc reads any real; its assembly (dataman2.cc, `InitialJointAssembly`)
            // passes when `sqrt(|F|²/(1 + |X|²)) <= tolerance`: with 0, only when the joints
            // hold exactly (romdyn's test is the same), with a negative one never.
            if !(a.tolerance >= 0.0) {
                return Err(c.error_at(span, format!("the initial assembly tolerance must not be negative, found {} (MBDyn 1.7.3 reads it, but its assembly test 'residual <= tolerance' can then never pass)", a.tolerance)));
            }
        }
        "max iterations" | "max initial iterations" => a.max_iterations = c.count("initial assembly max iterations")?,
        _ => {
            // `use: ITEM, …, in assembly`.
            let mut other = None;
            loop {
                if c.accept("in assembly") {
                    break;
                }
                let item = c.keyword("an element kind (or 'in assembly')", &["rigid bodies", "gravity", "forces", "beams", "aerodynamic elements", "loadable elements", "plates"])?;
                if item != "beams" && other.is_none() {
                    other = Some(item.to_string());
                }
            }
            return Ok(other);
        }
    }
    Ok(None)
}

/// What control data says about the motion file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlOutput {
    /// Whether structural nodes are written unless their card says otherwise.
    pub structural_nodes: bool,
    /// Output every this many steps.
    pub every: usize,
    pub orientation: OrientationOutput,
    /// `output precision: N`: digits after the decimal point in the `.mov` file.
    pub precision: Option<usize>,
    /// `default output: accelerations`: dynamic nodes write their accelerations unless
    /// their card says otherwise (dataman3.cc; `all` does not set it).
    pub accelerations: bool,
    /// Whether abstract, electric and hydraulic nodes are written unless their card says
    /// otherwise.
    pub scalar_nodes: [bool; 3],
    /// Whether hydraulic elements write their `.hyd` rows unless their card says otherwise.
    pub hydraulic_elements: bool,
}

/// Largest `output precision` romdyn writes (17 significant digits already identify a
/// double; this only bounds a file's request).
const MAX_OUTPUT_PRECISION: usize = 30;

impl Default for ControlOutput {
    fn default() -> Self {
        ControlOutput { structural_nodes: true, every: 1, orientation: OrientationOutput::Euler123Degrees, precision: None, accelerations: false, scalar_nodes: [true; 3], hydraulic_elements: true }
    }
}

/// `default output: {all | none | structural nodes | …} …` (dataman3.cc, case
/// DEFAULTOUTPUT): `all` and `none` set every kind, a kind's name switches it on; only the
/// nodes' (structural, abstract, electric, hydraulic) and the accelerations' flags matter
/// for romdyn's files.
fn default_output(c: &mut Cursor, out: &mut ControlOutput) -> Result<(), MbdynError> {
    const KINDS: [&str; 27] = [
        "all", "none", "reference frames", "accelerations", "drive callers", "structural nodes", "electric nodes", "thermal nodes", "abstract nodes",
        "hydraulic nodes", "gravity", "rigid bodies", "joints", "beams", "plates", "shells", "membranes", "aerodynamic elements", "forces", "genels",
        "electric elements", "hydraulic elements", "loadable", "induced velocity elements", "aeromodals", "external elements", "thermal elements",
    ];
    while !c.is_done() {
        match c.keyword("an output kind", &KINDS)? {
            "all" => {
                out.structural_nodes = true;
                out.scalar_nodes = [true; 3];
                out.hydraulic_elements = true;
            }
            "structural nodes" => out.structural_nodes = true,
            "abstract nodes" => out.scalar_nodes[0] = true,
            "electric nodes" => out.scalar_nodes[1] = true,
            "hydraulic nodes" => out.scalar_nodes[2] = true,
            "hydraulic elements" => out.hydraulic_elements = true,
            "accelerations" => out.accelerations = true,
            "none" => {
                out.structural_nodes = false;
                out.scalar_nodes = [false; 3];
                out.hydraulic_elements = false;
            }
            _ => {}
        }
    }
    Ok(())
}

/// Declared counts by kind, with the statement that declares them.
pub type Counts = HashMap<&'static str, (usize, Span)>;

/// Statements of the initial assembly.
const ASSEMBLY: [&str; 8] = ["skip initial joint assembly", "initial stiffness", "omega rotates", "tolerance", "initial tolerance", "max iterations", "max initial iterations", "use"];

/// Reads the `control data` block: the counts, the output settings and the initial
/// assembly's settings.
pub fn control_data(block: Option<&Block>, sources: &Sources) -> Result<(Counts, ControlOutput, InitialAssembly), MbdynError> {
    let mut counts = Counts::new();
    let mut output = ControlOutput::default();
    let mut assembly = InitialAssembly::default();
    let Some(cd) = block else { return Ok((counts, output, assembly)) };
    let mut used = None;
    for st in &cd.statements {
        let mut c = Cursor::new(st, sources);
        if let Some(k) = known(&st.keyword, &ASSEMBLY) {
            if let Some(item) = assembly_statement(k, &mut c, &mut assembly)? {
                used = Some((item, st.span));
            }
        } else if known(&st.keyword, &["default output"]).is_some() {
            default_output(&mut c, &mut output)?;
        } else if known(&st.keyword, &["output frequency"]).is_some() {
            let span = c.here();
            let n = c.count("output frequency (steps)")?;
            if n < 1 {
                return Err(c.error_at(span, "the output frequency must be at least 1 step"));
            }
            output.every = n;
        } else if known(&st.keyword, &["output precision"]).is_some() {
            let span = c.here();
            let n = c.count("output precision (digits)")?;
            if n > MAX_OUTPUT_PRECISION {
                return Err(c.error_at(span, format!("the output precision must be at most {MAX_OUTPUT_PRECISION} digits, found {n}")));
            }
            output.precision = Some(n);
        } else if known(&st.keyword, &["default orientation"]).is_some() {
            output.orientation = orientation_kind(&mut c)?;
        } else if let Some(kind) = known(&st.keyword, &COUNTED) {
            let n = if kind == "gravity" { 1 } else { c.count(&format!("number of {kind}"))? };
            counts.insert(kind, (n, st.span));
        } else if known(&st.keyword, &["air properties"]).is_some() {
            // dataman3.cc: `air properties;` takes no count (like `gravity`): one card.
            return Err(c.error_at(st.span, "control data declares air properties (aerodynamics), which romdyn does not support (MBDyn 1.7.3 runs them)"));
        } else if let Some(kind) = known(&st.keyword, &UNSUPPORTED_COUNTERS) {
            let span = c.here();
            if c.count(&format!("number of {kind}"))? > 0 {
                return Err(c.error_at(span, format!("control data declares {kind}, which romdyn does not support (MBDyn 1.7.3 runs them)")));
            }
        } else if known(&st.keyword, &IGNORED).is_some() {
            // MBDyn's assembly and output settings: romdyn uses its own.
            c.skip_rest();
        } else if known(&st.keyword, &["output meter"]).is_some() {
            // A drive caller, read with the cards (model.rs, `output_meter`).
            c.skip_rest();
        } else if known(&st.keyword, &["rigid body kinematics"]).is_some() {
            // Read with the drive callers (`super::rbk`, from `crate::mbdyn::model`).
            c.skip_rest();
        } else if known(&st.keyword, &["model"]).is_some() {
            // dataman3.cc: `model: static` makes every body a static body (on a static
            // node; see model.rs), nothing else.
            c.keyword("the model type", &["static"])?;
        } else {
            return Err(c.error_at(st.span, format!("statement '{}' in control data is not supported by romdyn", st.keyword)));
        }
        c.finish()?;
    }
    if let Some((item, span)) = used.filter(|_| !assembly.skip) {
        return Err(sources.error(span, format!("'use: {item}, in assembly' is not supported by romdyn (MBDyn 1.7.3 runs it): its initial assembly uses joints and beams only, as MBDyn's does by default")));
    }
    Ok((counts, output, assembly))
}
