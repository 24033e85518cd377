//! Constitutive laws (input manual, "General", §Constitutive Laws) that romdyn's elements
//! honour: `linear elastic [isotropic]`, `linear elastic generic`, `linear viscous
//! [isotropic]`, `linear viscous generic`, `linear viscoelastic [isotropic]`, `linear
//! viscoelastic generic` (viscosity or `proportional, FACTOR`), `linear time variant
//! viscoelastic generic` (the same matrices, each times a drive caller's value), with the optional
//! `prestress` and `prestrain` (constant; a drive on a rod); `reference, LABEL` to a
//! `constitutive law:` card.
//! Laws are read for 1 (rod), 3 (deformable displacement joint and hinge) or 6 (beams)
//! dimensions. The nonlinear laws `nlsf elastic`, `nlsf viscous` and `nlsf viscoelastic`
//! (constltp_nlsf.cc: `f_i = Σ_j k_ij (ε_j − ε_p,j) + f′_i(ε_i − ε_p,i) + Σ_j c_ij ε̇_j +
//! f″_i(ε̇_i) + f_p,i`, each scalar function or `null`) and `scalar function elastic
//! [isotropic | orthotropic]` (ScalarFunctionsImpl.cc: `f_i = F_i(ε_i)`, no prestrain or
//! prestress) are read in every dimension; [`nonlinear_law`] and [`axial_law`] take them
//! (deformable displacement joint, deformable hinge, deformable joint, beams; deformable
//! axial joint), [`linear_law`] refuses them by name. The time-variant law goes wherever
//! the nonlinear ones go and on the invariant deformable hinge
//! ([`linear_or_time_variant_law`]); [`linear_law`] refuses it.

use std::collections::HashMap;

use nalgebra::{DMatrix, DVector};

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::mbdyn::drives::callers::{single_term, template_vec3, Drives};
use crate::mbdyn::syntax::parser::Statement;
use crate::element::{LawFunctions, TimeVariance};
use crate::element::drive::{Drive, ScalarFunction};
use crate::kinematics::{Mat3, Vec3};
use crate::mbdyn::drives::callers;
use crate::mbdyn::drives::scalar_functions;
use crate::mbdyn::drives::templates;
use crate::mbdyn::syntax::diagnostic;
use crate::mbdyn::syntax::parser;

/// A (visco)elastic law in `dim` dimensions: `f = K (ε − ε_p) + C ε̇ + f_p`, plus a nonlinear
/// law's per-component functions.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearLaw {
    pub stiffness: DMatrix<f64>,
    pub viscosity: DMatrix<f64>,
    pub prestrain: DVector<f64>,
    pub prestress: DVector<f64>,
    /// A nonlinear law's per-component `f′_i(ε_i − ε_p,i)` and `f″_i(ε̇_i)` (empty when linear).
    pub functions: LawFunctions,
    /// The keyword of a nonlinear law (`nlsf …`, `scalar function elastic …`), for messages.
    pub nonlinear: Option<&'static str>,
    /// A `linear elastic bistop` or `linear viscoelastic bistop` law's switch (1-D, rods).
    pub bistop: Option<Bistop>,
    /// A `linear time variant viscoelastic generic` law's drives on `K` and `C`.
    pub time_variance: Option<TimeVariance>,
}

/// The switch of MBDyn's bistop laws (constltp_impl.h, `BiStopCLWrapper`): the law acts
/// from the instant `activate` is non-zero, on the strain from that instant's strain, until
/// `deactivate` is non-zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Bistop {
    pub initially_active: bool,
    pub activate: Drive,
    pub deactivate: Drive,
}

impl LinearLaw {
    pub fn dim(&self) -> usize {
        self.stiffness.nrows()
    }
    pub fn stiffness3(&self) -> Mat3 {
        Mat3::from_fn(|i, j| self.stiffness[(i, j)])
    }
    pub fn viscosity3(&self) -> Mat3 {
        Mat3::from_fn(|i, j| self.viscosity[(i, j)])
    }
}

