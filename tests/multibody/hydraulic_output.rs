//! The hydraulic elements' own output, MBDyn's `.hyd` file (issue 34): a run writes one row
//! per hydraulic element and output instant in the columns of MBDyn 1.7.3's `Output`
//! (hydr/actuator.cc, hminor.cc, valve.cc, pipe.cc, hutils.cc), checked against MBDyn
//! 1.7.3's rows on the same files (tests/mbdyn_files/hydraulic_*.mbd with `output
//! precision: 16` added to control data, `mbdyn -f FILE -o PREFIX`); `output, no` on a card
//! and `default output: none` switch it off.

use crate::common;
use common::cli::temp_dir;
use common::mbdyn::test_file;
use romdyn::analysis::{run, RunFiles};
use romdyn::input::mbdyn::read_model_text;

/// The `.hyd` rows romdyn writes for the model read from `text` (named `name`).
pub fn hyd_rows(name: &str, text: &str) -> Vec<Vec<f64>> {
    let m = read_model_text(text, &test_file(name), romdyn::input::mbdyn::ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let dir = temp_dir(&format!("hyd-{name}"));
    let prefix = dir.join("run");
    let mut files = RunFiles::create(&prefix, name, &m.model, &m.problem).unwrap();
    let report = run(&m.model, &m.problem, &mut files).unwrap_or_else(|e| panic!("{name}: {e}"));
    files.finish(&report).unwrap();
    let Ok(hyd) = std::fs::read_to_string(dir.join("run.hyd")) else { return Vec::new() };
    hyd.lines().map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect()).collect()
}

/// Asserts that romdyn's rows of output instant `instant` (with `per` rows an instant)
/// equal MBDyn's `want` (label first), each number to `1e-8` of itself plus `floor`.
pub fn assert_instant(name: &str, rows: &[Vec<f64>], per: usize, instant: usize, want: &[&[f64]], floor: f64) {
    for (k, want) in want.iter().enumerate() {
        let got = &rows[instant * per + k];
        assert_eq!(got.len(), want.len(), "{name}, instant {instant}: {got:?}");
        for (j, (g, w)) in got.iter().zip(want.iter()).enumerate() {
            assert!((g - w).abs() <= 1e-8 * w.abs() + floor, "{name}, instant {instant}, element {}, column {j}: romdyn {g:e}, MBDyn {w:e}", want[0]);
        }
    }
}

