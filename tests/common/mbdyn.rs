//! Reading MBDyn text in tests, and comparing a file's model with one built through the API.

use std::path::Path;

use romdyn::dae::{Assembler, State};
use romdyn::input::mbdyn::{build, parse_text, MbdynModel};
use romdyn::linear::ConstraintForm;
use romdyn::model::Model;

use super::fixtures::Noise;

pub fn read(text: &str) -> MbdynModel {
    parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)).unwrap_or_else(|e| panic!("{e}"))
}

pub fn variables(text: &str) -> romdyn::input::mbdyn::Variables {
    parse_text(text, Path::new("m.mbd")).unwrap_or_else(|e| panic!("{e}")).variables
}

/// A file with the given control data, nodes and elements.
pub fn file(control: &str, nodes: &str, elements: &str) -> String {
    format!("begin: data; problem: initial value; end: data;\nbegin: control data; {control} end: control data;\nbegin: nodes;\n{nodes}\nend: nodes;\nbegin: elements;\n{elements}\nend: elements;\n")
}

/// `F(y, ẏ, t)` at the initial state moved by noise (same layout for equal models).
pub fn residual(model: &Model, t: f64, seed: u64) -> Vec<f64> {
    let asm = Assembler::new(model);
    let mut st = State::initial(model, &asm.dofs);
    st.t = t;
    let mut n = Noise(seed);
    st.y.iter_mut().chain(st.yp.iter_mut()).for_each(|v| *v += 0.1 * n.next());
    asm.residual(&st, ConstraintForm::Plain, 1.0)
}

/// The model read from `text` has the residual of `expected` (same nodes and elements in the
/// same order) at three states and times, to 1e-12 relative.
pub fn assert_same_physics(text: &str, expected: Model) {
    let got = read(text).model;
    assert_eq!(got.nodes.len(), expected.nodes.len(), "node count");
    assert_eq!(got.elements.len(), expected.elements.len(), "element count");
    for (seed, t) in [(7, 0.0), (11, 0.37), (13, 2.5)] {
        let (a, b) = (residual(&got, t, seed), residual(&expected, t, seed));
        let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            assert!((x - y).abs() <= 1e-12 * scale, "t = {t}, equation {i}: read {x}, expected {y}");
        }
    }
}