const KINDS: [&str; 9] = [
    "linear elastic generic", "linear elastic isotropic", "linear elastic", "linear viscous generic", "linear viscous isotropic", "linear viscous",
    "linear viscoelastic generic", "linear viscoelastic isotropic", "linear viscoelastic",
];

const UNSUPPORTED: [&str; 13] = [
    "linear elastic generic axial torsion coupling", "cubic elastic generic", "inverse square elastic", "log elastic",
    "double linear elastic", "isotropic hardening elastic",
    "cubic viscoelastic generic", "double linear viscoelastic", "turbulent viscoelastic", "shock absorber",
    "symbolic elastic", "symbolic viscous", "symbolic viscoelastic",
];

/// Where a bistop law is read elsewhere than on a rod.
const BISTOP_ON_RODS: &str = "a bistop constitutive law is supported by romdyn on a rod only (its status and reference strain are the rod's events)";

const NLSF: [&str; 3] = ["nlsf viscoelastic", "nlsf elastic", "nlsf viscous"];

/// The `scalar function elastic` laws, longest first.
const FUNCTION_ELASTIC: [&str; 3] = ["scalar function elastic isotropic", "scalar function elastic orthotropic", "scalar function elastic"];

/// The elements that take a nonlinear law, for messages.
const NONLINEAR_ELEMENTS: &str = "the deformable displacement joint, deformable hinge, deformable joint, deformable axial joint, rod, beam3 and beam2";

/// The `constitutive law:` cards read so far.
#[derive(Default)]
pub struct Laws {
    table: HashMap<u32, (LinearLaw, usize, Span)>,
    /// The scalar functions each law card names (an element referring to the law uses them).
    functions: HashMap<u32, Vec<String>>,
}

/// Reads a `constitutive law: LABEL, [name, "…",] DIM, LAW;` card.
pub fn constitutive_law_card(st: &Statement, c: &mut Cursor, laws: &mut Laws, drives: &Drives) -> Result<(), MbdynError> {
    let span = c.here();
    let label = c.label("constitutive law label")?;
    if let Some((_, _, at)) = laws.table.get(&label) {
        return Err(c.error_at(span, format!("constitutive law {label} is defined twice (first at line {})", at.line)));
    }
    if c.accept("name") {
        c.string("constitutive law name")?;
    }
    let dim_span = c.here();
    let dim = c.count("dimension of the constitutive law (1, 3 or 6)")?;
    if ![1, 3, 6].contains(&dim) {
        return Err(c.error_at(dim_span, format!("a constitutive law has dimension 1, 3 or 6, found {dim}")));
    }
    let law_span = c.here();
    let before = drives.functions.take_used();
    let (law, varying) = read_law(c, dim, laws, drives, st.seq)?;
    if varying.is_some() {
        return Err(c.error_at(law_span, "a time-varying prestrain is supported by romdyn on rods only, written on the rod's own law"));
    }
    c.finish()?;
    laws.functions.insert(label, drives.functions.take_used());
    before.iter().for_each(|n| drives.functions.note_used(n));
    laws.table.insert(label, (law, st.seq, st.span));
    Ok(())
}

/// A linear constitutive law of dimension `dim` at statement `seq` that does not change in
/// time (the viscous body's: a nonlinear law, a time-variant one and a prestrain that changes
/// in time are refused by name).
pub fn linear_law(c: &mut Cursor, dim: usize, laws: &Laws, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let span = c.here();
    let law = linear_or_time_variant_law(c, dim, laws, drives, seq)?;
    if law.time_variance.is_some() {
        return Err(c.error_at(span, format!("constitutive law '{TIME_VARIANT}' is supported by romdyn on {NONLINEAR_ELEMENTS} and the invariant deformable hinge, not on this element (MBDyn 1.7.3 refuses it on a viscous body too, which needs a viscous law)")));
    }
    Ok(law)
}

