//! Beam internal forces: at a static solution against statics, and written by `romdyn run`
//! in MBDyn's `.act` layout (with romdyn's `.bst` strains).

use crate::common;

use common::beams::{simply_supported, TABLE3};
use common::cli::{example_variant, listing, romdyn_at, temp_dir, write_file};
use common::rel;
use romdyn::dae::{Assembler, State};
use romdyn::solve::{static_solution, NewtonSettings};

#[test]
fn internal_forces_at_the_evaluation_points_match_statics() {
    // Simply supported beam, force F up at mid-span (4 elements): the structure is
    // statically determinate, so at abscissa x of an evaluation point the shear force is
    // F/2 and the bending moment M_z = −F x/2 (x < L/2) or −F (L − x)/2 (curvature v″ < 0);
    // the finite-volume beam evaluates them exactly (1e-8 relative; a small F keeps the
    // section rotations, which tilt the shear force by cos φ, below 1e-6 rad).
    let f = 0.01;
    let model = simply_supported(&TABLE3, 4, 0.0, f);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings { tolerance: 1e-10, ..NewtonSettings::default() }).unwrap();
    let beams = asm.section_states(&st);
    assert_eq!(beams.len(), 4);
    for (_, sections) in &beams {
        for s in sections {
            let x = s.position.x;
            let arm = x.min(TABLE3.length - x);
            let moment = -f * arm / 2.0;
            assert!(rel(s.moment.z, moment) < 1e-8, "x = {x}: M_z {} against {moment}", s.moment.z);
            assert!(rel(s.force.y.abs(), f / 2.0) < 1e-8, "x = {x}: shear {}", s.force.y);
            assert!(rel(s.curvature.z, moment / TABLE3.ej) < 1e-8);
        }
    }
}

#[test]
fn run_writes_act_and_bst_with_a_line_per_beam_and_instant() {
    let dir = temp_dir("beam-act");
    let text = example_variant("cantilever.mbd", &[("    final time: 0.1;", "    final time: 1.e-3;"), ("    eigenanalysis: 0.1, output matrices, use lapack;\n", "")]);
    let file = write_file(&dir, "cantilever.mbd", &text);
    let (ok, _, err) = romdyn_at(&dir, &["run", &file]);
    assert!(ok, "{err}");
    let files = listing(&dir);
    assert!(files.contains(&"cantilever.act".to_string()) && files.contains(&"cantilever.bst".to_string()), "{files:?}");
    for ext in ["act", "bst"] {
        let body = std::fs::read_to_string(dir.join(format!("cantilever.{ext}"))).unwrap();
        let lines: Vec<&str> = body.lines().collect();
        // 10 beams × 11 instants (the initial state and 10 steps of 1e-4 s).
        assert_eq!(lines.len(), 10 * 11, "{ext}");
        for l in &lines {
            let cols: Vec<f64> = l.split_whitespace().map(|c| c.parse().unwrap()).collect();
            assert_eq!(cols.len(), 13, "{ext}: label and 2 x 6 values: {l}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
