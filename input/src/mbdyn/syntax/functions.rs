//! The math parser's built-in functions and predefined constants (input manual, "General",
//! tables "Built-in mathematical functions" and "Predefined variables and constants").
//! Functions that print, stop the run, draw random numbers or format strings are not
//! supported: romdyn reads a model, it does not run scripts.

use super::value::TypedValue;

/// Functions romdyn evaluates, with their number of arguments.
pub const FUNCTIONS: [(&str, usize); 38] = [
    ("abs", 1), ("acos", 1), ("acosh", 1), ("actan", 1), ("actan2", 2), ("actanh", 1), ("asin", 1), ("asinh", 1),
    ("atan", 1), ("atan2", 2), ("atanh", 1), ("ceil", 1), ("copysign", 2), ("cos", 1), ("cosh", 1), ("ctan", 1),
    ("ctanh", 1), ("exp", 1), ("floor", 1), ("in_ee", 3), ("in_el", 3), ("in_le", 3), ("in_ll", 3), ("log", 1),
    ("log10", 1), ("max", 2), ("min", 2), ("par", 1), ("ramp", 1), ("round", 1), ("sign", 1), ("sin", 1),
    ("sinh", 1), ("sqrt", 1), ("sramp", 2), ("step", 1), ("tan", 1), ("tanh", 1),
];

/// Built-in functions of MBDyn that romdyn deliberately does not evaluate.
pub const UNSUPPORTED_FUNCTIONS: [&str; 6] = ["print", "rand", "random", "seed", "sprintf", "stop"];

/// Whether `name` is a built-in function (supported or not): such names cannot be variables.
pub fn is_function(name: &str) -> bool {
    FUNCTIONS.iter().any(|(f, _)| *f == name) || UNSUPPORTED_FUNCTIONS.contains(&name)
}

/// The predefined constants, all `const`.
pub fn constants() -> Vec<(&'static str, TypedValue)> {
    use std::f64::consts::{E, PI};
    let r = TypedValue::Real;
    vec![
        ("pi", r(PI)),
        ("e", r(E)),
        ("TRUE", TypedValue::Bool(true)),
        ("FALSE", TypedValue::Bool(false)),
        ("INT_MAX", TypedValue::Int(i32::MAX as i64)),
        ("INT_MIN", TypedValue::Int(i32::MIN as i64)),
        ("RAND_MAX", TypedValue::Int(i32::MAX as i64)),
        ("REAL_MAX", r(f64::MAX)),
        ("REAL_MIN", r(f64::MIN_POSITIVE)),
        ("in2m", r(0.0254)),
        ("m2in", r(1.0 / 0.0254)),
        ("in2mm", r(25.4)),
        ("mm2in", r(1.0 / 25.4)),
        ("ft2m", r(0.3048)),
        ("m2ft", r(1.0 / 0.3048)),
        ("lb2kg", r(0.45359237)),
        ("kg2lb", r(1.0 / 0.45359237)),
        ("deg2rad", r(PI / 180.0)),
        ("rad2deg", r(180.0 / PI)),
        ("slug2kg", r(14.5939)),
        ("kg2slug", r(1.0 / 14.5939)),
    ]
}

/// Evaluates built-in `name` on real arguments (the caller checked the count); the error
/// says why the argument is out of the function's domain.
pub fn call(name: &str, a: &[f64]) -> Result<TypedValue, String> {
    let x = a.first().copied().unwrap_or(0.0);
    let domain = |ok: bool, rule: &str| if ok { Ok(()) } else { Err(format!("{name}({x}): argument out of domain ({rule})")) };
    let real = TypedValue::Real;
    let v = match name {
        "abs" => real(x.abs()),
        "acos" | "asin" => {
            domain(x.abs() <= 1.0, "|x| must not exceed 1")?;
            real(if name == "acos" { x.acos() } else { x.asin() })
        }
        "acosh" => {
            domain(x >= 1.0, "x must be at least 1")?;
            real(x.acosh())
        }
        "actan" => real(1f64.atan2(x)),
        "actan2" => real(a[1].atan2(x)),
        "actanh" => {
            domain(x.abs() > 1.0, "|x| must exceed 1")?;
            real((1.0 / x).atanh())
        }
        "asinh" => real(x.asinh()),
        "atan" => real(x.atan()),
        "atan2" => real(x.atan2(a[1])),
        "atanh" => {
            domain(x.abs() < 1.0, "|x| must be less than 1")?;
            real(x.atanh())
        }
        "ceil" => TypedValue::Int(x.ceil() as i64),
        "copysign" => real(x.copysign(a[1])),
        "cos" => real(x.cos()),
        "cosh" => real(x.cosh()),
        "ctan" => {
            domain(x.tan() != 0.0, "tan(x) must not be zero")?;
            real(1.0 / x.tan())
        }
        "ctanh" => {
            domain(x != 0.0, "x must not be zero")?;
            real(1.0 / x.tanh())
        }
        "exp" => real(x.exp()),
        "floor" => TypedValue::Int(x.floor() as i64),
        "in_ee" => TypedValue::Bool(x <= a[1] && a[1] <= a[2]),
        "in_el" => TypedValue::Bool(x <= a[1] && a[1] < a[2]),
        "in_le" => TypedValue::Bool(x < a[1] && a[1] <= a[2]),
        "in_ll" => TypedValue::Bool(x < a[1] && a[1] < a[2]),
        "log" | "log10" => {
            domain(x > 0.0, "x must be positive")?;
            real(if name == "log" { x.ln() } else { x.log10() })
        }
        "max" => real(x.max(a[1])),
        "min" => real(x.min(a[1])),
        "par" => real(if x > 0.0 { x * x } else { 0.0 }),
        "ramp" => real(x.max(0.0)),
        "round" => TypedValue::Int(x.round() as i64),
        "sign" => TypedValue::Int(if x == 0.0 { 0 } else { x.signum() as i64 }),
        "sin" => real(x.sin()),
        "sinh" => real(x.sinh()),
        "sqrt" => {
            domain(x >= 0.0, "x must not be negative")?;
            real(x.sqrt())
        }
        "sramp" => real(if x < 0.0 {
            0.0
        } else if x > a[1] {
            a[1]
        } else {
            x
        }),
        "step" => real(if x > 0.0 {
            1.0
        } else if x < 0.0 {
            0.0
        } else {
            0.5
        }),
        "tan" => real(x.tan()),
        "tanh" => real(x.tanh()),
        _ => return Err(format!("function '{name}' is not supported by romdyn (MBDyn 1.7.3 runs it)")),
    };
    Ok(v)
}
