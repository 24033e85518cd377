//! From a parsed document to a [`Model`] and the analysis it asks for: the `data`,
//! `initial value`, `control data`, `nodes` and `elements` blocks.

use std::collections::HashMap;
use std::path::Path;

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Span};
use super::elements::{element, Parsed};
use super::parser::{parse_file, Block, Document};
use crate::model::{AbortAfter, EigenOutput, EigenRequest, InitialValueProblem, Method, Model, ModelBuilder, NodeKind, StructuralNode};

/// A model file: the model and the initial-value problem it asks for.
pub struct MbdynModel {
    pub model: Model,
    pub problem: InitialValueProblem,
}

/// Reads an MBDyn input file into a model.
pub fn read_model(path: &Path) -> Result<MbdynModel, MbdynError> {
    build(&parse_file(path)?)
}

fn block<'d>(doc: &'d Document, name: &str) -> Option<&'d Block> {
    doc.blocks.iter().find(|b| b.name == name)
}

/// Builds the model from a parsed document.
pub fn build(doc: &Document) -> Result<MbdynModel, MbdynError> {
    let src = &doc.sources;
    let first = doc.blocks.first().map_or(Span::default(), |b| b.span);
    for b in &doc.blocks {
        if !["data", "initial value", "control data", "nodes", "elements"].contains(&b.name.as_str()) {
            return Err(src.error(b.span, format!("block '{}' is not supported by romdyn", b.name)));
        }
    }
    let data = block(doc, "data").ok_or_else(|| src.error(first, "missing 'begin: data;' block"))?;
    for st in &data.statements {
        let mut c = Cursor::new(st, src);
        match st.keyword.as_str() {
            "problem" => {
                c.word("the problem", &["initial value"])?;
                c.finish()?;
            }
            other => return Err(src.error(st.span, format!("statement '{other}' in the data block is not supported by romdyn"))),
        }
    }
    let problem = initial_value(doc)?;
    let counts = control_data(doc)?;
    let nodes = nodes(doc)?;
    let mut b = ModelBuilder::new();
    for n in &nodes {
        b.node(n.clone());
    }
    let mut found: HashMap<&str, (usize, Span)> = HashMap::new();
    let mut labels: HashMap<(String, u32), Span> = HashMap::new();
    if let Some(els) = block(doc, "elements") {
        for st in &els.statements {
            let mut c = Cursor::new(st, src);
            let parsed = element(&st.keyword, &mut c, &nodes)?;
            c.finish()?;
            match parsed {
                Parsed::Gravity(g) => {
                    b.gravity(g);
                    found.entry("gravity").or_insert((0, st.span)).0 += 1;
                }
                Parsed::Element(e) => {
                    let kind = match st.keyword.as_str() {
                        "body" => "rigid bodies",
                        "joint" => "joints",
                        _ => "forces",
                    };
                    if let Some(prev) = labels.insert((st.keyword.clone(), e.label()), st.span) {
                        return Err(src.error(st.span, format!("{} {} is defined twice (first at line {})", st.keyword, e.label(), prev.line)));
                    }
                    found.entry(kind).or_insert((0, st.span)).0 += 1;
                    b.boxed_element(e);
                }
            }
        }
    }
    found.insert("structural nodes", (nodes.len(), block(doc, "nodes").map_or(first, |b| b.span)));
    for (kind, (declared, span)) in &counts {
        let have = found.get(kind.as_str()).map_or(0, |x| x.0);
        if have != *declared {
            return Err(src.error(*span, format!("control data declares {declared} {kind}, the model has {have}")));
        }
    }
    for (kind, (have, span)) in &found {
        if *have > 0 && !counts.contains_key(*kind) {
            return Err(src.error(*span, format!("the model has {have} {kind}, but control data does not declare '{kind}'")));
        }
    }
    let model = b.build().map_err(|e| src.error(first, e.to_string()))?;
    Ok(MbdynModel { model, problem })
}

fn initial_value(doc: &Document) -> Result<InitialValueProblem, MbdynError> {
    let src = &doc.sources;
    let mut a = InitialValueProblem::default();
    let Some(iv) = block(doc, "initial value") else { return Ok(a) };
    for st in &iv.statements {
        let mut c = Cursor::new(st, src);
        match st.keyword.as_str() {
            "initial time" => a.initial_time = c.real("initial time [s]")?,
            "final time" => a.final_time = c.real("final time [s]")?,
            "time step" => a.time_step = c.real("time step [s]")?,
            "tolerance" => a.tolerance = c.real("residual tolerance")?,
            "max iterations" => a.max_iterations = c.label("maximum number of iterations")? as usize,
            "method" => a.method = method(&mut c)?,
            "eigenanalysis" => a.eigenanalysis = Some(eigenanalysis(&mut c)?),
            "derivatives tolerance" => a.derivatives_tolerance = c.real("derivatives tolerance")?,
            "derivatives max iterations" => a.derivatives_max_iterations = c.label("derivatives max iterations")? as usize,
            "abort after" => {
                a.abort_after = Some(match c.word("where to stop", &["input", "assembly", "derivatives", "dummy steps"])?.as_str() {
                    "input" => AbortAfter::Input,
                    "assembly" => AbortAfter::Assembly,
                    "derivatives" => AbortAfter::Derivatives,
                    _ => AbortAfter::DummySteps,
                })
            }
            "derivatives coefficient" | "linear solver" | "threads" | "output" => {
                // Accepted; romdyn's own settings apply (documented in the manual page).
                while !c.is_done() {
                    if c.peek_word().is_some() {
                        c.word("", &[])?;
                    } else {
                        c.real("value")?;
                    }
                }
            }
            other => return Err(src.error(st.span, format!("statement '{other}' in the initial value block is not supported by romdyn"))),
        }
        c.finish()?;
    }
    Ok(a)
}

