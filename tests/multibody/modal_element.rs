//! MBDyn's `modal` joint (issue 35): a flexible body from a FEM file, its Jacobian against
//! finite differences, and its frequencies and motion against closed forms. The FEM files
//! are written by the tests from the closed forms they check (Euler–Bernoulli beams,
//! point masses on springs).

use crate::common;

use std::fmt::Write;
use std::path::Path;

use common::cli::{temp_dir, write_file};
use romdyn::analysis::Reference;
use romdyn::dae::{check_jacobians, Assembler, State};
use romdyn::eigen::ModeKind;
use romdyn::model::ConstraintForm;
use romdyn::study::{EigenSettings, Linearization, Study};

/// A FEM node: label, position [m], lumped mass [kg] and rotational inertias [kg m²].
struct FemNode {
    label: String,
    x: [f64; 3],
    mass: f64,
    inertia: [f64; 3],
}

/// The text of a FEM file (input manual, §FEM File Format): `shapes[mode][node]` six
/// components, modal mass and stiffness `modes × modes`.
fn fem_text(nodes: &[FemNode], shapes: &[Vec<[f64; 6]>], mass: &[Vec<f64>], stiffness: &[Vec<f64>]) -> String {
    let mut t = String::new();
    let modes = shapes.len();
    writeln!(t, "** RECORD GROUP 1, HEADER\n**   REVISION.  NODES.  NORMAL.  ATTACHMENT  CONSTRAINT  REJECTED.\nREV0 {} {modes} 0 0 0", nodes.len()).unwrap();
    writeln!(t, "** RECORD GROUP 2, FINITE ELEMENT NODE LIST").unwrap();
    writeln!(t, "{}", nodes.iter().map(|n| n.label.clone()).collect::<Vec<_>>().join(" ")).unwrap();
    for (k, axis) in ["X", "Y", "Z"].iter().enumerate() {
        writeln!(t, "** RECORD GROUP {}, NODAL {axis} COORDINATES", 5 + k).unwrap();
        for n in nodes {
            writeln!(t, "{:e}", n.x[k]).unwrap();
        }
    }
    writeln!(t, "** RECORD GROUP 8, MODE SHAPES").unwrap();
    for (m, shape) in shapes.iter().enumerate() {
        writeln!(t, "**    NORMAL MODE SHAPE #  {}", m + 1).unwrap();
        for s in shape {
            writeln!(t, "{:e} {:e} {:e} {:e} {:e} {:e}", s[0], s[1], s[2], s[3], s[4], s[5]).unwrap();
        }
    }
    for (record, what, matrix) in [(9, "MODAL MASS MATRIX", mass), (10, "MODAL STIFFNESS MATRIX", stiffness)] {
        writeln!(t, "** RECORD GROUP {record}, {what}").unwrap();
        for row in matrix {
            writeln!(t, "{}", row.iter().map(|v| format!("{v:e}")).collect::<Vec<_>>().join(" ")).unwrap();
        }
    }
    writeln!(t, "** RECORD GROUP 11, DIAGONAL OF LUMPED MASS MATRIX").unwrap();
    for n in nodes {
        writeln!(t, "{:e} {:e} {:e} {:e} {:e} {:e}", n.mass, n.mass, n.mass, n.inertia[0], n.inertia[1], n.inertia[2]).unwrap();
    }
    writeln!(t, "** END OF FILE").unwrap();
    t
}

fn diagonal(values: &[f64]) -> Vec<Vec<f64>> {
    (0..values.len()).map(|i| (0..values.len()).map(|j| if i == j { values[i] } else { 0.0 }).collect()).collect()
}

/// An MBDyn file with the given nodes and elements (initial value, `final_time`, step `dt`).
fn mbdyn_file(nodes: &str, elements: &str, final_time: f64, dt: f64, counts: &str) -> String {
    format!(
        "begin: data; problem: initial value; end: data;\n\
         begin: initial value; initial time: 0.; final time: {final_time:e}; time step: {dt:e};\n\
         tolerance: 1e-10; max iterations: 20; method: ms, 0.6; end: initial value;\n\
         begin: control data; {counts} end: control data;\n\
         begin: nodes;\n{nodes}\nend: nodes;\nbegin: elements;\n{elements}\nend: elements;\n"
    )
}