#[test]
fn hydraulic_elements_write_mbdyns_hyd_rows() {
    // MBDyn 1.7.3's rows at output instants 500 and the last (t = 5.0e-3 s and the final
    // time of each file). Over whole runs romdyn's rows differ from MBDyn's by at most
    // (measured): actuator pressures 3.5e-7 Pa, rates 4e-4 Pa/s on 1.4e8, flows of the
    // closed chambers 3.4e-14 kg/s (noise about zero in both); minor loss 5.8e-10 relative;
    // control valve 2.7e-12 relative; pipe 7.4e-13 relative. Tolerance: 1e-8 relative plus
    // 1e-11 absolute (the closed chambers' flows, the valve's state at its zero crossing).
    let name = "hydraulic_actuator_mass.mbd";
    let rows = hyd_rows(name, &std::fs::read_to_string(test_file(name)).unwrap());
    assert_eq!(rows.len(), 2002);
    // Label; flows out of nodes 1, 2 [kg/s]; π₁, π₂ [Pa]; π̇₁, π̇₂ [Pa/s]; V₁, V₂ [m³]; ρ₁, ρ₂.
    let mid: &[f64] = &[1.0, 3.3635316754043740e-14, 3.3649527608758947e-14, 9.7054556064614793e+05, 1.0294561751809100e+06, -1.0022826882871541e+08, 1.0024007854302758e+08, 1.0000294553072550e-04, 9.9997054469274507e-05, 8.4997496372654928e+02, 8.5002503774890374e+02];
    let last: &[f64] = &[1.0, 5.2191584387628615e-16, 5.2230442193490493e-16, 8.0006767449167080e+05, 1.2000123033643658e+06, 3.3245965671607926e+06, -3.3272569400185784e+06, 1.0001999723065295e-04, 9.9980002769347077e-05, 8.4983005752331792e+02, 8.5017001045785969e+02];
    assert_instant(name, &rows, 1, 500, &[mid], 1e-11);
    assert_instant(name, &rows, 1, 2001, &[last], 1e-11);

    // Actuator 1 as above, minor loss 2: velocity [m/s], flow [kg/s].
    let name = "hydraulic_minor_loss.mbd";
    let rows = hyd_rows(name, &std::fs::read_to_string(test_file(name)).unwrap());
    assert_eq!(rows.len(), 2 * 1002);
    let mid: [&[f64]; 2] = [
        &[1.0, 1.4919322112812137e-02, 0.0, 1.7381339149342997e+06, 1.6158428387548025e+06, 1.6995717552666590e+08, 5.4623533096174421e+06, 1.0006154638098008e-04, 9.9938453619019928e-05, 8.5062741382769411e+02, 8.5052346641294162e+02],
        &[2.0, 1.7552143662131925e+01, 1.4919322112812137e-02],
    ];
    let last: [&[f64]; 2] = [
        &[1.0, -5.8186445747544790e-04, 0.0, 2.0005974698474233e+06, 1.9328393051030464e+06, -1.2596637524451341e+07, 5.7678984199991645e+06, 1.0009319699269739e-04, 9.9906803007302622e-05, 8.5085050784937027e+02, 8.5079291340933764e+02],
        &[2.0, -6.8454642055933212e-01, -5.8186445747543229e-04],
    ];
    assert_instant(name, &rows, 2, 500, &mid, 1e-11);
    assert_instant(name, &rows, 2, 1001, &last, 1e-11);

    // Control valve 2: its state (held in [−1, 1]), the net flows into nodes 1 to 4 [kg/s].
    let name = "hydraulic_control_valve.mbd";
    let rows = hyd_rows(name, &std::fs::read_to_string(test_file(name)).unwrap());
    assert_eq!(rows.len(), 2 * 5001);
    let mid: [&[f64]; 2] = [
        &[1.0, 7.6308647863887963e-03, -7.2659259279721951e-03, 1.0092718616480681e+06, 1.0036879607656102e+06, 1.2046156531145979e+07, -7.7577505599216577e+06, 1.0002301744341480e-04, 9.9976982556585213e-05, 8.5000788108240090e+02, 8.5000313476665076e+02],
        &[2.0, 2.9389262614623474e-01, -8.1225558932619332e-03, 7.6308647863874649e-03, -7.2659259279712297e-03, 7.7576170348456971e-03],
    ];
    let last: [&[f64]; 2] = [
        &[1.0, 2.4312746501706995e-04, -2.4037566593595032e-04, 1.0562427353670713e+06, 1.0366721380225067e+06, 3.3831419391068923e+06, -3.3516624630400455e+06, 1.0001343574233699e-04, 9.9986564257663015e-05, 8.5004780632506197e+02, 8.5003117131731915e+02],
        &[2.0, 2.9120005698172632e-13, -7.3674771747721571e-04, 2.4312746501707974e-04, -2.4037566593593923e-04, 7.3399591839607521e-04],
    ];
    assert_instant(name, &rows, 2, 500, &mid, 1e-11);
    assert_instant(name, &rows, 2, 5000, &last, 1e-11);

    // Pipe 2: velocity [m/s], flow [kg/s], Reynolds number (turbulent at 5 ms).
    let name = "hydraulic_pipe.mbd";
    let text = std::fs::read_to_string(test_file(name)).unwrap();
    let rows = hyd_rows(name, &text);
    assert_eq!(rows.len(), 2 * 1002);
    let mid: [&[f64]; 2] = [
        &[1.0, 3.3103289667749822e-02, -1.7763568394002505e-18, 1.9681308982872467e+06, 2.1024235112263681e+06, 2.2074317915304017e+08, 1.6867254846929795e+08, 1.0011012095111542e-04, 9.9889879048884592e-05, 8.5082291126354414e+02, 8.5093705998454243e+02],
        &[2.0, 3.0991483430736766e+00, 3.3103289667749822e-02, 1.0537104366450500e+04],
    ];
    let last: [&[f64]; 2] = [
        &[1.0, 1.0949745110991465e-02, 1.7763568394002505e-18, 1.9965588002626917e+06, 1.8830499392000588e+06, -9.0380249157368187e+06, 1.3797262535151544e+08, 1.0008822708494714e-04, 9.9911772915052882e-05, 8.5084707498022328e+02, 8.5075059244832005e+02],
        &[2.0, 1.0251212117709445e+00, 1.0949745110991465e-02, 3.4854121200212112e+03],
    ];
    assert_instant(name, &rows, 2, 500, &mid, 1e-11);
    assert_instant(name, &rows, 2, 1001, &last, 1e-11);

    // `output, no` on the pipe's card leaves its rows out; `default output: none` writes no
    // `.hyd` (MBDyn 1.7.3 writes none either), `default output: none, hydraulic elements`
    // writes both elements again.
    let pipe_card = "fluid, incompressible, density, RHO, viscosity, 1.e-3;";
    assert!(text.contains(pipe_card));
    let quiet = text.replace(pipe_card, "fluid, incompressible, density, RHO, viscosity, 1.e-3, output, no;");
    let rows = hyd_rows(name, &quiet);
    assert_eq!(rows.len(), 1002);
    assert!(rows.iter().all(|r| r[0] == 1.0 && r.len() == 11));
    let none = text.replace("begin: control data;", "begin: control data;\n    default output: none;");
    assert!(hyd_rows(name, &none).is_empty());
    let again = text.replace("begin: control data;", "begin: control data;\n    default output: none, hydraulic elements;");
    assert_eq!(hyd_rows(name, &again).len(), 2 * 1002);
}