/// A linear constitutive law of dimension `dim` at statement `seq`, time-variant or not (the
/// invariant deformable hinge's); a nonlinear law is refused by name.
pub fn linear_or_time_variant_law(c: &mut Cursor, dim: usize, laws: &Laws, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let span = c.here();
    let law = nonlinear_law(c, dim, laws, drives, seq)?;
    if let Some(kind) = law.nonlinear {
        return Err(c.error_at(span, format!("constitutive law '{kind}' is supported by romdyn on {NONLINEAR_ELEMENTS}, not on this element")));
    }
    Ok(law)
}

/// A constitutive law of dimension `dim` at statement `seq`, linear or nonlinear (`nlsf`,
/// `scalar function elastic`); a prestrain that changes in time is refused by name.
pub fn nonlinear_law(c: &mut Cursor, dim: usize, laws: &Laws, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let span = c.here();
    let (law, varying) = read_law(c, dim, laws, drives, seq)?;
    if law.bistop.is_some() {
        return Err(c.error_at(span, BISTOP_ON_RODS));
    }
    if varying.is_some() {
        return Err(c.error_at(span, "a time-varying prestrain is supported by romdyn on rods only"));
    }
    Ok(law)
}

/// A 1-D law whose prestrain may be a drive that changes in time (or reads the model's
/// state; a rod's): the law with its constant prestrain zero, and that drive; linear, `nlsf`
/// or `scalar function elastic`.
pub fn law_with_prestrain_drive(c: &mut Cursor, dim: usize, laws: &Laws, drives: &Drives, seq: usize) -> Result<(LinearLaw, Option<Drive>), MbdynError> {
    read_law(c, dim, laws, drives, seq)
}

/// A 1-D law at statement `seq`, linear or nonlinear (the deformable axial joint's).
pub fn axial_law(c: &mut Cursor, laws: &Laws, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let span = c.here();
    let (law, varying) = read_law(c, 1, laws, drives, seq)?;
    if law.bistop.is_some() {
        return Err(c.error_at(span, BISTOP_ON_RODS));
    }
    if varying.is_some() {
        return Err(c.error_at(span, "a time-varying prestrain is supported by romdyn on rods only"));
    }
    Ok(law)
}

const BISTOP: [&str; 2] = ["linear viscoelastic bistop", "linear elastic bistop"];

/// `linear [visco]elastic bistop, E, [E′,] [initial status, {active | inactive | BOOL},]
/// ACTIVATING_DRIVE, DEACTIVATING_DRIVE` after its keyword (constltp_impl.cc,
/// `LinearBiStopCLR::Read`); the prestress and prestrain follow.
fn bistop(c: &mut Cursor, kind: &str, dim: usize, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    if dim != 1 {
        return Err(c.error(format!("constitutive law '{kind}' is supported by romdyn in 1-D only (a rod), not in {dim}-D")));
    }
    let k = c.real("stiffness [per unit strain]")?;
    let v = if kind == "linear viscoelastic bistop" { c.real("viscosity [per unit strain rate]")? } else { 0.0 };
    let mut initially_active = false;
    if c.accept("initial status") {
        initially_active = if c.accept("active") {
            true
        } else if c.accept("inactive") {
            false
        } else {
            c.real("initial status (active, inactive or a boolean)")? != 0.0
        };
    }
    let activate = callers::drive(c, drives, seq)?;
    let deactivate = callers::drive(c, drives, seq)?;
    let one = |x: f64| DMatrix::from_element(1, 1, x);
    let bistop = Some(Bistop { initially_active, activate, deactivate });
    Ok(LinearLaw { stiffness: one(k), viscosity: one(v), prestrain: DVector::zeros(1), prestress: DVector::zeros(1), functions: LawFunctions::default(), nonlinear: None, bistop, time_variance: None })
}

/// The one time-variant law MBDyn 1.7.3 registers.
const TIME_VARIANT: &str = "linear time variant viscoelastic generic";

/// Whether the keyword `w` begins with the words of `start` (spaces and case aside).
fn same_start(w: &str, start: &str) -> bool {
    let squeeze = |s: &str| s.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_lowercase()).collect::<String>();
    squeeze(w).starts_with(&squeeze(start))
}

