//! `joint: LABEL, modal, …` (input manual §Modal; modal.cc, `ReadModal`, MBDyn 1.7.3):
//!
//! ```text
//! modal, {MODAL_NODE | clamped [, position, X] [, orientation, R]}, MODES [, list, M, …]
//!     [, initial value, …], {FEM_NODES | from file}
//!     [, {no damping | damping from file | rayleigh damping, A, B
//!        | single factor damping, Z | proportional damping, Z
//!        | diag damping, {all, Z, … | COUNT, MODE, Z, …}}]
//!     , "FEM_FILE" [, [mass | damping | stiffness] threshold, T]…
//!     [, create binary | use binary | update binary]… [, echo, "FILE" [, precision, N]]
//!     [, {origin node, "FEM_LABEL" | origin position, X}]
//!     , INTERFACES [, output, FLAG] {, "FEM_LABEL", NODE, OFFSET [, output, FLAG]}…
//!     [, use invariant 9] [, "LEGACY_OUTPUT_FILE"]
//! ```
//!
//! (`use invariant 9` where MBDyn 1.7.3's reader takes it, after the interface nodes; its
//! manual shows it before `origin node`.)
//!
//! mapped onto [`ModalBody`]; the FEM file is read by [`crate::fem`]. Without
//! a damping keyword MBDyn uses record 13 when the file has it (`damping from file`).

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use super::context::ElementContext;
use crate::element::modal::{Component, Invariants};
use crate::element::{FemNode, ModalBody, ModalFrame, ModalInterface};
use crate::fem::FemFile;
use crate::kinematics::{Mat3, Vec3};
use crate::model::Label;
use nalgebra::DMatrix;
use crate::mbdyn::drives::file_drivers;

/// How the modal damping matrix is made.
enum Damping {
    FromFile,
    None,
    Rayleigh(f64, f64),
    /// Damping ratios per active mode: `cᵢᵢ = 2 ζᵢ √(kᵢᵢ mᵢᵢ)`.
    Ratios(Vec<f64>),
}

