//! Bounded fuzzing of the MBDyn reader: random token streams built from the grammar's
//! words, random statements inside valid blocks, and random mutations of the shipped
//! examples. Every input must give a model or an error, never a panic (a panic prints the
//! input that caused it). Each generator runs for a fixed share of a few seconds, so the
//! test stays short on slow machines; the streams are deterministic (seeded xorshift).
//! For a longer local run: `ROMDYN_FUZZ_SECONDS=60 ROMDYN_FUZZ_SEED=7 cargo test --test
//! mbdyn_fuzz`.

use std::fmt::Write;
use std::path::Path;
use std::time::{Duration, Instant};

use romdyn::input::mbdyn::{build, parse_text};

use crate::common;

use common::fuzz::Rng;

fn budget() -> Duration {
    common::fuzz::budget(Duration::from_millis(1500))
}

/// Words of the grammar: statements, blocks, element and joint types, keywords of entities.
const WORDS: &[&str] = &[
    "begin", "end", "data", "problem", "initial value", "control data", "nodes", "elements", "drivers", "set", "include", "remark", "reference",
    "drive caller", "constitutive law", "structural", "static", "dynamic", "dummy", "modal", "offset", "at reference", "body", "joint", "force",
    "couple", "gravity", "beam3", "beam2", "clamp", "revolute hinge", "revolute pin", "spherical hinge", "spherical pin", "total joint",
    "total pin joint", "deformable displacement joint", "deformable hinge", "rod", "rod with offset", "position", "orientation",
    "axial rotation", "deformable joint", "deformable axial joint", "invariant deformable hinge", "drive hinge", "drive displacement",
    "drive displacement pin", "imposed displacement", "imposed displacement pin", "cardano hinge", "cardano pin", "cardano rotation",
    "position orientation", "rotation orientation", "position constraint", "orientation constraint", "active", "inactive", "velocity",
    "angular velocity", "global", "node", "other node", "other position", "other orientation", "null", "eye", "matr", "sym", "diag", "skew",
    "euler", "euler123", "euler313", "euler321", "degrees", "vector", "guess", "scale", "default", "const", "time", "ramp", "step", "sine",
    "cosine", "piecewise linear", "forever", "one", "half", "single", "component", "array", "linear elastic", "linear elastic generic",
    "linear viscoelastic", "linear viscous generic", "proportional", "prestrain", "prestress", "from nodes", "absolute", "follower", "uniform",
    "condense", "structural nodes", "rigid bodies", "joints", "forces", "beams", "initial time", "final time", "time step", "method", "ms",
    "crank nicolson", "implicit euler", "bdf", "order", "tolerance", "max iterations", "eigenanalysis", "list", "parameter", "output matrices",
    "use lapack", "balance", "abort after", "real", "integer", "bool", "string", "ifndef", "pi", "e", "sin", "sqrt", "log", "atan2", "x", "L",
    "beam slider", "type", "classic", "spherical", "spline", "same", "initial beam", "initial node", "smearing", "hinge", "screw", "pitch",
    "brake", "friction", "preload", "modlugre", "simple", "template drive caller", "variable body", "3x3", "6x6",
];

const SYMBOLS: &[&str] = &[":", ",", ";", "(", ")", "[", "]", "+", "-", "*", "/", "%", "^", "=", "==", "!", "&&", "||", "::", "~|", "<", ">=", "\"", "#", "/*", "*/"];

const NUMBERS: &[&str] = &["0", "1", "2", "3", "-1", "0.", "1.", ".5", "1e300", "1e-300", "-2.5", "99999999999", "4294967296", "1.e9", "2147483647", "3.14159"];

fn token(r: &mut Rng) -> String {
    match r.below(10) {
        0..=3 => r.pick(WORDS).to_string(),
        4..=6 => r.pick(NUMBERS).to_string(),
        7..=8 => r.pick(SYMBOLS).to_string(),
        _ => format!("\"{}\"", r.pick(WORDS)),
    }
}

/// Runs the reader on `text`; a panic fails the test with the input.
fn survives(text: &str, what: &str) {
    let result = std::panic::catch_unwind(|| {
        let _ = parse_text(text, Path::new("fuzz.mbd")).and_then(|d| build(&d));
    });
    if result.is_err() {
        panic!("the reader panicked on this {what}:\n-----\n{text}\n-----");
    }
}