/// The dynamic eigenvalues' imaginary parts > 0 [rad/s], ascending.
fn frequencies(file: &Path) -> Vec<f64> {
    let lin = Linearization { reference: Reference::Initial, inputs: vec![], outputs: vec![] };
    let study = Study::from_model_file(file, &lin, EigenSettings::default()).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    let mut im: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda.im).collect();
    im.sort_by(f64::total_cmp);
    im
}

/// A small body with everything the invariants have: three FEM nodes off the axes with
/// rotational inertias, two coupled modes with translations and rotations at every node.
fn irregular_body() -> String {
    let nodes = [
        FemNode { label: "A".into(), x: [0.0, 0.0, 0.0], mass: 2.0, inertia: [0.1, 0.2, 0.15] },
        FemNode { label: "B".into(), x: [0.8, 0.1, -0.05], mass: 1.5, inertia: [0.05, 0.07, 0.06] },
        FemNode { label: "C".into(), x: [0.3, -0.4, 0.2], mass: 1.0, inertia: [0.02, 0.03, 0.04] },
    ];
    let shapes = vec![
        vec![[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.1, 0.6, -0.2, 0.3, -0.1, 0.5], [-0.3, 0.2, 0.4, -0.2, 0.4, 0.1]],
        vec![[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.5, -0.2, 0.3, 0.1, 0.6, -0.3], [0.2, 0.5, -0.1, 0.3, 0.2, -0.4]],
    ];
    fem_text(&nodes, &shapes, &[vec![1.2, 0.1], vec![0.1, 0.9]], &[vec![400.0, 20.0], vec![20.0, 900.0]])
}

#[test]
fn modal_joint_jacobian_matches_finite_differences() {
    let dir = temp_dir("modal-jacobian");
    write_file(&dir, "body.fem", &irregular_body());
    let nodes = "structural: 1, modal, 0.1, -0.2, 0.3, euler123, 0.2, -0.1, 0.4, 0.3, 0.1, -0.2, 0.5, -1.2, 2.0;\n\
                 structural: 2, dynamic, reference, global, 0.1, -0.2, 0.3, euler123, 0.2, -0.1, 0.4, null, null;";
    for (modal, invariant_9) in [("1", ""), ("1", "use invariant 9,"), ("clamped, position, 0.1, -0.2, 0.3, orientation, euler123, 0.2, -0.1, 0.4", "")] {
        let elements = format!(
            "gravity: uniform, 0.3, -1., -9.81, const, 1.;\n\
             body: 3, 2, 0.5, null, eye;\n\
             joint: 10, modal, {modal}, 2, from file, rayleigh damping, 0.1, 0.002, \"body.fem\", {invariant_9}\n\
             origin node, \"A\", 1, \"B\", 2, 0.8, 0.1, -0.05;"
        );
        let counts = "structural nodes: 2; rigid bodies: 1; joints: 1; gravity;";
        let file = write_file(&dir, "m.mbd", &mbdyn_file(nodes, &elements, 1.0, 1e-3, counts));
        let m = romdyn::input::mbdyn::read_model(Path::new(&file)).unwrap_or_else(|e| panic!("{e}"));
        for form in [ConstraintForm::Plain, ConstraintForm::Scaled] {
            let asm = Assembler::new(&m.model);
            let mut st = State::initial(&m.model, &asm.dofs);
            let mut noise = common::fixtures::Noise(17);
            for x in st.y.iter_mut().chain(st.yp.iter_mut()) {
                *x += 0.3 * noise.next();
            }
            let checks = check_jacobians(&asm, &st, 0.37, form);
            assert!(checks.iter().any(|c| c.element.contains("modal")), "{modal}: the modal joint's entries were not compared");
            // 1e-7: central differences on smooth elements give about 1e-9 (analysis::check).
            for c in &checks {
                assert!(c.within(1e-7), "{modal} {invariant_9} {form:?}: {c:?}");
            }
        }
    }
}