/// `linear time variant viscoelastic generic, K, DRIVE_K, {C | proportional, FACTOR},
/// DRIVE_C` after its keyword (constltp_impl.cc, `LTVViscoElasticGenericCLR::Read`): `K`,
/// `C` a number in 1-D, a matrix in 3-D and 6-D; `f = f_p + s_K(t) K (ε − ε_p) + s_C(t) C ε̇`
/// (MBDyn 1.7.3 builds this law whatever `K` and `C` are: its reader's switch to an elastic
/// or viscous law on a null matrix is compiled out).
fn time_variant(c: &mut Cursor, dim: usize, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let stiffness = matrix(c, dim, if dim == 1 { "stiffness [per unit strain]" } else { "stiffness matrix" })?;
    let stiffness_scale = callers::drive(c, drives, seq)?;
    let viscosity = if c.accept("proportional") { &stiffness * c.real("proportional damping factor [s]")? } else { matrix(c, dim, if dim == 1 { "viscosity [per unit strain rate]" } else { "viscosity matrix" })? };
    let viscosity_scale = callers::drive(c, drives, seq)?;
    let time_variance = Some(TimeVariance { stiffness: stiffness_scale, viscosity: viscosity_scale });
    Ok(LinearLaw { stiffness, viscosity, prestrain: DVector::zeros(dim), prestress: DVector::zeros(dim), functions: LawFunctions::default(), nonlinear: None, bistop: None, time_variance })
}

/// `nlsf …` after its keyword: `K, {F_1 | null}, …, {F_dim | null}` for the elastic part,
/// `{C | proportional, FACTOR}, {F_1 | null}, …` for the viscous part (`K`, `C` a number in
/// 1-D, a matrix in 3-D and 6-D, `null` zero; `proportional` only in `nlsf viscoelastic`):
/// constltp_nlsf.cc, `NLSFViscoElasticCLR`.
///
/// MBDyn 1.7.3 adds a viscous function `f″_i` in 3-D and 6-D only when the law also has an
/// elastic part (its `Update` tests the elastic flag there, the viscous one in 1-D): a 3-D or
/// 6-D law with viscous functions and no elastic part drops them there. romdyn applies the
/// manual's formula in every dimension.
fn nlsf(c: &mut Cursor, kind: &'static str, dim: usize, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    let functions = |c: &mut Cursor| -> Result<Vec<Option<ScalarFunction>>, MbdynError> {
        (0..dim).map(|_| if c.accept("null") { Ok(None) } else { scalar_functions::scalar_function(c, &drives.functions, seq).map(Some) }).collect()
    };
    let coefficients = |c: &mut Cursor, what: &str| -> Result<DMatrix<f64>, MbdynError> {
        if dim == 1 && c.accept("null") {
            return Ok(DMatrix::zeros(1, 1));
        }
        matrix(c, dim, what)
    };
    let zero = DMatrix::zeros(dim, dim);
    let (mut k, mut v) = (zero.clone(), zero);
    let mut f = LawFunctions { elastic: vec![None; dim], viscous: vec![None; dim] };
    if kind != "nlsf viscous" {
        k = coefficients(c, if dim == 1 { "stiffness [per unit strain]" } else { "stiffness matrix" })?;
        f.elastic = functions(c)?;
    }
    if kind != "nlsf elastic" {
        v = if kind == "nlsf viscoelastic" && c.accept("proportional") {
            &k * c.real("proportional damping factor [s]")?
        } else {
            coefficients(c, if dim == 1 { "viscosity [per unit strain rate]" } else { "viscosity matrix" })?
        };
        f.viscous = functions(c)?;
    }
    Ok(LinearLaw { stiffness: k, viscosity: v, prestrain: DVector::zeros(dim), prestress: DVector::zeros(dim), functions: f, nonlinear: Some(kind), bistop: None, time_variance: None })
}

