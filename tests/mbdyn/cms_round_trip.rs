//! Component mode synthesis round trip (issue 35 point 3): `tests/mbdyn_files/cms_substructure.mbd`
//! (the outer half of the cantilever `cms_cantilever.mbd`) reduced by `romdyn::cms` with N
//! fixed-interface modes and node 9's six constraint modes, written as a FEM file, read
//! back by romdyn's modal joint in `cms_reduced.mbd` (the inner half as beams), against the
//! whole cantilever's modes.

use crate::common;

use common::mbdyn::test_file;
use romdyn::analysis::Reference;
use romdyn::cms::{craig_bampton, CmsRequest};
use romdyn::eigen::ModeKind;
use romdyn::study::{StudySource, Study};

/// The lowest `count` natural frequencies [rad/s] of an MBDyn file.
fn lowest(path: &std::path::Path, count: usize) -> Vec<f64> {
    let study = Study::builder(StudySource::model_file(path)).reference(Reference::Initial).build().unwrap_or_else(|e| panic!("{e}"));
    let mut w: Vec<f64> = study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im > 1e-6).map(|m| m.lambda.im).collect();
    w.sort_by(f64::total_cmp);
    assert!(w.len() >= count, "{} modes: {w:?}", w.len());
    w.truncate(count);
    w
}

/// The reduced cantilever's lowest `count` frequencies with `n` fixed-interface modes.
fn reduced(dir: &std::path::Path, n: usize, count: usize) -> Vec<f64> {
    let sub = common::mbdyn::read_test_file("cms_substructure.mbd");
    let request = CmsRequest { interfaces: vec![9], modes: n, reference: Reference::Initial };
    let cb = craig_bampton(&sub.model, &sub.problem, &request).unwrap_or_else(|e| panic!("{e}"));
    assert!(cb.warnings.is_empty(), "{:?}", cb.warnings);
    cb.write(&dir.join("cms_substructure.fem"), "cms_substructure.mbd").unwrap_or_else(|e| panic!("{e}"));
    let text = std::fs::read_to_string(test_file("cms_reduced.mbd")).unwrap().replace("set: ifndef integer MODES = 10;", &format!("set: integer MODES = {};", n + 6));
    let path = common::cli::write_file(dir, "cms_reduced.mbd", &text);
    lowest(std::path::Path::new(&path), count)
}

