//! Typed values of MBDyn's math parser (input manual, "General", §Numeric Values): `bool`,
//! `integer`, `real` and `string`. Operations between integers (and bools) stay integer,
//! so `1/3` is 0 and `1./3` is real; a value assigned to a typed variable is cast to its
//! type (`set: integer n = 7/2.;` stores 3).

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum TypedValue {
    Bool(bool),
    Int(i64),
    Real(f64),
    Str(String),
}

/// A variable's declared type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    Bool,
    Integer,
    Real,
    String,
}

impl Type {
    pub fn from_name(name: &str) -> Option<Type> {
        match name {
            "bool" => Some(Type::Bool),
            "integer" => Some(Type::Integer),
            "real" => Some(Type::Real),
            "string" => Some(Type::String),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Type::Bool => "bool",
            Type::Integer => "integer",
            Type::Real => "real",
            Type::String => "string",
        }
    }
    /// The value of a declared but unassigned variable.
    pub fn zero(self) -> TypedValue {
        match self {
            Type::Bool => TypedValue::Bool(false),
            Type::Integer => TypedValue::Int(0),
            Type::Real => TypedValue::Real(0.0),
            Type::String => TypedValue::Str(String::new()),
        }
    }
}

impl fmt::Display for TypedValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TypedValue::Bool(b) => write!(f, "{}", u8::from(*b)),
            TypedValue::Int(i) => write!(f, "{i}"),
            TypedValue::Real(x) => write!(f, "{x}"),
            TypedValue::Str(s) => write!(f, "\"{s}\""),
        }
    }
}

impl TypedValue {
    pub fn type_of(&self) -> Type {
        match self {
            TypedValue::Bool(_) => Type::Bool,
            TypedValue::Int(_) => Type::Integer,
            TypedValue::Real(_) => Type::Real,
            TypedValue::Str(_) => Type::String,
        }
    }

    /// The numeric value; `None` for strings.
    pub fn real(&self) -> Option<f64> {
        match self {
            TypedValue::Bool(b) => Some(f64::from(u8::from(*b))),
            TypedValue::Int(i) => Some(*i as f64),
            TypedValue::Real(x) => Some(*x),
            TypedValue::Str(_) => None,
        }
    }

    fn integer(&self) -> Option<i64> {
        match self {
            TypedValue::Bool(b) => Some(i64::from(*b)),
            TypedValue::Int(i) => Some(*i),
            _ => None,
        }
    }

    pub fn truth(&self) -> Result<bool, String> {
        self.real().map(|x| x != 0.0).ok_or_else(|| "a string has no truth value".into())
    }

    /// Converts to type `t` (MBDyn's cast: reals truncate toward zero into integers).
    pub fn cast(&self, t: Type) -> Result<TypedValue, String> {
        if let TypedValue::Str(s) = self {
            return match t {
                Type::String => Ok(TypedValue::Str(s.clone())),
                _ => Err(format!("cannot cast the string \"{s}\" into {}", t.name())),
            };
        }
        let x = self.real().unwrap_or(0.0);
        Ok(match t {
            Type::Bool => TypedValue::Bool(x != 0.0),
            Type::Integer => TypedValue::Int(self.integer().unwrap_or(x.trunc() as i64)),
            Type::Real => TypedValue::Real(x),
            Type::String => TypedValue::Str(match self {
                TypedValue::Real(x) => format!("{x:e}"),
                other => other.to_string(),
            }),
        })
    }

