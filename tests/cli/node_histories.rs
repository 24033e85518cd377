//! Node histories kept in memory (the Python package's `Model.run()`).

use std::path::Path;

use romdyn::analysis::{run, NodeHistories};
use romdyn::input::mbdyn::read_model;

#[test]
fn pendulum_histories_keep_the_hinge_and_the_step_count() {
    let m = read_model(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pendulum.mbd")).unwrap();
    let mut h = NodeHistories::default();
    run(&m.model, &m.problem, &mut h).unwrap();
    // MBDyn's step count: 1 ms steps until the time passes 2 s (2001 steps + the initial state).
    assert_eq!(h.time.len(), 2002);
    assert_eq!(h.labels, vec![1, 2]);
    assert_eq!((h.position.len(), h.orientation.len()), (2002 * 2 * 3, 2002 * 2 * 9));
    for k in 0..h.time.len() {
        // Node 2 stays L = 1 m from the hinge at the origin (the file's tolerance is 1e-9).
        let p = &h.position[k * 6 + 3..k * 6 + 6];
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        assert!((r - 1.0).abs() < 1e-6, "step {k}: r = {r}");
        // Orientation matrices stay orthonormal: row 0 of node 2 has unit length.
        let o = &h.orientation[k * 18 + 9..k * 18 + 12];
        assert!(((o[0] * o[0] + o[1] * o[1] + o[2] * o[2]).sqrt() - 1.0).abs() < 1e-9);
    }
}
