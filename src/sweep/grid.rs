//! Design points: values of an MBDyn file's `set:` variables, as a list or a linspace per
//! variable and their full grid.

use crate::study::{Setting, StudyError};

/// One swept variable and its values.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// The `set:` variable's name, as the file spells it.
    pub name: String,
    pub values: Vec<f64>,
}

/// Largest number of design points of one sweep (a typo such as `0:1:1e9` would otherwise
/// allocate and run for days).
pub const MAX_POINTS: usize = 1_000_000;

impl std::str::FromStr for Parameter {
    type Err = String;

    /// `NAME=A:B:N` (N equally spaced values from A to B, both included) or
    /// `NAME=V1,V2,…` (a list).
    fn from_str(s: &str) -> Result<Self, String> {
        let (name, spec) = s.split_once('=').ok_or_else(|| format!("'{s}': expected NAME=A:B:N or NAME=V1,V2,…"))?;
        let name = name.trim();
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') || name.starts_with(|c: char| c.is_ascii_digit()) {
            return Err(format!("'{name}' is not a variable name (letters, digits and '_', not starting with a digit)"));
        }
        let number = |t: &str| -> Result<f64, String> {
            let x: f64 = t.trim().parse().map_err(|_| format!("{name}: '{}' is not a number", t.trim()))?;
            if x.is_finite() { Ok(x) } else { Err(format!("{name}: {x} is not a finite value")) }
        };
        let values = if spec.contains(':') {
            let parts: Vec<&str> = spec.split(':').collect();
            let [a, b, n] = parts[..] else { return Err(format!("{name}={spec}: expected A:B:N (from A to B in N points)")) };
            let (a, b) = (number(a)?, number(b)?);
            let n: usize = n.trim().parse().map_err(|_| format!("{name}={spec}: N '{}' is not a whole number of points", n.trim()))?;
            match n {
                0 => return Err(format!("{name}={spec}: need at least 1 point")),
                1 if a != b => return Err(format!("{name}={spec}: 1 point cannot span {a} to {b} (give N >= 2, or A:A:1)")),
                n if n > MAX_POINTS => return Err(format!("{name}={spec}: {n} points, more than romdyn's limit of {MAX_POINTS}")),
                1 => vec![a],
                // a + (b − a) k/(n − 1), the last one exactly b.
                n => (0..n).map(|k| if k + 1 == n { b } else { a + (b - a) * k as f64 / (n - 1) as f64 }).collect(),
            }
        } else {
            spec.split(',').map(number).collect::<Result<Vec<_>, _>>()?
        };
        Ok(Parameter { name: name.to_string(), values })
    }
}

/// The values `--set NAME=VALUE` gives a single run (eig, rom, validate, run, …): one value
/// per variable, each variable once.
pub fn single_values(parameters: &[Parameter]) -> Result<crate::input::mbdyn::SetOverrides, String> {
    let mut out = crate::input::mbdyn::SetOverrides::new();
    for p in parameters {
        if out.contains_key(&p.name) {
            return Err(format!("{}: the variable is given twice", p.name));
        }
        let [value] = p.values[..] else {
            return Err(format!("{}: {} values; one run takes one value, NAME=VALUE (romdyn sweep runs a grid)", p.name, p.values.len()));
        };
        out.insert(p.name.clone(), value);
    }
    Ok(out)
}

/// The point `--interpolate NAME=VALUE` gives: one value for each swept parameter, in the
/// order of `swept`, each within its swept values (checked before any point runs).
pub fn interpolation_point(swept: &[Parameter], given: &[Parameter]) -> Result<Vec<f64>, String> {
    let values = single_values(given)?;
    let names: Vec<&str> = swept.iter().map(|p| p.name.as_str()).collect();
    if let Some(extra) = values.keys().find(|k| !names.contains(&k.as_str())) {
        return Err(format!("{extra}: not a swept parameter (swept: {})", names.join(", ")));
    }
    swept
        .iter()
        .map(|p| {
            let v = *values.get(&p.name).ok_or_else(|| format!("{}: give a value for every swept parameter (swept: {})", p.name, names.join(", ")))?;
            let (lo, hi) = p.values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
            if v >= lo && v <= hi { Ok(v) } else { Err(format!("{} = {v} is outside the sweep's values {lo} to {hi}: a ROM is only interpolated between design points", p.name)) }
        })
        .collect()
}