pub fn modal(label: Label, c: &mut Cursor, ctx: &ElementContext) -> Result<ModalBody, MbdynError> {
    let frame = if c.accept("clamped") {
        let g = ctx.global();
        let position = if c.accept("position") { g.position(c, "position of the clamped FEM frame [m]")? } else { Vec3::zeros() };
        let orientation = if c.accept("orientation") { g.orientation(c, "orientation of the clamped FEM frame")? } else { Mat3::identity() };
        (ModalFrame::Clamped { position, orientation }, position, orientation)
    } else {
        let span = c.here();
        let n = ctx.node(c, "modal node")?;
        if !ctx.nodes.find(n.label).is_some_and(|e| e.modal) {
            return Err(c.error_at(span, format!("structural node {} is not a 'modal' node: a modal joint's reference node must be declared 'structural: {}, modal, …' (or write 'clamped')", n.label, n.label)));
        }
        (ModalFrame::Node(n.label), n.position, n.orientation)
    };
    let (frame, _, _) = frame;
    let modes_span = c.here();
    let modes = c.count("number of modes")?;
    if modes == 0 {
        return Err(c.error_at(modes_span, "a modal joint needs at least one mode"));
    }
    let mut numbers: Vec<usize> = (1..=modes).collect();
    if c.accept("list") {
        for k in 0..modes {
            let span = c.here();
            let m = c.count("mode number (1-based, in the FEM file)")?;
            if m == 0 || numbers[..k].contains(&m) {
                return Err(c.error_at(span, format!("mode number {m}: expected a mode of the FEM file, from 1, each listed once")));
            }
            numbers[k] = m;
        }
    }
    // `initial value, mode, J, Q, QP, …` or one pair per mode (MBDyn 1.7.3 stores every
    // pair of the second form in mode 1, a slip of modal.cc; romdyn gives each its mode,
    // as the input manual says).
    let mut initial: Vec<Option<(f64, f64)>> = vec![None; modes];
    if c.accept("initial value") {
        // Given, it replaces the FEM file's records 3 and 4 for every mode (modal.cc).
        initial = vec![Some((0.0, 0.0)); modes];
        if c.accept("mode") {
            loop {
                let span = c.here();
                let m = c.count("mode number")?;
                let Some(k) = numbers.iter().position(|x| *x == m) else {
                    return Err(c.error_at(span, format!("initial value: mode {m} is not one of the active modes {numbers:?}")));
                };
                initial[k] = Some((c.real("initial modal coordinate")?, c.real("initial modal velocity [1/s]")?));
                if !c.accept("mode") {
                    break;
                }
            }
        } else {
            for v in initial.iter_mut() {
                *v = Some((c.real("initial modal coordinate")?, c.real("initial modal velocity [1/s]")?));
            }
        }
    }
    let nodes_span = c.here();
    let fem_nodes = if c.accept("from file") { None } else { Some(c.count("number of FEM nodes")?) };
    let damping = damping(c, modes)?;
    let file_span = c.here();
    let name = c.string("FEM file name")?;
    let path = file_drivers::data_path(c, file_span, &name);
    let fem = crate::fem::read_fem(&path).map_err(|e| c.error_at(file_span, format!("modal joint {label}: the FEM file cannot be used: {e}")))?;
    if let Some(n) = fem_nodes.filter(|n| *n != fem.nodes()) {
        return Err(c.error_at(nodes_span, format!("modal joint {label}: {n} FEM nodes given, the FEM file '{}' has {} (write 'from file' to take its count)", path.display(), fem.nodes())));
    }
    if let Some(&m) = numbers.iter().find(|m| **m > fem.modes()) {
        return Err(c.error_at(modes_span, format!("modal joint {label}: mode {m} asked for, the FEM file '{}' has {} modes", path.display(), fem.modes())));
    }
    let mut thresholds = [0.0; 3]; // mass, damping, stiffness
    loop {
        let which = match c.accept_any(&["threshold", "mass threshold", "damping threshold", "stiffness threshold"]) {
            Some("threshold") => vec![0, 1, 2],
            Some("mass threshold") => vec![0],
            Some("damping threshold") => vec![1],
            Some(_) => vec![2],
            None => break,
        };
        let span = c.here();
        let t = c.real("threshold")?;
        if t < 0.0 {
            return Err(c.error_at(span, format!("invalid threshold {t}: expected a non-negative number")));
        }
        for w in which {
            thresholds[w] = t;
        }
    }
    // romdyn reads the text file every time: the binary cache options change nothing.
    while c.accept_any(&["create binary", "use binary", "update binary"]).is_some() {}
    // `echo, "FILE" [, precision, N]` writes the FEM data back out in MBDyn; romdyn reads
    // it and writes nothing (the data are the FEM file's).
    if c.accept("echo") {
        c.string("echo file name")?;
        if c.accept("precision") {
            c.count("echo precision (digits)")?;
        }
    }
    if c.peek_keyword() == Some("use invariant 9") {
        return Err(c.error("'use invariant 9' comes after the interface nodes: MBDyn 1.7.3 reads it there (modal.cc, after the FEM data, when record 11 gives the lumped masses), not where its input manual shows it"));
    }
    let mut origin = Vec3::zeros();
    if c.accept("origin node") {
        let span = c.here();
        let l = fem_label(c)?;
        let Some(i) = fem.node_labels.iter().position(|x| *x == l) else {
            return Err(c.error_at(span, format!("origin node: FEM node \"{l}\" is not in the FEM file '{}'", path.display())));
        };
        origin = Vec3::from(fem.positions[i]);
    } else if c.accept("origin position") {
        origin = ctx.global().position(c, "origin position in the FEM frame [m]")?;
    }
    let selected = |m: &faer::Mat<f64>, threshold: f64| DMatrix::from_fn(modes, modes, |j, k| Some(m[(numbers[j] - 1, numbers[k] - 1)]).filter(|x| x.abs() >= threshold).unwrap_or(0.0));
    let mass = selected(&fem.mass, thresholds[0]);
    let stiffness = selected(&fem.stiffness, thresholds[2]);
    let damping = match damping {
        Damping::FromFile => fem.damping.as_ref().map_or_else(|| DMatrix::zeros(modes, modes), |d| selected(d, thresholds[1])),
        Damping::None => DMatrix::zeros(modes, modes),
        Damping::Rayleigh(a, b) => a * &mass + b * &stiffness,
        Damping::Ratios(z) => DMatrix::from_fn(modes, modes, |j, k| if j == k { 2.0 * z[j] * (stiffness[(j, j)] * mass[(j, j)]).sqrt() } else { 0.0 }),
    };
    let mut component = component(&fem, &numbers, origin);
    let interfaces = interfaces(c, ctx, &fem, &component, &path)?;
    if let Some(k) = c.peek_keyword().filter(|k| *k == "use invariant 9") {
        if fem.lumped_inertia.is_none() {
            return Err(c.error(format!("'{k}': the FEM file '{}' has no lumped masses (record 11), so there are no invariants to use; MBDyn 1.7.3 does not read the keyword then either", path.display())));
        }
        c.accept(k);
        component.invariant_9 = true;
    }
    // A string here is the per-element output file of MBDyn before 1.2.7, which 1.7.3
    // reads and ignores (its output goes to the `.mod` file).
    if c.next_is_string() {
        c.string("legacy output file name")?;
    }
    // The FEM file's records 3 and 4, unless `initial value` was given.
    let initial = initial.iter().zip(&numbers).map(|(v, m)| v.unwrap_or((fem.modal_displacements[m - 1], fem.modal_velocities[m - 1]))).collect();
    let mut body = ModalBody::new(label, frame, mass, stiffness, damping, Invariants::of(&component), interfaces, numbers, initial);
    body.input_warnings = fem.warnings.clone();
    body.fem_nodes = fem.node_labels.iter().enumerate().map(|(i, l)| FemNode { label: l.clone(), position: component.positions[i], translation: component.translations.iter().map(|t| t[i]).collect(), rotation: component.rotations.iter().map(|t| t[i]).collect() }).collect();
    Ok(body)
}

