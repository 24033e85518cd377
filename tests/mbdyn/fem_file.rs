//! MBDyn's FEM file of the modal element (input manual, appendix "Modal Element Data",
//! §FEM File Format; issue 35 point 1): read as MBDyn 1.7.3 reads it, every record counted
//! against the header, bad files refused with file:line:column.

use std::path::{Path, PathBuf};

use romdyn::input::fem::{parse_fem, read_fem};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fem/three_nodes.fem")
}

fn original() -> String {
    std::fs::read_to_string(data()).unwrap()
}

#[test]
fn a_hand_made_file_reads_as_written() {
    let fem = read_fem(&data()).unwrap_or_else(|e| panic!("{e}"));
    // Header: 3 + 0 + 0 − 1 rejected = 2 modes; 3 nodes.
    assert_eq!((fem.nodes(), fem.modes()), (3, 2));
    assert_eq!(fem.node_labels, ["A1", "A2", "A3"]);
    assert_eq!(fem.positions, [[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [3.0, 0.0, 0.5]]);
    // Record 3 absent: zero; record 4 as written.
    assert_eq!(fem.modal_displacements, [0.0, 0.0]);
    assert_eq!(fem.modal_velocities, [0.5, -0.25]);
    // The rejected mode (all 9s) comes first and is dropped.
    assert_eq!(fem.shapes.len(), 2);
    assert_eq!(fem.shapes[0][1], [0.0, 0.0, 0.5, 0.0, -0.5, 0.0]);
    assert_eq!(fem.shapes[1][2], [0.0, 1.0, 0.0, 0.0, 0.0, 1.5]);
    // Matrices: entry (j, k) is the k-th value of the j-th group, as MBDyn puts them.
    assert_eq!((fem.mass[(0, 0)], fem.mass[(1, 1)], fem.mass[(0, 1)]), (2.0, 3.0, 0.0));
    assert_eq!((fem.stiffness[(0, 1)], fem.stiffness[(1, 0)], fem.stiffness[(1, 1)]), (0.25, 0.5, 27.0));
    let c = fem.damping.as_ref().expect("record 13");
    assert_eq!((c[(0, 0)], c[(1, 1)]), (0.1, 0.2));
    assert!(fem.rigid_inertia.is_none() && fem.warnings.is_empty());
    // Rigid-body inertia from the lumped masses 1, 2, 1 kg at x = 0, 1, 3 m (z = 0.5 m) and
    // nodal inertias 0.1, 0.2, 0.3 kg m² each, by hand: m = 4 kg, x_cm = 5/4 m, z_cm = 0.5 m;
    // Σ m (x − x_cm)² = 1.5625 + 2 · 0.0625 + 3.0625 = 4.75 kg m², so J = diag(0.3, 4.75 + 0.6,
    // 4.75 + 0.9) kg m² with no products of inertia (every node at y = 0, z = z_cm). 1e-14.
    let r = fem.rigid_body_inertia().expect("record 11 gives it");
    assert!((r.mass - 4.0).abs() < 1e-14);
    assert!((r.centre_of_mass[0] - 1.25).abs() < 1e-14 && r.centre_of_mass[1].abs() < 1e-14 && (r.centre_of_mass[2] - 0.5).abs() < 1e-14);
    let expected = [[0.3, 0.0, 0.0], [0.0, 5.35, 0.0], [0.0, 0.0, 5.65]];
    for i in 0..3 {
        for j in 0..3 {
            assert!((r.inertia[i][j] - expected[i][j]).abs() < 1e-14, "J[{i}][{j}] = {}", r.inertia[i][j]);
        }
    }
}

#[test]
fn record_12_gives_the_rigid_body_inertia_and_unequal_lumped_masses_warn() {
    let text = original()
        .replace("  2 2 2 0.1 0.2 0.3", "  2 2 2.5 0.1 0.2 0.3")
        .replace("** END OF FILE", "** RECORD GROUP 12, GLOBAL INERTIA\n 7\n 1 2 3\n 4 0 0\n 0 5 0\n 0 0 6\n** END OF FILE");
    let fem = parse_fem(&text, Path::new("f.fem")).unwrap_or_else(|e| panic!("{e}"));
    let r = fem.rigid_body_inertia().unwrap();
    assert_eq!((r.mass, r.centre_of_mass, r.inertia), (7.0, [1.0, 2.0, 3.0], [[4.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 6.0]]));
    // MBDyn 1.7.3 warns too ("component(3) of FEM node(2) mass differs from component(1)").
    assert_eq!(fem.warnings.len(), 1);
    assert!(fem.warnings[0].starts_with("f.fem:43:3: FEM node 2 has lumped masses 2, 2, 2.5"), "{}", fem.warnings[0]);
}

/// Each changed text is refused with `file:line:column` and a message holding `expected`.
#[test]
fn bad_files_are_refused_with_their_place() {
    let original = original();
    let cases: Vec<(String, &str)> = vec![
        // A record shorter than the header says: MBDyn would read the next record's values.
        (original.replace("  0 3\n** RECORD GROUP 10", "  0\n** RECORD GROUP 10"), "f.fem:37:3: record group 9 (line 35) holds 3 of the 4 modal mass matrix entries the header announces before line 38"),
        // One value too many: the header's counts do not match the data.
        (original.replace("  0.5 27\n", "  0.5 27 1\n"), "f.fem:40:10: record group 10 (line 38) holds more than the 4 modal stiffness matrix entries the header announces: '1' is one too many"),
        (original.replace("** RECORD GROUP 7, NODAL Z COORDINATES\n  5.0E-01 0.5 .5\n", ""), "record group(s) 7 missing: a FEM file needs records 1, 2 and 5 to 10"),
        (original.replace("** RECORD GROUP 1, HEADER", "** RECORD GROUP 2, HEADER"), "f.fem:4:1: record group 2 comes before record group 1"),
        (original.replace("** RECORD GROUP 6, NODAL Y", "** RECORD GROUP 5, NODAL Y"), "f.fem:18:1: record group 5 appears twice (first at line 14)"),
        (original.replace("** RECORD GROUP 13, MODAL", "** RECORD GROUP 14, MODAL"), "f.fem:45:17: expected a record group number from 1 to 13"),
        (original.replace("  8 0.25", "  8.0D+00 0.25"), "f.fem:39:3: record group 10: expected a real number, found '8.0D+00' (a Fortran exponent: write E instead of D)"),
        (original.replace("  0 0 0.5 0 -0.5 0", "  0 0 nan 0 -0.5 0"), "f.fem:29:7: record group 8: expected a finite real number, found 'nan'"),
        (original.replace("      A1 A2 A3", "      A1 A2 A1"), "f.fem:9:13: FEM node label 'A1' appears twice in record group 2 (first at line 9)"),
        (original.replace("REV0         3         3         0         0         1", "REV0 3 3 0 0 4"), "f.fem:6:20: 4 rejected modes, more than the 3 normal, attached and constraint modes listed"),
        (original.replace("REV0         3         3", "REV0 three 3"), "f.fem:6:12: expected the number of FEM nodes (a non-negative integer), found 'three'"),
        (original.replace("REV0         3         3         0         0         1", "REV0 3 3"), "f.fem:4:1: record group 1 (the header) needs the revision and five counts"),
        // Sizes from the header are checked against the file before allocating: a billion
        // nodes (48 GB of mode shapes) in a 1.5 kB file.
        (original.replace("REV0         3         3", "REV0 1000000000 3"), "f.fem:6:12: the header announces 1000000000 nodes and 3 modes: records 5 to 10 need at least 21000000008 values, more than this file"),
        (original.replace("REV0         3         3", "REV0 18446744073709551615 3"), "records 5 to 10 need at least more than 2^64 values"),
        ("** not a FEM file\n1 2 3\n".to_string(), "f.fem:1:1: no '** RECORD GROUP 1' line"),
    ];
    for (text, expected) in cases {
        let e = parse_fem(&text, Path::new("f.fem")).err().map(|e| e.to_string()).unwrap_or_else(|| "accepted".into());
        assert!(e.contains(expected), "expected '{expected}', got '{e}'");
        assert!(e.starts_with("f.fem:"), "{e}");
    }
    // Not a regular file: refused from its metadata, named.
    let e = read_fem(Path::new("/dev/zero")).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("/dev/zero") && e.contains("not a regular file"), "{e}");
}

