//! Drive caller and scalar function cards that name earlier cards (issue 32's grammar:
//! `reference`, `array`, `mult`, `drive`, string drives calling `model::drive` and
//! `model::sf`, `sum`/`sub`/`mul`/`div`), built from the input bytes: each byte pair picks a
//! card's kind and the earlier card it names, so the fuzzer reaches deep chains and
//! doubling trees. Reading and building must give a model or an error: no panic, no stack
//! overflow, no unbounded memory (the limits of `romdyn::limits`).
#![no_main]

use std::fmt::Write;

use libfuzzer_sys::fuzz_target;

const NUMBERS: [&str; 8] = ["0.", "1.", "-2.5", "1e308", "1e-300", "3", "0.5", "1e309"];

fuzz_target!(|data: &[u8]| {
    let mut s = String::from("scalar function: \"f0\", const, 1.;\ndrive caller: 1, sine, 0., 1., 1., forever, 0.;\n");
    let mut k = 0usize;
    for pair in data.chunks(2) {
        k += 1;
        let (kind, pick) = (pair[0], *pair.get(1).unwrap_or(&0) as usize);
        // The previous card when `pick` is even, else one further back.
        let a = if pick % 2 == 0 { k - 1 } else { (pick / 2) % k };
        let f = match kind % 6 {
            0 => format!("sum, \"f{a}\", \"f{a}\""),
            1 => format!("mul, \"f{a}\", \"f{}\"", k - 1),
            2 => format!("div, \"f{a}\", \"f{}\"", k - 1),
            3 => format!("sub, \"f{a}\", \"f{}\"", k - 1),
            4 => format!("linear, 0., {a}., 1., {k}."),
            _ => format!("const, {}", NUMBERS[pick % NUMBERS.len()]),
        };
        let _ = writeln!(s, "scalar function: \"f{k}\", {f};");
        let (a, b) = (a + 1, k);
        let d = match (kind / 6) % 8 {
            0 => format!("reference, {a}"),
            1 => format!("array, 2, reference, {a}, reference, {b}"),
            2 => format!("mult, reference, {a}, reference, {b}"),
            3 => format!("drive, reference, {a}, reference, {b}"),
            4 => format!("string, \"model::drive({a}, Time) + model::drive({b}, 2.*Time)\""),
            5 => format!("string, \"model::sf::f{k}(Time) * {}\"", NUMBERS[pick % NUMBERS.len()]),
            6 => format!("scalar function, \"f{k}\""),
            _ => format!("string, \"{}^(Time*{a}.)\"", NUMBERS[pick % NUMBERS.len()]),
        };
        let _ = writeln!(s, "drive caller: {}, {d};", k + 1);
    }
    let _ = writeln!(s, "set: real x = model::drive({}, 0.5);\nset: real y = model::sf::f{k}(0.5);", k + 1);
    let text = format!(
        "begin: data; problem: initial value; end: data;\n{s}\
         begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-2; end: initial value;\n\
         begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; end: control data;\n\
         begin: nodes; structural: 1, dynamic, null, eye, null, null; end: nodes;\n\
         begin: elements; body: 1, 1, 1., null, eye; force: 1, absolute, 1, position, null, 1., 0., 0., reference, {}; end: elements;",
        k + 1
    );
    let _ = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("fuzz.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d));
});