/// `scalar function elastic [isotropic | orthotropic], …` after its keyword
/// (ScalarFunctionsImpl.cc): in 1-D one function, whichever word follows (MBDyn's 1-D
/// orthotropic reader is the isotropic one); in 3-D and 6-D `isotropic, F` (`F` on every
/// component) or `orthotropic, {F_1 | null}, …, {F_dim | null}`. No prestrain or prestress.
fn function_elastic(c: &mut Cursor, kind: &'static str, dim: usize, drives: &Drives, seq: usize) -> Result<LinearLaw, MbdynError> {
    if dim > 1 && kind == "scalar function elastic" {
        return Err(c.error(format!("constitutive law 'scalar function elastic' is registered by MBDyn 1.7.3 in 1-D only (ScalarFunctionsImpl.cc); in {dim}-D write 'scalar function elastic isotropic' or 'scalar function elastic orthotropic'")));
    }
    let function = |c: &mut Cursor| scalar_functions::scalar_function(c, &drives.functions, seq);
    let elastic = if dim == 1 || kind == "scalar function elastic isotropic" {
        vec![Some(function(c)?); dim]
    } else {
        (0..dim).map(|_| if c.accept("null") { Ok(None) } else { function(c).map(Some) }).collect::<Result<_, _>>()?
    };
    let zero = DMatrix::zeros(dim, dim);
    let functions = LawFunctions { elastic, viscous: vec![None; dim] };
    Ok(LinearLaw { stiffness: zero.clone(), viscosity: zero, prestrain: DVector::zeros(dim), prestress: DVector::zeros(dim), functions, nonlinear: Some(kind), bistop: None, time_variance: None })
}

/// A constitutive law of dimension `dim` at statement `seq`, `nlsf` included, with the drive
/// of a 1-D prestrain that changes in time.
fn read_law(c: &mut Cursor, dim: usize, laws: &Laws, drives: &Drives, seq: usize) -> Result<(LinearLaw, Option<Drive>), MbdynError> {
    let span = c.here();
    if c.accept("reference") {
        let label = c.label("constitutive law label")?;
        return match laws.table.get(&label) {
            Some((l, s, _)) if *s < seq && l.dim() == dim => {
                laws.functions.get(&label).into_iter().flatten().for_each(|n| drives.functions.note_used(n));
                Ok((l.clone(), None))
            }
            Some((l, s, _)) if *s < seq => Err(c.error_at(span, format!("constitutive law {label} has dimension {}, this element needs {dim}", l.dim()))),
            Some((_, _, at)) => Err(c.error_at(span, format!("constitutive law {label} is used before its definition (line {})", at.line))),
            None => Err(c.error_at(span, format!("constitutive law {label} is not defined"))),
        };
    }
    if let Some(kind) = c.accept_any(&NLSF) {
        let mut law = nlsf(c, kind, dim, drives, seq)?;
        let varying = prestress_and_prestrain(c, &mut law, dim, drives, seq)?;
        return Ok((law, varying));
    }
    if let Some(kind) = c.accept_any(&FUNCTION_ELASTIC) {
        return Ok((function_elastic(c, kind, dim, drives, seq)?, None));
    }
    if c.accept(TIME_VARIANT) {
        let mut law = time_variant(c, dim, drives, seq)?;
        let varying = prestress_and_prestrain(c, &mut law, dim, drives, seq)?;
        return Ok((law, varying));
    }
    if let Some(w) = c.peek_keyword().filter(|w| same_start(w, "linear time variant")) {
        return Err(c.error(format!("constitutive law '{w}' is not registered by MBDyn 1.7.3 (constltp_impl.cc, `InitCL`: of the time-variant laws only '{TIME_VARIANT}', which MBDyn's manual's example writes without 'generic'), nor by romdyn: write '{TIME_VARIANT}, K, DRIVE, {{C | proportional, FACTOR}}, DRIVE' (a null C for an elastic law)")));
    }
    if let Some(kind) = c.accept_any(&BISTOP) {
        let mut law = bistop(c, kind, dim, drives, seq)?;
        let varying = prestress_and_prestrain(c, &mut law, dim, drives, seq)?;
        return Ok((law, varying));
    }
    let Some(kind) = c.accept_any(&KINDS) else {
        if let Some(k) = c.peek_keyword().and_then(|w| UNSUPPORTED.iter().find(|u| parser::same_keyword(u, w))) {
            let rods = if k.starts_with("symbolic") {
                "; a symbolic law needs its expression's derivative, which MBDyn takes with GiNaC (MBDyn 1.7.3 built without it refuses it too) and romdyn's math parser does not"
            } else {
                ""
            };
            let refusal = if k.starts_with("symbolic") { format!("constitutive law '{k}' is not supported by romdyn (an MBDyn 1.7.3 built with GiNaC runs it)") } else { diagnostic::mbdyn_runs_it(&format!("constitutive law '{k}'")) };
            return Err(c.error(format!("{refusal} (supported: linear elastic, linear viscous, linear viscoelastic, each isotropic or generic; {TIME_VARIANT}; nlsf elastic, viscous, viscoelastic; scalar function elastic isotropic, orthotropic{rods})")));
        }
        return Err(c.error(format!("expected a constitutive law ({}, {TIME_VARIANT}, {}, {}, {}), found {}", KINDS.join(", "), NLSF.join(", "), FUNCTION_ELASTIC.join(", "), BISTOP.join(", "), c.found())));
    };
    let generic = kind.ends_with("generic");
    let read = |c: &mut Cursor, what: &str| if generic { matrix(c, dim, what) } else { Ok(DMatrix::identity(dim, dim) * c.real(what)?) };
    let zero = DMatrix::zeros(dim, dim);
    let (stiffness, viscosity) = if kind.starts_with("linear elastic") {
        (read(c, "stiffness")?, zero)
    } else if kind.starts_with("linear viscous") {
        (zero, read(c, "viscosity")?)
    } else {
        let k = read(c, "stiffness")?;
        let v = if c.accept("proportional") { &k * c.real("proportional damping factor [s]")? } else { read(c, "viscosity")? };
        (k, v)
    };
    let mut law = LinearLaw { stiffness, viscosity, prestrain: DVector::zeros(dim), prestress: DVector::zeros(dim), functions: LawFunctions::default(), nonlinear: None, bistop: None, time_variance: None };
    let varying = prestress_and_prestrain(c, &mut law, dim, drives, seq)?;
    Ok((law, varying))
}