/// A FEM node label: a string, or (MBDyn's legacy form) an integer.
fn fem_label(c: &mut Cursor) -> Result<String, MbdynError> {
    if !c.next_is_string() {
        return Ok(c.integer("FEM node label")?.to_string());
    }
    c.string("FEM node label (a string in double quotes, or an integer)")
}

fn damping(c: &mut Cursor, modes: usize) -> Result<Damping, MbdynError> {
    Ok(match c.accept_any(&["no damping", "damping from file", "rayleigh damping", "single factor damping", "proportional damping", "diag damping"]) {
        None | Some("damping from file") => Damping::FromFile,
        Some("no damping") => Damping::None,
        Some("rayleigh damping") => Damping::Rayleigh(c.real("mass damping coefficient [1/s]")?, c.real("stiffness damping coefficient [s]")?),
        Some("single factor damping" | "proportional damping") => Damping::Ratios(vec![c.real("damping factor")?; modes]),
        Some(_) => {
            let mut z = vec![0.0; modes];
            if c.accept("all") {
                for zk in z.iter_mut() {
                    *zk = c.real("damping factor")?;
                }
            } else {
                let span = c.here();
                let count = c.count("number of damped modes")?;
                if count == 0 || count > modes {
                    return Err(c.error_at(span, format!("invalid number of damped modes {count}: expected 1 to {modes}")));
                }
                let mut seen = vec![false; modes];
                for _ in 0..count {
                    let span = c.here();
                    let m = c.count("damped mode index (1 to the number of modes)")?;
                    if m == 0 || m > modes || seen[m - 1] {
                        return Err(c.error_at(span, format!("damped mode index {m}: expected an active mode's index from 1 to {modes}, each given once")));
                    }
                    seen[m - 1] = true;
                    z[m - 1] = c.real("damping factor")?;
                }
            }
            Damping::Ratios(z)
        }
    })
}

/// The FEM data of the active modes in the floating frame (origin at `origin`).
fn component(fem: &FemFile, numbers: &[usize], origin: Vec3) -> Component {
    let positions: Vec<Vec3> = fem.positions.iter().map(|p| Vec3::from(*p) - origin).collect();
    let shape = |range: std::ops::Range<usize>| numbers.iter().map(|m| fem.shapes[m - 1].iter().map(|s| Vec3::new(s[range.start], s[range.start + 1], s[range.start + 2])).collect()).collect();
    let lumped = fem.lumped_inertia.as_ref().map(|l| l.iter().map(|m| (m[0], Vec3::new(m[3], m[4], m[5]))).collect());
    let rigid = fem.rigid_inertia.as_ref().map(|r| {
        let i = r.inertia;
        (r.mass, Vec3::from(r.centre_of_mass) - origin, Mat3::new(i[0][0], i[0][1], i[0][2], i[1][0], i[1][1], i[1][2], i[2][0], i[2][1], i[2][2]))
    });
    Component { positions, translations: shape(0..3), rotations: shape(3..6), lumped, rigid, invariant_9: false }
}

fn interfaces(c: &mut Cursor, ctx: &ElementContext, fem: &FemFile, comp: &Component, path: &std::path::Path) -> Result<Vec<ModalInterface>, MbdynError> {
    let count = c.count("number of interface nodes")?;
    if c.accept("output") {
        c.flag("output of the interface nodes")?;
    }
    let mut out = Vec::with_capacity(count.min(fem.nodes()));
    for _ in 0..count {
        let span = c.here();
        let l = fem_label(c)?;
        let Some(i) = fem.node_labels.iter().position(|x| *x == l) else {
            return Err(c.error_at(span, format!("interface node: FEM node \"{l}\" is not in the FEM file '{}'", path.display())));
        };
        let node = ctx.node(c, "multibody node of the interface")?;
        let offset = ctx.on(node).relative_position(c, "offset of the FEM node from the multibody node [m]")?;
        if c.accept_any(&["hinge", "orientation"]).is_some() {
            let span = c.here();
            let r = ctx.on(node).relative_orientation(c, "orientation of the interface")?;
            if (r - Mat3::identity()).abs().max() > 0.0 {
                return Err(c.error_at(span, "an interface orientation other than the identity: MBDyn 1.7.3 reads it but does not use it (modal.cc: 'FIXME: not used'), so romdyn refuses it rather than guess; orient the multibody node as the FEM frame"));
            }
        }
        if c.accept("output") {
            c.flag("output of the interface node")?;
        }
        out.push(ModalInterface { node: node.label, fem_node: l, position: comp.positions[i], translation: comp.translations.iter().map(|m| m[i]).collect(), rotation: comp.rotations.iter().map(|m| m[i]).collect(), offset });
    }
    Ok(out)
}
