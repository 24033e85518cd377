mod common;
use romdyn::linear::*;
#[test]
fn print() {
    for scaled in [false, true] { for r in [0.0, 10.0] { for c in [1e-1, 1e-3, 1e-5] {
        let d = common::with_coefficient(&common::two_masses(r, scaled), c);
        for route in [EigenRoute::Direct, EigenRoute::Lambda] {
            let m = ModalAnalysis::compute(&d.jacobians, route).unwrap();
            println!("scaled={scaled} r={r} c={c:e} {route:?}");
            for md in &m.modes { println!("   {:>24.10e} {:>24.10e} {:?} err={:.2e} z={:.2e} i={:.2e} u={:.2e}", md.lambda.re, md.lambda.im, md.kind, md.error, md.classification.to_zero, md.classification.to_infinity, md.classification.uncertainty); }
        }
    }}}
}
