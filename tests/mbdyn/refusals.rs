//! Issue 38 point 4: every refusal names the card and says whether MBDyn 1.7.3 runs it, so
//! a user learns whether the file is valid MBDyn (romdyn's limit) or wrong (a typo). The
//! cards "MBDyn 1.7.3 runs" are those its 1.7.3 source registers by that keyword (elman.cc,
//! joint.cc, genel.cc, constltp.cc, nodeman, dataman4.cc, drive.cc, friction.cc; read in the
//! mirror github:alex-marinov/mbdyn); the unknown names are in none of those tables.

use std::path::Path;

use romdyn::input::mbdyn::{build, parse_text};

fn error_of(text: &str) -> String {
    match parse_text(text, Path::new("m.mbd")).and_then(|d| build(&d)) {
        Ok(_) => "accepted".into(),
        Err(e) => e.to_string().lines().next().unwrap_or("").to_string(),
    }
}

fn model(control: &str, cards: &str, elements: &str) -> String {
    format!(
        "begin: data; problem: initial value; end: data;\n{cards}\n\
         begin: initial value; initial time: 0.; final time: 1.e-2; time step: 1.e-3; end: initial value;\n\
         begin: control data; structural nodes: 2; {control} end: control data;\n\
         begin: nodes; structural: 1, static, null, eye, null, null; structural: 2, dynamic, 0., -1., 0., eye, null, null; end: nodes;\n\
         begin: elements;\n{elements}\nend: elements;\n"
    )
}

const RUNS: &str = "(MBDyn 1.7.3 runs it)";

#[test]
fn a_card_mbdyn_runs_is_refused_as_romdyns_limit() {
    let cases = [
        ("element type", model("aerodynamic elements: 0; joints: 0;", "", "aerodynamic body: 1, 2, rotor, 1, null, eye, 1., 1., const, 0., const, 0., const, 0., const, 0., 1;")),
        ("joint type", model("joints: 1;", "", "joint: 1, point contact, 1, 2, null;")),
        ("genel type", model("genels: 1;", "", "genel: 1, swashplate, 1, 2, 3;")),
        ("constitutive law", model("joints: 1;", "", "joint: 1, rod, 1, 2, 1., log elastic, 1.;")),
        ("node type", format!("begin: data; problem: initial value; end: data;\nbegin: initial value; initial time: 0.; final time: 1.e-2; time step: 1.e-3; end: initial value;\nbegin: control data; structural nodes: 1; end: control data;\nbegin: nodes; structural: 1, static, null, eye, null, null; thermal: 1, value, 300.; end: nodes;\nbegin: elements; end: elements;\n")),
        ("card", model("", "c81 data: 1, \"naca.c81\";", "")),
        ("file driver", format!("begin: data; problem: initial value; end: data;\nbegin: initial value; initial time: 0.; final time: 1.e-2; time step: 1.e-3; end: initial value;\nbegin: control data; structural nodes: 1; file drivers: 1; end: control data;\nbegin: nodes; structural: 1, static, null, eye, null, null; end: nodes;\nbegin: drivers; file: 1, socket, create, yes, port, 9011; end: drivers;\nbegin: elements; end: elements;\n")),
        ("friction model", model("joints: 1;", "", "joint: 1, revolute hinge, 1, null, 2, null, friction, 0.1, preload, 1., discrete coulomb, simple;")),
        ("joint friction", model("joints: 1;", "scalar function: \"mu\", const, 0.3;", "joint: 1, axial rotation, 1, null, 2, null, const, 1., friction, 0.1, preload, 1., modlugre, 1000., 1., 0., 0.5, \"mu\", simple;")),
    ];
    let mut failures = Vec::new();
    for (what, text) in &cases {
        let got = error_of(text);
        if !got.contains("not supported by romdyn") || !got.contains(RUNS) {
            failures.push(format!("{what}: {got}"));
        }
    }
    // Control data counters MBDyn reads (dataman3.cc): "MBDyn 1.7.3 runs them".
    let got = error_of(&model("electric bulk elements: 1;", "", ""));
    if !got.contains("MBDyn 1.7.3 runs them") {
        failures.push(format!("counter: {got}"));
    }
    assert!(failures.is_empty(), "refusals that do not say MBDyn runs the card:\n{}", failures.join("\n"));
}

#[test]
fn a_feature_of_a_card_mbdyn_runs_is_refused_as_romdyns_limit() {
    // Options of cards romdyn reads, which MBDyn 1.7.3 honours (its input manual).
    let cases = [
        ("integration method", model("", "", "").replace("time step: 1.e-3;", "time step: 1.e-3; method: hope, 0.6, 0.6;")),
        ("use in assembly", model("rigid bodies: 1; use: rigid bodies, in assembly;", "", "body: 1, 2, 1., null, eye;")),
        ("inverse dynamics", model("", "", "").replace("problem: initial value;", "problem: inverse dynamics;")),
    ];
    for (what, text) in cases {
        let got = error_of(&text);
        assert!(got.contains("not supported by romdyn (MBDyn 1.7.3 runs it"), "{what}: {got}");
    }
}

#[test]
fn a_name_neither_program_knows_is_said_to_be_unknown_to_both() {
    // A typo ("revolut hinge", "aerodynamic bodyy") is not a card MBDyn runs: the message
    // must not send the user looking for a romdyn feature.
    for (what, text) in [
        ("element type", model("", "", "aerodynamic bodyy: 1, 2;")),
        ("joint type", model("joints: 1;", "", "joint: 1, revolut hinge, 1, null, 2, null;")),
    ] {
        let got = error_of(&text);
        assert!(got.contains(&format!("unknown {what}")) && got.contains("MBDyn 1.7.3 has none either") && !got.contains(RUNS), "{what}: {got}");
    }
}

#[test]
fn friction_where_mbdyn_reads_none_is_not_said_to_run() {
    // joint.cc reads `friction` on revolute hinge, brake, axial rotation, in line, screw.
    let text = model("joints: 1;", "scalar function: \"mu\", const, 0.3;", "joint: 1, spherical hinge, 1, null, 2, null, friction, 0.1, preload, 1., modlugre, 1000., 1., 0., 0.5, \"mu\", simple;");
    let got = error_of(&text);
    assert!(got.contains("read by neither romdyn nor MBDyn 1.7.3") && !got.contains(RUNS), "{got}");
}

#[test]
fn cards_that_need_an_mbdyn_build_option_say_so() {
    // GiNaC-based cards run only in an MBDyn built with GiNaC (configure --with-ginac).
    let got = error_of(&model("joints: 1;", "", "joint: 1, rod, 1, 2, 1., symbolic elastic, epsilon, \"eps\", expression, \"eps\";"));
    assert!(got.contains("an MBDyn 1.7.3 built with GiNaC runs it"), "{got}");
    let got = error_of(&model("forces: 1;", "drive caller: 1, ginac, \"Time\";", ""));
    assert!(got.contains("an MBDyn 1.7.3 built with GiNaC runs it"), "{got}");
}