fn run(mut make: impl FnMut(&mut Rng) -> String, seed: u64, what: &str) -> usize {
    let mut r = Rng::seeded(seed);
    let start = Instant::now();
    let mut n = 0;
    while start.elapsed() < budget() {
        let text = make(&mut r);
        survives(&text, what);
        n += 1;
    }
    eprintln!("{what}: {n} inputs in {:?}", start.elapsed());
    n
}

#[test]
fn random_token_streams_never_panic() {
    let n = run(
        |r| {
            let len = 1 + r.below(60);
            (0..len).map(|_| token(r)).collect::<Vec<_>>().join(" ")
        },
        0x9E37_79B9_7F4A_7C15,
        "token stream",
    );
    assert!(n > 100, "only {n} inputs");
}

#[test]
fn random_statements_in_valid_blocks_never_panic() {
    // Statements of plausible shape (keyword: args;) inside the blocks they belong to, so
    // the generator reaches the model builder and the element readers.
    let statement = |r: &mut Rng, keywords: &[&str]| {
        let args = (0..r.below(25)).map(|_| if r.below(4) == 0 { r.pick(WORDS).to_string() } else { r.pick(NUMBERS).to_string() }).collect::<Vec<_>>().join(", ");
        format!("{}: {args};", r.pick(keywords))
    };
    let n = run(
        |r| {
            let iv: Vec<String> = (0..r.below(3)).map(|_| statement(r, &["initial time", "final time", "time step", "method", "tolerance", "eigenanalysis", "abort after", "max iterations"])).collect();
            let cd: Vec<String> = (0..r.below(4)).map(|_| statement(r, &["structural nodes", "rigid bodies", "joints", "forces", "beams", "gravity"])).collect();
            let nodes: Vec<String> = (0..1 + r.below(3)).map(|k| format!("structural: {}, {}, {};", k + 1, r.pick(&["static", "dynamic", "dummy"]), (0..r.below(14)).map(|_| token(r)).collect::<Vec<_>>().join(", "))).collect();
            let elements: Vec<String> = (0..1 + r.below(4))
                .map(|_| {
                    let kw = r.pick(&["body", "joint", "force", "couple", "gravity", "reference", "drive caller", "constitutive law"]);
                    let args = (0..r.below(30)).map(|_| if r.below(3) == 0 { r.pick(WORDS).to_string() } else { r.pick(NUMBERS).to_string() }).collect::<Vec<_>>().join(", ");
                    format!("{kw}: {args};")
                })
                .collect();
            format!(
                "begin: data; problem: initial value; end: data;\nbegin: initial value; {}\nend: initial value;\nbegin: control data; {}\nend: control data;\nbegin: nodes; {}\nend: nodes;\nbegin: elements; {}\nend: elements;",
                iv.join(" "),
                cd.join(" "),
                nodes.join(" "),
                elements.join(" ")
            )
        },
        0x2545_F491_4F6C_DD1D,
        "generated model",
    );
    assert!(n > 100, "only {n} inputs");
}

#[test]
fn mutated_examples_never_panic() {
    let examples: Vec<String> = ["pendulum", "inverted_pendulum", "double_pendulum", "mass_on_springs", "spatial_mechanism"]
        .iter()
        .map(|f| format!("examples/{f}.mbd"))
        .chain(["beam_slider", "screw", "brake", "variable_mass_body", "rod_prestrain", "template_drive_cards"].iter().map(|f| format!("tests/mbdyn_files/{f}.mbd")))
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect();
    let n = run(
        |r| {
            let base = &examples[r.below(examples.len())];
            // Token-level edits: split on separators, then replace, drop, duplicate or insert.
            let mut pieces: Vec<String> = base.split_inclusive([',', ';', ' ', '\n']).map(str::to_string).collect();
            for _ in 0..1 + r.below(6) {
                let i = r.below(pieces.len());
                match r.below(5) {
                    0 => pieces[i] = format!("{} ", token(r)),
                    1 => {
                        pieces.remove(i);
                    }
                    2 => {
                        let p = pieces[i].clone();
                        pieces.insert(i, p);
                    }
                    3 => pieces.insert(i, format!("{}, ", r.pick(NUMBERS))),
                    _ => {
                        let j = r.below(pieces.len());
                        pieces.swap(i, j);
                    }
                }
            }
            let mut text = pieces.concat();
            // Byte-level edits too.
            let mut bytes = text.into_bytes();
            for _ in 0..r.below(3) {
                if bytes.is_empty() {
                    break;
                }
                let i = r.below(bytes.len());
                let alphabet = b" ,;:()\"#*/=-+0123456789.abcdefghijklmnopqrstuvwxyz";
                bytes[i] = alphabet[r.below(alphabet.len())];
            }
            text = String::from_utf8_lossy(&bytes).into_owned();
            text
        },
        0xD1B5_4A32_D192_ED03,
        "mutated example",
    );
    assert!(n > 100, "only {n} inputs");
}

