//! The plate elements' section laws (input manual, "Plate Elements"; MBDyn 1.7.3's
//! shell.cc `ReadShellConstLaw`, membrane.cc `ReadMembraneConstLaw`):
//!
//! - shells: the 12×12 law as `matr` (or bare, 144 values row by row), `sym` (the upper
//!   triangle, 78 values row by row), `diag` (12 values), `isotropic, {E | Young modulus},
//!   E, {nu | Poisson modulus}, NU, {G | shear modulus}, G, thickness, H [, as, AS] [, at,
//!   AT]` (two of E, ν, G; `as` = 1 and `at` = 0.01 by default), or `plane stress
//!   orthotropic, {E_l | longitudinal Young modulus}, EL, {E_t | transverse Young modulus},
//!   ET, {nu_lt | longitudinal transverse Poisson modulus}, NU [or {nu_tl | transverse
//!   longitudinal Poisson modulus}, NU], {G | shear modulus}, G, thickness, H [, as, AS]
//!   [, at, AT]` (the orthotropy axes along the element's first surface direction, MBDyn's
//!   shell.cc only: the manual writes such a law as a `matr`); then `[, prestress, (Vec12)]`;
//! - membranes: the 3×3 law on (n₁₁, n₂₂, n₁₂) as `matr` (9 values), `sym` (6), `diag` (3),
//!   or `isotropic` (E, ν, G, thickness as above, no `as`, `at`); then `[, prestress, T11,
//!   T22, T12]`.

use nalgebra::{SMatrix, SVector};

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::element::{MembraneLaw, ShellLaw};

/// A shell's 12×12 law and its prestress.
pub fn shell_law(c: &mut Cursor) -> Result<ShellLaw, MbdynError> {
    let mut law = if c.accept("isotropic") {
        let d = isotropic_data(c, "shell", true)?;
        ShellLaw::isotropic(d.e, d.nu, d.g, d.thickness, d.shear_factor, d.drilling_factor)
    } else if c.accept("plane stress orthotropic") {
        orthotropic(c)?
    } else {
        ShellLaw { stiffness: square(c, "shell stiffness")?, prestress: SVector::zeros() }
    };
    if c.accept("prestress") {
        law.prestress = vector(c, "shell prestress component", "[N/m, N]")?;
    }
    Ok(law)
}

/// A membrane's 3×3 law and its prestress.
pub fn membrane_law(c: &mut Cursor) -> Result<MembraneLaw, MbdynError> {
    let mut law = if c.accept("isotropic") {
        let d = isotropic_data(c, "membrane", false)?;
        MembraneLaw::isotropic(d.e, d.nu, d.g, d.thickness)
    } else {
        MembraneLaw { stiffness: square(c, "membrane stiffness")?, prestress: SVector::zeros() }
    };
    if c.accept("prestress") {
        law.prestress = vector(c, "membrane prestress component", "[N/m]")?;
    }
    Ok(law)
}

/// `diag` (N values), `sym` (the upper triangle row by row) or `[matr,]` (N×N row by row).
fn square<const N: usize>(c: &mut Cursor, what: &str) -> Result<SMatrix<f64, N, N>, MbdynError> {
    let mut k = SMatrix::<f64, N, N>::zeros();
    let entry = |c: &mut Cursor, i: usize, j: usize| c.real(&format!("{what} D({},{})", i + 1, j + 1));
    if c.accept("diag") {
        for i in 0..N {
            k[(i, i)] = entry(c, i, i)?;
        }
    } else if c.accept("sym") {
        for i in 0..N {
            for j in i..N {
                k[(i, j)] = entry(c, i, j)?;
                k[(j, i)] = k[(i, j)];
            }
        }
    } else {
        c.accept("matr");
        for i in 0..N {
            for j in 0..N {
                k[(i, j)] = entry(c, i, j)?;
            }
        }
    }
    Ok(k)
}

fn vector<const N: usize>(c: &mut Cursor, what: &str, unit: &str) -> Result<SVector<f64, N>, MbdynError> {
    let mut v = SVector::<f64, N>::zeros();
    for i in 0..N {
        v[i] = c.real(&format!("{what} {} {unit}", i + 1))?;
    }
    Ok(v)
}

/// Data of the isotropic law.
struct Isotropic {
    e: f64,
    nu: f64,
    g: f64,
    thickness: f64,
    shear_factor: f64,
    drilling_factor: f64,
}

/// Keyworded data, each once, in any order, as MBDyn's readers take them: `(keywords,
/// name, check)` per datum; the values by datum.
fn keyworded<const N: usize>(c: &mut Cursor, law: &str, data: [(&[&str], &str, fn(f64) -> Option<&'static str>); N]) -> Result<[Option<f64>; N], MbdynError> {
    let mut got = [None; N];
    'next: loop {
        for (k, (keywords, name, check)) in data.iter().enumerate() {
            if !keywords.iter().any(|w| c.accept(w)) {
                continue;
            }
            let span = c.here();
            if got[k].is_some() {
                return Err(c.error_at(span, format!("{law}: {name} given twice")));
            }
            let v = c.real(name)?;
            if let Some(range) = check(v) {
                return Err(c.error_at(span, format!("{law}: {name} must be {range}, found {v}")));
            }
            got[k] = Some(v);
            continue 'next;
        }
        return Ok(got);
    }
}

fn positive(v: f64) -> Option<&'static str> {
    (v <= 0.0).then_some("positive")
}

fn poisson(v: f64) -> Option<&'static str> {
    (!(0.0..0.5).contains(&v)).then_some("in [0, 0.5)")
}

fn any(_: f64) -> Option<&'static str> {
    None
}

