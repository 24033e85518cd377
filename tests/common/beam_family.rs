//! The beam family of issue 30 (finding 3) in MBDyn syntax: a cantilever of N `beam3`
//! elements with a tip mass, every node dynamic and free in 3-D; shared by
//! tests/eigen/dense_eigen_scaling.rs and benches/dense_beam_family.rs.

/// Lumped masses and inertias of the beam file below, node by node: `(m, J_x, J_y, J_z)`.
pub fn beam_inertia(elements: usize) -> Vec<[f64; 4]> {
    let n = 2 * elements + 1;
    let dl = 1.0 / (n - 1) as f64;
    let mut out: Vec<[f64; 4]> = (0..n)
        .map(|i| {
            let l = if i == 0 || i == n - 1 { dl / 2.0 } else { dl };
            [l, 1e-3 * l, l.powi(3) / 12.0, l.powi(3) / 12.0]
        })
        .collect();
    // Tip mass 0.1 kg with 1e-4 kg m² about every axis on the last node.
    let tip = &mut out[n - 1];
    *tip = [tip[0] + 0.1, tip[1] + 1e-4, tip[2] + 1e-4, tip[3] + 1e-4];
    out
}

/// A cantilever of `elements` beam3 elements along x (L = 1 m, ρA = 1 kg/m, GA = EA,
/// GJ = EJ), clamped at node 1, with a tip mass, every node dynamic and free in 3-D (the
/// model of issue 30: 12 (2N + 1) + 6 equations).
pub fn cantilever(elements: usize, ea: f64, ej: f64) -> String {
    let n = 2 * elements + 1;
    let dl = 1.0 / (n - 1) as f64;
    let mut nodes = String::new();
    let mut elems = String::from("joint: 1, clamp, 1, node, node;\n");
    for (i, [m, jx, jy, jz]) in beam_inertia(elements).into_iter().enumerate() {
        nodes += &format!("structural: {}, dynamic, {:e}, 0., 0., eye, null, null;\n", i + 1, i as f64 * dl);
        elems += &format!("body: {}, {}, {m:e}, null, diag, {jx:e}, {jy:e}, {jz:e};\n", i + 1, i + 1);
    }
    let law = format!("eye, linear elastic generic, diag, {ea:e}, {ea:e}, {ea:e}, {ej:e}, {ej:e}, {ej:e}");
    for e in 0..elements {
        let (a, b, c) = (2 * e + 1, 2 * e + 2, 2 * e + 3);
        elems += &format!("beam3: {}, {a}, null, {b}, null, {c}, null, {law}, {law};\n", e + 1);
    }
    format!("begin: data; problem: initial value; end: data;\nbegin: control data; structural nodes: {n}; rigid bodies: {n}; joints: 1; beams: {elements}; end: control data;\nbegin: nodes;\n{nodes}end: nodes;\nbegin: elements;\n{elems}end: elements;\n")
}