/// Drive caller and scalar function cards that name earlier cards at random (issue 32's
/// grammar: `reference`, `array`, `mult`, `drive`, string drives calling `model::drive` and
/// `model::sf`, `sum`/`sub`/`mul`/`div` of functions), up to 300 cards, so that chains
/// deeper than the limits and doubling trees come up; `set:` cards then evaluate the last
/// drive and function while the file is read. A stack overflow aborts the test process,
/// an unbounded tree exhausts its memory: the limits must stop both with an error.
#[test]
fn random_chains_of_drives_and_functions_never_panic() {
    let n = run(
        |r| {
            let cards = 1 + r.below(300);
            let mut s = String::from("scalar function: \"f0\", const, 1.;\ndrive caller: 1, sine, 0., 1., 1., forever, 0.;\n");
            for k in 1..cards {
                // A card k' < k, mostly the previous one (deep chains) or any (trees).
                let earlier = |r: &mut Rng| if r.below(3) == 0 { r.below(k) } else { k - 1 };
                let (a, b) = (earlier(r), earlier(r));
                let f = match r.below(6) {
                    0 => format!("sum, \"f{a}\", \"f{b}\""),
                    1 => format!("mul, \"f{a}\", \"f{a}\""),
                    2 => format!("div, \"f{a}\", \"f{b}\""),
                    3 => format!("sub, \"f{a}\", \"f{b}\""),
                    4 => format!("linear, 0., {a}., 1., {b}."),
                    _ => format!("const, {}", r.pick(NUMBERS)),
                };
                let _ = writeln!(s, "scalar function: \"f{k}\", {f};");
                let (a, b) = (a + 1, b + 1);
                let d = match r.below(8) {
                    0 => format!("reference, {a}"),
                    1 => format!("array, 2, reference, {a}, reference, {b}"),
                    2 => format!("mult, reference, {a}, reference, {b}"),
                    3 => format!("drive, reference, {a}, reference, {b}"),
                    4 => format!("string, \"model::drive({a}, Time) + model::drive({b}, 2.*Time)\""),
                    5 => format!("string, \"model::sf::f{k}(Time) * {}\"", r.pick(NUMBERS)),
                    6 => format!("scalar function, \"f{k}\""),
                    _ => format!("array, 3, reference, {a}, reference, {b}, const, {}", r.pick(NUMBERS)),
                };
                let _ = writeln!(s, "drive caller: {}, {d};", k + 1);
            }
            let _ = writeln!(s, "set: real x = model::drive({cards}, 0.5);\nset: real y = model::sf::f{}(0.5);", cards - 1);
            format!(
                "begin: data; problem: initial value; end: data;\n{s}\
                 begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-2; end: initial value;\n\
                 begin: control data; structural nodes: 1; rigid bodies: 1; forces: 1; end: control data;\n\
                 begin: nodes; structural: 1, dynamic, null, eye, null, null; end: nodes;\n\
                 begin: elements; body: 1, 1, 1., null, eye; force: 1, absolute, 1, position, null, 1., 0., 0., reference, {cards}; end: elements;"
            )
        },
        0x6A09_E667_F3BC_C908,
        "drive and function chain",
    );
    assert!(n > 20, "only {n} inputs");
}