/// Truncated at every byte and with every line dropped in turn, the file is read or
/// refused with its place, never a panic.
#[test]
fn every_truncation_is_read_or_refused() {
    let original = original();
    let lines: Vec<&str> = original.lines().collect();
    let dropped = (0..lines.len()).map(|i| lines.iter().enumerate().filter(|(k, _)| *k != i).map(|(_, l)| *l).collect::<Vec<_>>().join("\n"));
    for text in (0..original.len()).filter(|&n| original.is_char_boundary(n)).map(|n| original[..n].to_string()).chain(dropped) {
        if let Err(e) = parse_fem(&text, Path::new("f.fem")) {
            assert!(e.to_string().starts_with("f.fem:"), "{e}");
        }
    }
}

#[test]
fn zeros_after_a_record_are_skipped_with_a_warning_as_mbdyn_does() {
    // femgen wrote a twelfth row of zeros after record 11's eleven nodes in MBDyn's own
    // tests/joints/modal/beam/beam.fem; MBDyn 1.7.3 reads the announced values and skips the
    // rest. Zeros change nothing, so romdyn skips them too, with a warning; any other value
    // stays an error (bad_files_are_refused_with_their_place, record 10).
    let text = original().replace("  1 1 1 0.1 0.2 0.3\n** RECORD GROUP 13", "  1 1 1 0.1 0.2 0.3\n  0.0 0 0 0 0 0\n** RECORD GROUP 13");
    let fem = parse_fem(&text, Path::new("f.fem")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(fem.lumped_inertia.as_ref().map(|l| l.len()), Some(3));
    assert!(fem.warnings.iter().any(|w| w.starts_with("f.fem:45:3: record group 11 holds 6 zero(s) after the 18 lumped inertia components")), "{:?}", fem.warnings);
    let text = original().replace("  1 1 1 0.1 0.2 0.3\n** RECORD GROUP 13", "  1 1 1 0.1 0.2 0.3\n  0 0 1e-9\n** RECORD GROUP 13");
    let err = parse_fem(&text, Path::new("f.fem")).err().expect("a non-zero extra value is refused").to_string();
    assert!(err.starts_with("f.fem:45:3: record group 11 (line 41) holds more than the 18 lumped inertia components"), "{err}");
}