/// The optional `prestress, …` and `prestrain, …` after a law, into `law`; a 1-D prestrain
/// that changes in time is returned as its drive (`law`'s constant prestrain stays zero).
fn prestress_and_prestrain(c: &mut Cursor, law: &mut LinearLaw, dim: usize, drives: &Drives, seq: usize) -> Result<Option<Drive>, MbdynError> {
    if c.accept("prestress") {
        law.prestress = if dim == 3 { DVector::from_column_slice(c.vec3_values("prestress")?.as_slice()) } else { vector(c, dim, "prestress")? };
    }
    let mut varying = None;
    if c.accept("prestrain") {
        let span = c.here();
        if dim == 1 {
            // A 1-D template drive caller (tpldrive_impl.cc, ReadDC1D): `[single |
            // component,] DRIVE` with no value before the drive (SingleTDCR<doublereal>
            // reads none), `null`, `zero`, `array, N, …`.
            match template_1d(c, drives, seq)? {
                Drive::Const(x) => law.prestrain[0] = x,
                d => varying = Some(d),
            }
        } else {
            law.prestrain = prestrain(c, dim, drives, seq)?;
        }
        if varying.as_ref().is_some_and(|_| law.stiffness[(0, 0)] == 0.0) {
            return Err(c.error_at(span, "a prestrain needs a stiffness"));
        }
    }
    Ok(varying)
}