fn method(c: &mut Cursor) -> Result<Method, MbdynError> {
    let m = c.word("an integration method", &["ms", "crank nicolson", "implicit euler", "bdf"])?;
    Ok(match m.as_str() {
        "ms" => {
            let rho = c.real("asymptotic spectral radius rho")?;
            if !c.is_done() {
                c.real("algebraic spectral radius")?;
            }
            Method::Ms { rho }
        }
        "crank nicolson" => Method::CrankNicolson,
        "implicit euler" => Method::ImplicitEuler,
        _ => Method::Ms { rho: 0.0 },
    })
}

fn eigenanalysis(c: &mut Cursor) -> Result<EigenRequest, MbdynError> {
    let times = if c.accept("list") {
        let n = c.label("number of eigenanalysis times")?;
        (0..n).map(|_| c.real("eigenanalysis time [s]")).collect::<Result<_, _>>()?
    } else {
        vec![c.real("eigenanalysis time [s] (or list)")?]
    };
    let mut r = EigenRequest { times, dcoef: None, lower_frequency_hz: None, upper_frequency_hz: None, output: EigenOutput::default() };
    let options = ["output matrices", "output full matrices", "output sparse matrices", "output eigenvectors", "output geometry", "use lapack", "use arpack", "use jdqz", "parameter", "lower frequency limit", "upper frequency limit"];
    while !c.is_done() {
        let w = c.word("an eigenanalysis option", &options)?;
        match w.as_str() {
            "output matrices" | "output full matrices" => r.output.full_matrices = true,
            "output sparse matrices" => r.output.sparse_matrices = true,
            "output eigenvectors" => r.output.eigenvectors = true,
            "output geometry" => r.output.geometry = true,
            "parameter" => r.dcoef = Some(c.real("parameter (dCoef) [s]")?),
            "lower frequency limit" => r.lower_frequency_hz = Some(c.real("lower frequency limit [Hz]")?),
            "upper frequency limit" => r.upper_frequency_hz = Some(c.real("upper frequency limit [Hz]")?),
            _ => {}
        }
    }
    Ok(r)
}

/// Declared counts: kind → (count, span).
fn control_data(doc: &Document) -> Result<HashMap<String, (usize, Span)>, MbdynError> {
    let src = &doc.sources;
    let mut counts = HashMap::new();
    let Some(cd) = block(doc, "control data") else { return Ok(counts) };
    for st in &cd.statements {
        let mut c = Cursor::new(st, src);
        match st.keyword.as_str() {
            "structural nodes" | "rigid bodies" | "joints" | "forces" => {
                counts.insert(st.keyword.clone(), (c.label(&format!("number of {}", st.keyword))? as usize, st.span));
            }
            "gravity" => {
                counts.insert("gravity".into(), (1, st.span));
            }
            "beams" | "aerodynamic elements" | "electric nodes" | "abstract nodes" | "hydraulic nodes" | "genels" => {
                if c.label("count")? > 0 {
                    return Err(src.error(st.span, format!("{} are not supported by romdyn", st.keyword)));
                }
            }
            "default output" | "output frequency" | "print" | "output results" | "default orientation" | "max iterations" | "tolerance" => {
                while !c.is_done() {
                    if c.peek_word().is_some() {
                        c.word("", &[])?;
                    } else {
                        c.real("value")?;
                    }
                }
            }
            other => return Err(src.error(st.span, format!("statement '{other}' in control data is not supported by romdyn"))),
        }
        c.finish()?;
    }
    Ok(counts)
}

fn nodes(doc: &Document) -> Result<Vec<StructuralNode>, MbdynError> {
    let src = &doc.sources;
    let mut out: Vec<StructuralNode> = Vec::new();
    let Some(nb) = block(doc, "nodes") else { return Ok(out) };
    for st in &nb.statements {
        if st.keyword != "structural" {
            return Err(src.error(st.span, format!("node type '{}' is not supported by romdyn", st.keyword)));
        }
        let mut c = Cursor::new(st, src);
        let n = structural(&mut c)?;
        if out.iter().any(|p| p.label == n.label) {
            return Err(src.error(st.span, format!("structural node {} is defined twice", n.label)));
        }
        out.push(n);
    }
    Ok(out)
}

fn structural(c: &mut Cursor) -> Result<StructuralNode, MbdynError> {
    let label = c.label("node label")?;
    let kind = match c.word("the node type", &["static", "dynamic"])?.as_str() {
        "static" => NodeKind::Static,
        _ => NodeKind::Dynamic,
    };
    let position = c.vec3("position [m]")?;
    let orientation = c.orientation("orientation")?;
    let velocity = c.vec3("velocity [m/s]")?;
    let angular_velocity = c.vec3("angular velocity [rad/s]")?;
    c.finish()?;
    Ok(StructuralNode { label, kind, position, orientation, velocity, angular_velocity })
}
