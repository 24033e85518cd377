//! The model namespace's calls inside an expression (modelns.cc; input manual, "General",
//! §Model namespace): `model::sf::NAME(x [, order])` and the other `model::…` functions,
//! evaluated against the state, drives and scalar functions the [`Evaluator`] was given.

use crate::mbdyn::syntax::diagnostic::Span;
use crate::mbdyn::syntax::value::TypedValue;
use crate::mbdyn::syntax::model_namespace;
use super::{Evaluator, MbdynError};

impl Evaluator<'_> {
    /// `model::NAME…` other than `model::sf::` (modelns.cc): the state functions, the
    /// structural nodes' private data, `model::drive`; the rest is refused by name.
    pub(super) fn model_function(&mut self, name: &str, span: Span) -> Result<TypedValue, MbdynError> {
        let what = format!("model::{name}");
        let no_reads = |e: &Self| e.err(span, format!("{what} reads the model's state, which is not available here"));
        let real = |e: &Self, v: &TypedValue| v.real().ok_or_else(|| e.err(span, format!("{what} takes numbers, found a string")));
        if model_namespace::is_previous_step(name) {
            let Some(previous) = self.previous else {
                return Err(self.err(span, format!("{what} reads the previous time step's state, which romdyn keeps only for a driven element's hints: not supported here")));
            };
            let stem = name.trim_end_matches("_prev");
            let n = model_namespace::arity(stem).unwrap_or(1);
            let args = self.arguments(&what, span)?;
            if args.len() != n {
                return Err(self.err(span, format!("{what} takes {n} node label(s), found {} argument(s)", args.len())));
            }
            let labels = args.iter().map(|a| real(self, a)).collect::<Result<Vec<f64>, _>>()?;
            return model_namespace::state_function(stem, &labels, previous).map(TypedValue::Real).map_err(self.at(span));
        }
        if let Some(n) = model_namespace::arity(name) {
            let args = self.arguments(&what, span)?;
            if args.len() != n {
                return Err(self.err(span, format!("{what} takes {n} node label(s), found {} argument(s)", args.len())));
            }
            let labels = args.iter().map(|a| real(self, a)).collect::<Result<Vec<f64>, _>>()?;
            let reads = self.reads.ok_or_else(|| no_reads(self))?;
            return model_namespace::state_function(name, &labels, reads).map(TypedValue::Real).map_err(self.at(span));
        }
        match name {
            "node" => {
                let kind = if self.eat("::") { self.word(0).map(str::to_string) } else { None };
                if kind.as_deref() != Some("structural") {
                    return Err(self.err(span, "model::node:: reads structural nodes only in romdyn: expected model::node::structural(LABEL, \"NAME[i]\")"));
                }
                self.pos += 1;
                let what = "model::node::structural";
                let args = self.arguments(what, span)?;
                let [label, TypedValue::Str(data)] = &args[..] else {
                    return Err(self.err(span, format!("{what} takes a node label and a private data name in double quotes, e.g. (1, \"X[3]\")")));
                };
                let label = real(self, label)?;
                let reads = self.reads.ok_or_else(|| no_reads(self))?;
                model_namespace::node_private_data(label, data, reads).map(TypedValue::Real).map_err(self.at(span))
            }
            "drive" => {
                // `model::drive(LABEL [, x])`: without x (modelns.cc of MBDyn's development
                // version; 1.7.3 needs x) the drive at the current time, 0 while reading.
                let args = self.arguments(&what, span)?;
                if !(1..=2).contains(&args.len()) {
                    return Err(self.err(span, format!("{what} takes a drive caller label and its optional argument, found {} argument(s)", args.len())));
                }
                let label = real(self, &args[0])?;
                let x = match args.get(1) {
                    Some(x) => real(self, x)?,
                    None => self.state.map_or(0.0, |s| s.time()),
                };
                let (Some(table), Some(reads)) = (self.drives, self.reads) else {
                    return Err(self.err(span, "model::drive: romdyn calls drive callers in string drives only"));
                };
                model_namespace::drive(table, label, x, reads, self.state).map(TypedValue::Real).map_err(self.at(span))
            }
            "element" => {
                // modelns.cc `model_elem`: `model::element::TYPE(LABEL, "NAME")`.
                let kind = if self.eat("::") { self.word(0).map(str::to_string) } else { None };
                let Some(kind) = kind else {
                    return Err(self.err(span, "model::element:: expects an element type, e.g. model::element::body(LABEL, \"E\")"));
                };
                self.pos += 1;
                let what = format!("model::element::{kind}");
                let args = self.arguments(&what, span)?;
                let [label, TypedValue::Str(data)] = &args[..] else {
                    return Err(self.err(span, format!("{what} takes an element label and a private data name in double quotes, e.g. (1, \"E\")")));
                };
                let label = real(self, label)?;
                if let Some(run) = self.run_elements {
                    // A string drive: the element's datum at the state of the evaluation.
                    return super::element_calls::string_read(&kind, label, data, run).map(TypedValue::Real).map_err(self.at(span));
                }
                let Some(elements) = self.elements else {
                    return Err(self.err(span, format!("{what}: romdyn reads an element's private data while it reads the file ('const', 'set:', a card's numbers) and in string drives of the input file, not here")));
                };
                let reads = self.reads.ok_or_else(|| no_reads(self))?;
                model_namespace::element_private_data(&kind, label, data, elements, reads).map(TypedValue::Real).map_err(self.at(span))
            }
            "current" => {
                // modelns.cc `model_curr`: a name the card being read publishes (see
                // [`super::Deferred`]).
                let args = self.arguments(&what, span)?;
                let [TypedValue::Str(data)] = &args[..] else {
                    return Err(self.err(span, "model::current takes the name of a datum in double quotes, e.g. model::current(\"L\")"));
                };
                match self.current.iter().find(|(n, _)| n == data) {
                    Some((_, v)) => Ok(TypedValue::Real(*v)),
                    None if self.current.is_empty() => Err(self.err(span, format!("model::current(\"{data}\") is not defined here: MBDyn publishes \"L\" while it reads a distance joint's drive, and \"L0\" and \"L\" while it reads a rod's constitutive law"))),
                    None => {
                        let names = self.current.iter().map(|(n, _)| format!("\"{n}\"")).collect::<Vec<_>>().join(" and ");
                        Err(self.err(span, format!("model::current(\"{data}\") is not defined: this part of the card publishes {names}")))
                    }
                }
            }
            "drivep" => Err(self.err(span, "model::drivep (a drive caller's derivative) is not supported by romdyn (MBDyn 1.7.3 runs it)")),
            _ => Err(self.err(span, format!("unknown function '{what}' of the model namespace"))),
        }
    }

    /// `model::sf::NAME(x [, order])`: the scalar function `NAME` at `x` (order 0), or its
    /// derivative (order 1), as modelns.cc's `model_sf`.
    pub(super) fn scalar_function(&mut self, name: &str, span: Span) -> Result<TypedValue, MbdynError> {
        let what = format!("model::sf::{name}");
        let Some(functions) = self.functions else {
            return Err(self.err(span, format!("{what}: romdyn calls scalar functions in string drives only (it evaluates 'set:' while reading, before the scalar function cards)")));
        };
        let Some((f, _)) = functions.get(name) else {
            return Err(self.err(span, format!("{what}: scalar function \"{name}\" is not defined before this drive")));
        };
        if !self.eat("(") {
            return Err(self.err(span, format!("{what}: expected '(' and the function's argument")));
        }
        let x = self.statements()?;
        let order = if self.eat(",") { Some(self.statements()?) } else { None };
        if !self.eat(")") {
            return Err(self.err(span, format!("{what} takes an argument and an optional derivative order: expected ')'")));
        }
        let x = x.real().ok_or_else(|| self.err(span, format!("{what} takes a number, found a string")))?;
        let (value, derivative) = f.value_and_derivative(x);
        Ok(TypedValue::Real(match order.map(|o| o.real()) {
            None => value,
            Some(Some(o)) if o == 0.0 => value,
            Some(Some(o)) if o == 1.0 => derivative,
            _ => return Err(self.err(span, format!("{what}: the derivative order must be 0 or 1, as in MBDyn"))),
        }))
    }
}