    /// `+ - * / %`; integers (and bools) stay integer, anything with a real is real, `+`
    /// concatenates strings.
    pub fn arithmetic(&self, op: &str, rhs: &TypedValue) -> Result<TypedValue, String> {
        if let (TypedValue::Str(a), "+") = (self, op) {
            let b = match rhs {
                TypedValue::Str(b) => b.clone(),
                TypedValue::Real(x) => format!("{x:e}"),
                other => other.to_string(),
            };
            return Ok(TypedValue::Str(format!("{a}{b}")));
        }
        if let (Some(a), Some(b)) = (self.integer(), rhs.integer()) {
            let r = match op {
                "+" => a.checked_add(b),
                "-" => a.checked_sub(b),
                "*" => a.checked_mul(b),
                "/" | "%" if b == 0 => return Err("division by zero".into()),
                "/" => a.checked_div(b),
                _ => a.checked_rem(b),
            };
            return r.map(TypedValue::Int).ok_or_else(|| format!("integer overflow in {a} {op} {b}"));
        }
        let (Some(a), Some(b)) = (self.real(), rhs.real()) else {
            return Err(format!("operator '{op}' does not apply to strings"));
        };
        Ok(TypedValue::Real(match op {
            "+" => a + b,
            "-" => a - b,
            "*" => a * b,
            "/" | "%" if b == 0.0 => return Err("division by zero".into()),
            "/" => a / b,
            _ => a % b,
        }))
    }

    /// `^`: integer when both are integers and the exponent is not negative.
    /// `self ^ rhs` as MBDyn 1.7.3 computes it (mathp.cc `power_int`): a negative base with an
    /// exponent ≤ 0 is refused; two integers give an integer by products, 1 for a zero
    /// exponent and 0 for a negative one (`2^-1` = 0, `1^-1` = 0); otherwise `pow` of reals.
    pub fn power(&self, rhs: &TypedValue) -> Result<TypedValue, String> {
        let (Some(a), Some(b)) = (self.real(), rhs.real()) else {
            return Err("operator '^' does not apply to strings".into());
        };
        if a < 0.0 && b <= 0.0 {
            return Err(format!("a negative base raised to an exponent <= 0 ({a}^{b}): MBDyn 1.7.3 refuses it too (\"invalid operands in power()\")"));
        }
        if let (Some(a), Some(b)) = (self.integer(), rhs.integer()) {
            return match b {
                0 => Ok(TypedValue::Int(1)),
                b if b < 0 => Ok(TypedValue::Int(0)),
                b => u32::try_from(b).ok().and_then(|b| a.checked_pow(b)).map(TypedValue::Int).ok_or_else(|| format!("integer overflow in {a}^{b}")),
            };
        }
        if a == 0.0 && b < 0.0 {
            return Err("division by zero (0 raised to a negative power)".into());
        }
        Ok(TypedValue::Real(a.powf(b)))
    }

    pub fn negate(&self) -> Result<TypedValue, String> {
        match self {
            TypedValue::Bool(b) => Ok(TypedValue::Int(-i64::from(*b))),
            TypedValue::Int(i) => i.checked_neg().map(TypedValue::Int).ok_or_else(|| "integer overflow".into()),
            TypedValue::Real(x) => Ok(TypedValue::Real(-x)),
            TypedValue::Str(_) => Err("unary '-' does not apply to strings".into()),
        }
    }

    /// `> >= == <= < !=`, compared as reals (strings compare as text).
    pub fn compare(&self, op: &str, rhs: &TypedValue) -> Result<TypedValue, String> {
        let ord = match (self, rhs) {
            (TypedValue::Str(a), TypedValue::Str(b)) => a.partial_cmp(b),
            _ => match (self.real(), rhs.real()) {
                (Some(a), Some(b)) => a.partial_cmp(&b),
                _ => return Err(format!("cannot compare a string and a number with '{op}'")),
            },
        };
        use std::cmp::Ordering::*;
        let r = match (op, ord) {
            (_, None) => op == "!=",
            (">", Some(o)) => o == Greater,
            (">=", Some(o)) => o != Less,
            ("==", Some(o)) => o == Equal,
            ("<=", Some(o)) => o != Greater,
            ("<", Some(o)) => o == Less,
            (_, Some(o)) => o != Equal,
        };
        Ok(TypedValue::Bool(r))
    }
}