/// A 1-D template drive caller as one drive (`null`, `single`, `component`, `array`, and
/// `reference, LABEL` to a dimension-1 `template drive caller:` card, as mbpar.cc's
/// `GetTplDriveCaller` reads it: not a `drive caller:` card).
fn template_1d(c: &mut Cursor, drives: &Drives, seq: usize) -> Result<Drive, MbdynError> {
    let terms = templates::template(c, drives, seq, templates::TemplateDim::Scalar)?;
    let mut scaled: Vec<Drive> = terms
        .into_iter()
        .map(|(v, d)| match (v[0], d) {
            (f, d) if f == 1.0 => d,
            (f, Drive::Const(x)) => Drive::Const(f * x),
            (f, d) => Drive::Product(Box::new(Drive::Const(f)), Box::new(d)),
        })
        .collect();
    Ok(match scaled.len() {
        0 => Drive::Const(0.0),
        1 => scaled.remove(0),
        _ if scaled.iter().all(|d| matches!(d, Drive::Const(_))) => Drive::Const(scaled.iter().map(|d| d.value(0.0)).sum()),
        _ => Drive::Sum(scaled),
    })
}

/// A constant prestrain (a template drive caller that does not change in time).
fn prestrain(c: &mut Cursor, dim: usize, drives: &Drives, seq: usize) -> Result<DVector<f64>, MbdynError> {
    let span = c.here();
    let constant = |d: &Drive| matches!(d, Drive::Const(_));
    if dim == 3 {
        let terms = template_vec3(c, drives, seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values("prestrain"))?;
        return match single_term(terms) {
            Some((v, d)) if constant(&d) => Ok(DVector::from_column_slice((v * d.value(0.0)).as_slice())),
            _ => Err(c.error_at(span, "a time-varying prestrain is not supported by romdyn (MBDyn 1.7.3 runs it)")),
        };
    }
    c.accept("single");
    let v = vector(c, dim, "prestrain")?;
    let d = callers::drive(c, drives, seq)?;
    if !constant(&d) {
        return Err(c.error_at(span, "a time-varying prestrain is not supported by romdyn (MBDyn 1.7.3 runs it)"));
    }
    Ok(v * d.value(0.0))
}

fn vector(c: &mut Cursor, dim: usize, what: &str) -> Result<DVector<f64>, MbdynError> {
    if c.accept("null") {
        return Ok(DVector::zeros(dim));
    }
    let mut v = DVector::zeros(dim);
    for k in 0..dim {
        v[k] = c.real(what)?;
    }
    Ok(v)
}

/// A `dim × dim` matrix (a scalar for 1D; MBDyn's `Mat3x3` or `Mat6x6` forms otherwise,
/// [`Cursor::mat3x3`], [`Cursor::mat6x6`]).
fn matrix(c: &mut Cursor, dim: usize, what: &str) -> Result<DMatrix<f64>, MbdynError> {
    match dim {
        1 => Ok(DMatrix::from_element(1, 1, c.real(what)?)),
        3 => {
            let m = c.mat3x3(what)?;
            Ok(DMatrix::from_fn(3, 3, |i, j| m[(i, j)]))
        }
        // Dimension 6 (a law has dimension 1, 3 or 6).
        _ => {
            let m = c.mat6x6(what)?;
            Ok(DMatrix::from_fn(6, 6, |i, j| m[(i, j)]))
        }
    }
}

/// The 3-D law a deformable displacement joint or hinge takes.
pub fn three(law: &LinearLaw) -> crate::element::LinearViscoelastic {
    crate::element::LinearViscoelastic { stiffness: law.stiffness3(), viscosity: law.viscosity3() }
}

/// The prestrain and prestress of a 3-D law as one equivalent rest strain `ε_p − K⁻¹ f_p`
/// (`None` if a prestress meets a singular stiffness).
pub fn rest_strain(law: &LinearLaw) -> Option<Vec3> {
    let p = Vec3::new(law.prestrain[0], law.prestrain[1], law.prestrain[2]);
    let f = Vec3::new(law.prestress[0], law.prestress[1], law.prestress[2]);
    if f == Vec3::zeros() {
        return Some(p);
    }
    law.stiffness3().try_inverse().map(|k| p - k * f)
}
