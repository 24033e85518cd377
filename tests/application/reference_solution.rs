//! Linearizing a model file at a later time (`eig --at`, `analysis::reference_state`): the
//! file's problem is integrated up to that time first.

use crate::common;

use std::path::Path;

use common::cli::{pendulum_variant, romdyn, temp_dir, write_file, DISPLACED_NODE, PENDULUM_NODE};
use romdyn::analysis::{reference_state, Reference};
use romdyn::input::mbdyn::read_model;

/// Period released from rest at 0.1 rad (CASES C2, computed).
const PERIOD: f64 = 2.008325;

fn dynamic_im(out: &str) -> f64 {
    let v: serde_json::Value = serde_json::from_str(out).unwrap();
    v["eigenvalues"][0]["im"].as_f64().unwrap()
}

#[test]
fn the_reference_state_half_a_period_later_is_the_mirror_position() {
    // Released from rest at +0.1 rad, the pendulum is back at rest at −0.1 rad after T/2
    // (energy conservation and symmetry). The run stops at the first step at or after T/2
    // (h = 1e-3 s, so within 1 ms: angle change ½ θ₀ ω² (1e-3)² ≈ 5e-7 rad); the integrator's
    // period error is ~1e-6 relative. Tolerance 1e-5 rad on the angle.
    let dir = temp_dir("reference-mirror");
    let file = write_file(&dir, "swing.mbd", &pendulum_variant(&[(PENDULUM_NODE, DISPLACED_NODE)]));
    let m = read_model(Path::new(&file)).unwrap();
    let st = reference_state(&m.model, &m.problem, Reference::At(PERIOD / 2.0)).unwrap();
    assert!(st.t >= PERIOD / 2.0 && st.t < PERIOD / 2.0 + 1e-3, "t = {}", st.t);
    // Node 2 (x, y) are unknowns 6, 7: after the 6 of the static ground node.
    let (x, y) = (st.y[6], st.y[7]);
    let angle = x.atan2(-y);
    assert!((angle + 0.1).abs() < 1e-5, "angle {angle} rad at t = {} s", st.t);
    assert!(reference_state(&m.model, &m.problem, Reference::At(-1.0)).unwrap_err().to_string().contains("before the initial time"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn eig_at_a_time_linearizes_there() {
    // Hanging at rest, the pendulum stays at its equilibrium: ±3.130527 j rad/s at any time
    // (eq. 82, CASES C2, 1e-6 relative).
    let (ok, out, err) = romdyn(&["eig", "examples/pendulum.mbd", "--at", "0.5", "--json"]);
    assert!(ok, "{err}");
    assert!((dynamic_im(&out) - 3.130527).abs() / 3.130527 < 1e-6, "{out}");

    // Released at 0.1 rad: at rest at +0.1 rad (t = 0) and at −0.1 rad (t = T/2) the
    // linearizations are mirror images, so their eigenvalues agree (1e-5 relative, the
    // mirror-state accuracy above); both differ from the hanging value.
    let dir = temp_dir("reference-eig");
    let file = write_file(&dir, "swing.mbd", &pendulum_variant(&[(PENDULUM_NODE, DISPLACED_NODE)]));
    let at_start = romdyn(&["eig", &file, "--json"]);
    let half = format!("{}", PERIOD / 2.0);
    let at_half = romdyn(&["eig", &file, "--at", &half, "--json"]);
    assert!(at_start.0 && at_half.0, "{} {}", at_start.2, at_half.2);
    let (w0, w1) = (dynamic_im(&at_start.1), dynamic_im(&at_half.1));
    assert!((w0 - w1).abs() / w0 < 1e-5, "{w0} vs {w1}");
    assert!((w0 - 3.130527).abs() > 1e-3, "{w0}: not the hanging equilibrium");
    let (ok, _, err) = romdyn(&["eig", &file, "--at", "nonsense"]);
    assert!(!ok && err.contains("invalid value 'nonsense' for '--at <TIME>'"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