/// Relative errors of the reduced cantilever's six lowest frequencies against the whole
/// beam's, per number of fixed-interface modes (measured 2026-12-06; the table of
/// docs/src/guide/cms.md):
///
/// ```text
///  N   110.64    156.11    678.89    945.60    1570.42   1570.42 rad/s
///  0   2.7e-2    2.7e-2    3.1e-1    3.0e-1    9.5e-2    9.5e-2   (Guyan)
///  1   8.3e-5    2.7e-2    7.2e-3    3.0e-1    9.5e-2    9.5e-2
///  2   8.3e-5    9.3e-5    7.2e-3    8.0e-3    9.5e-2    9.5e-2
///  4   3.9e-6    9.3e-5    4.1e-4    8.0e-3    7.1e-4    9.5e-2
///  8   5.5e-7    6.7e-7    6.8e-5    8.2e-5    7.1e-4    7.1e-4
/// 16   4.9e-8    1.6e-7    6.6e-6    2.2e-5    9.8e-6    2.3e-5
/// ```
///
/// MBDyn's finite-volume `beam3` has a stiffness that is not symmetric (its rotation–
/// translation entries differ by 18 % from their transposes), so the reduction is two-sided
/// (`src/cms/`): with one-sided (Galerkin) modes of the symmetric part the errors stalled at
/// −1.8e-4 … −1.4e-3 here and reached −12 % on examples/optical_table_*.mbd.
#[test]
fn a_craig_bampton_substructure_reproduces_the_whole_beam() {
    let dir = common::cli::temp_dir("cms-round-trip");
    const COUNT: usize = 6;
    let full = lowest(&test_file("cms_cantilever.mbd"), COUNT);
    let mut largest = Vec::new();
    for n in [0, 1, 2, 4, 8, 16] {
        let reduced = reduced(&dir, n, COUNT);
        let errors: Vec<f64> = reduced.iter().zip(&full).map(|(r, f)| (r - f) / f).collect();
        largest.push((n, errors.iter().fold(0.0f64, |a, e| a.max(e.abs()))));
        eprintln!("N = {n:>2}: {}", errors.iter().map(|e| format!("{e:+.1e}")).collect::<Vec<_>>().join("  "));
        match n {
            // MBDyn 1.7.3 on the same cms_reduced.mbd with this FEM file (MODES = 10, output
            // matrices, eigenvalues of its Aplus/Aminus by `romdyn eig --pencil`, 2026-12-06):
            // 110.6418482, 156.1265556, 679.1694177, 953.1928662, 1571.536106, 1719.322528
            // rad/s; printed to 10 digits, so 1e-8.
            4 => {
                let mbdyn = [110.6418482, 156.1265556, 679.1694177, 953.1928662, 1571.536106, 1719.322528];
                for (r, m) in reduced.iter().zip(mbdyn) {
                    assert!(common::rel(*r, m) < 1e-8, "N = 4: {r} rad/s, MBDyn 1.7.3 {m} rad/s");
                }
            }
            _ => {}
        }
        // The two bending modes converge first: within 2e-4 from N = 2 on (measured 9.3e-5).
        if n >= 2 {
            assert!(errors[..2].iter().all(|e| e.abs() < 2e-4), "N = {n}: {errors:?}");
        }
        // Above the whole beam's, as a Rayleigh–Ritz approximation's (observed here; not a
        // theorem for a non-symmetric stiffness), to the two QZ's rounding.
        assert!(errors.iter().all(|e| *e > -1e-9), "N = {n}: {errors:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
    // Convergence: the largest error over the six modes never grows with N, and falls from
    // Guyan's 0.31 to 1e-3 at N = 8 (measured 7.1e-4) and 3e-5 at N = 16 (2.3e-5).
    assert!(largest.windows(2).all(|w| w[1].1 <= w[0].1 * (1.0 + 1e-9)), "{largest:?}");
    assert!(largest[0].1 > 0.3 && largest[4].1 < 1e-3 && largest[5].1 < 3e-5, "{largest:?}");
}

#[test]
fn the_written_fem_file_reads_back_as_written() {
    let dir = common::cli::temp_dir("cms-read-back");
    let sub = common::mbdyn::read_test_file("cms_substructure.mbd");
    let request = CmsRequest { interfaces: vec![9, 17], modes: 3, reference: Reference::Initial };
    let cb = craig_bampton(&sub.model, &sub.problem, &request).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("two.fem");
    cb.write(&path, "cms_substructure.mbd").unwrap_or_else(|e| panic!("{e}"));
    let back = romdyn::input::fem::read_fem(&path).unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_dir_all(&dir).ok();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_eq!((back.nodes(), back.modes()), (9, 3 + 12));
    // Shortest round-trip numbers: every value comes back to the bit.
    assert_eq!(back.shapes, cb.fem.shapes);
    assert_eq!(back.positions, cb.fem.positions);
    assert_eq!(back.mass, cb.fem.mass);
    assert_eq!(back.stiffness, cb.fem.stiffness);
    assert_eq!(back.lumped_inertia, cb.fem.lumped_inertia);
    // Fixed-interface modes have unit modal mass; a constraint mode is a unit motion of its
    // interface coordinate and none of the other interface's (node 17's x is mode 3 + 6 + 1).
    for j in 0..3 {
        assert!((back.mass[(j, j)] - 1.0).abs() < 1e-12, "{}", back.mass[(j, j)]);
    }
    let node17 = 8;
    assert_eq!(back.shapes[9][node17], [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(back.shapes[9][0], [0.0; 6]);
    // Record 12 from M (rigid motions) against the lumped masses of record 11 (this beam's
    // masses are at its nodes, so both are exact): mass 0.5 kg (rho A = 1 kg/m over 0.5 m),
    // centre at x = 0.75 m.
    let rigid = back.rigid_inertia.clone().expect("record 12");
    let lumped = romdyn::input::fem::FemFile { rigid_inertia: None, ..back.clone() }.rigid_body_inertia().expect("record 11");
    assert!((rigid.mass - 0.5).abs() < 1e-14 && (rigid.centre_of_mass[0] - 0.75).abs() < 1e-14, "{rigid:?}");
    for a in 0..3 {
        for b in 0..3 {
            assert!((rigid.inertia[a][b] - lumped.inertia[a][b]).abs() < 1e-14, "{rigid:?} {lumped:?}");
        }
    }
}

#[test]
fn substructures_that_do_not_fit_are_refused_in_words() {
    let sub = common::mbdyn::read_test_file("cms_substructure.mbd");
    let refuse = |interfaces: Vec<u32>, modes: usize| match craig_bampton(&sub.model, &sub.problem, &CmsRequest { interfaces, modes, reference: Reference::Initial }) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(refuse(vec![4], 2).contains("structural node 4 is not defined"));
    assert!(refuse(vec![9, 9], 2).contains("listed twice"));
    assert!(refuse(vec![], 2).contains("at least one interface node"));
    assert!(refuse(vec![9], 49).contains("at most 48 fixed-interface modes"));
    let clamped = common::mbdyn::read_test_file("cms_cantilever.mbd");
    let e = craig_bampton(&clamped.model, &clamped.problem, &CmsRequest { interfaces: vec![9], modes: 1, reference: Reference::Initial }).err().expect("a joint is refused").to_string();
    assert!(e.contains("clamp 1 has unknowns of its own"), "{e}");
}