/// The design points of several parameters: their full grid, the first parameter varying
/// slowest (as nested loops in the order given). Each point lists one value per parameter.
/// A bad grid is a [`Setting::Set`] error, named as each front end spells it.
pub fn grid(parameters: &[Parameter]) -> Result<Vec<Vec<f64>>, StudyError> {
    let bad = |message: String| Err(StudyError::Option { option: Setting::Set, message });
    for (k, p) in parameters.iter().enumerate() {
        if parameters[..k].iter().any(|q| q.name == p.name) {
            return bad(format!("{}: the variable is given twice", p.name));
        }
    }
    let total = parameters.iter().try_fold(1usize, |n, p| n.checked_mul(p.values.len()).filter(|&n| n <= MAX_POINTS));
    let Some(total) = total else { return bad(format!("the grid has more than romdyn's limit of {MAX_POINTS} design points")) };
    if parameters.is_empty() {
        return bad("a sweep needs at least one variable, NAME=A:B:N or NAME=V1,V2,…".into());
    }
    let mut points = Vec::with_capacity(total);
    for k in 0..total {
        let mut rest = k;
        let mut point = vec![0.0; parameters.len()];
        for (j, p) in parameters.iter().enumerate().rev() {
            point[j] = p.values[rest % p.values.len()];
            rest /= p.values.len();
        }
        points.push(point);
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linspace_list_and_grid_order() {
        let l: Parameter = "L=0.5:2:4".parse().unwrap();
        assert_eq!(l.values, vec![0.5, 1.0, 1.5, 2.0]);
        let m: Parameter = "M=1,2".parse().unwrap();
        assert_eq!(m.values, vec![1.0, 2.0]);
        let g = grid(&[l, m]).unwrap();
        assert_eq!(g.len(), 8);
        assert_eq!(g[0], vec![0.5, 1.0]);
        assert_eq!(g[1], vec![0.5, 2.0]);
        assert_eq!(g[7], vec![2.0, 2.0]);
    }

    #[test]
    fn bad_specifications_are_named() {
        for (s, part) in [("L", "expected NAME"), ("L=1:2", "A:B:N"), ("L=1:2:0", "at least 1"), ("L=a,2", "'a' is not a number"), ("1L=2", "not a variable name"), ("L=1:2:1", "1 point"), ("L=inf,1", "finite")] {
            let e = s.parse::<Parameter>().unwrap_err();
            assert!(e.contains(part), "{s}: {e}");
        }
        let l: Parameter = "L=1,2".parse().unwrap();
        assert_eq!(grid(&[l.clone(), l]).unwrap_err().to_string(), "--set: L: the variable is given twice");
        assert!(grid(&["A=0:1:100000".parse().unwrap(), "B=0:1:100000".parse().unwrap()]).unwrap_err().to_string().contains("limit"));
    }

    #[test]
    fn an_interpolation_point_names_every_swept_parameter_within_its_values() {
        let swept: Vec<Parameter> = vec!["L=1:2:3".parse().unwrap(), "M=1,3".parse().unwrap()];
        let at = |s: &[&str]| interpolation_point(&swept, &s.iter().map(|x| x.parse().unwrap()).collect::<Vec<_>>());
        assert_eq!(at(&["M=2", "L=1.25"]).unwrap(), vec![1.25, 2.0]);
        assert!(at(&["L=1.25"]).unwrap_err().contains("M: give a value for every swept parameter"));
        assert!(at(&["L=1.25", "M=2", "K=1"]).unwrap_err().contains("K: not a swept parameter"));
        assert!(at(&["L=2.5", "M=2"]).unwrap_err().contains("L = 2.5 is outside the sweep's values 1 to 2"));
    }
}