/// `isotropic, …` as MBDyn's shell.cc and membrane.cc read it: each datum once, two of E,
/// ν, G (all three consistent), the thickness; `as` and `at` for shells.
fn isotropic_data(c: &mut Cursor, element: &str, factors: bool) -> Result<Isotropic, MbdynError> {
    let start = c.here();
    let law = format!("{element} isotropic law");
    let got = keyworded(
        c,
        &law,
        [
            (&["E", "Young modulus"], "Young's modulus E [Pa]", positive),
            (&["nu", "Poisson modulus"], "Poisson's ratio nu", poisson),
            (&["G", "shear modulus"], "shear modulus G [Pa]", positive),
            (&["thickness"], "thickness [m]", positive),
            (if factors { &["as"] } else { &[] }, "shear factor 'as'", positive),
            (if factors { &["at"] } else { &[] }, "drilling factor 'at'", positive),
        ],
    )?;
    let (e, nu, g) = match (got[0], got[1], got[2]) {
        (Some(e), Some(nu), Some(g)) => {
            if (e / (2.0 * (1.0 + nu)) - g).abs() > f64::EPSILON * g.max(1.0) {
                return Err(c.error_at(start, format!("{law}: E = {e}, nu = {nu} and G = {g} are inconsistent (G must be E/(2 (1 + nu)))")));
            }
            (e, nu, g)
        }
        (Some(e), Some(nu), None) => (e, nu, e / (2.0 * (1.0 + nu))),
        (Some(e), None, Some(g)) => {
            let nu = e / (2.0 * g) - 1.0;
            if !(nu > 0.0 && nu < 0.5) {
                return Err(c.error_at(start, format!("{law}: E = {e} and G = {g} give nu = {nu}, outside (0, 0.5)")));
            }
            (e, nu, g)
        }
        (None, Some(nu), Some(g)) => (2.0 * (1.0 + nu) * g, nu, g),
        _ => return Err(c.error_at(start, format!("{law}: two of 'E', 'nu' and 'G' are needed"))),
    };
    let Some(thickness) = got[3] else {
        return Err(c.error_at(start, format!("{law}: the 'thickness' is missing")));
    };
    Ok(Isotropic { e, nu, g, thickness, shear_factor: got[4].unwrap_or(1.0), drilling_factor: got[5].unwrap_or(0.01) })
}

/// `plane stress orthotropic, …` as MBDyn 1.7.3's shell.cc reads it (the fiber angle
/// `beta` it refuses, "not supported yet"), into [`ShellLaw::orthotropic`]. Unlike
/// MBDyn, the thickness is required (MBDyn reads on with it undefined), and `nu_lt` and
/// `nu_tl` may both be given when consistent to rounding (MBDyn compares them to 2.2e-16
/// absolute).
fn orthotropic(c: &mut Cursor) -> Result<ShellLaw, MbdynError> {
    let start = c.here();
    let law = "shell plane stress orthotropic law";
    let got = keyworded(
        c,
        law,
        [
            (&["E_l", "longitudinal Young modulus"], "longitudinal Young's modulus E_l [Pa]", positive),
            (&["E_t", "transverse Young modulus"], "transverse Young's modulus E_t [Pa]", positive),
            (&["nu_lt", "longitudinal transverse Poisson modulus"], "Poisson's ratio nu_lt", any),
            (&["nu_tl", "transverse longitudinal Poisson modulus"], "Poisson's ratio nu_tl", any),
            (&["G", "shear modulus"], "shear modulus G [Pa]", positive),
            (&["thickness"], "thickness [m]", positive),
            (&["as"], "shear factor 'as'", positive),
            (&["at"], "drilling factor 'at'", positive),
        ],
    )?;
    if c.peek_keyword().is_some_and(|w| w.eq_ignore_ascii_case("beta")) {
        return Err(c.error("shell plane stress orthotropic law: the fiber angle 'beta' is not supported (MBDyn 1.7.3 refuses it too: \"not supported yet\"); give the law in the fibers' axes along the element's first direction"));
    }
    let missing = |what: &str| c.error_at(start, format!("{law}: the {what} is missing"));
    let (Some(el), Some(et)) = (got[0], got[1]) else {
        return Err(missing(if got[0].is_none() { "longitudinal Young's modulus 'E_l'" } else { "transverse Young's modulus 'E_t'" }));
    };
    // ν_tl E_l = ν_lt E_t (the compliance is symmetric).
    let nu_lt = match (got[2], got[3]) {
        (Some(lt), Some(tl)) if (tl * el - lt * et).abs() > 4.0 * f64::EPSILON * (tl * el).abs().max((lt * et).abs()) => {
            return Err(c.error_at(start, format!("{law}: nu_lt = {lt} and nu_tl = {tl} are inconsistent (nu_tl E_l must equal nu_lt E_t)")));
        }
        (Some(lt), _) => lt,
        (None, Some(tl)) => tl * el / et,
        (None, None) => return Err(missing("Poisson's ratio ('nu_lt' or 'nu_tl')")),
    };
    let Some(g) = got[4] else { return Err(missing("shear modulus 'G'")) };
    let Some(h) = got[5] else { return Err(missing("'thickness'")) };
    let denominator = 1.0 - nu_lt * nu_lt * et / el;
    if denominator <= 0.0 {
        return Err(c.error_at(start, format!("{law}: nu_lt^2 E_t/E_l = {} is not below 1 (the law would not be positive definite)", 1.0 - denominator)));
    }
    Ok(ShellLaw::orthotropic(el, et, nu_lt, g, h, got[6].unwrap_or(1.0), got[7].unwrap_or(0.01)))
}
