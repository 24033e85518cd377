//! Bounded fuzzing of the JSON pencil, Matrix Market and Octave `.m` readers, as
//! tests/reliability/mbdyn_fuzz.rs does for the MBDyn reader: random mutations of valid files and
//! random token streams of each format's words. Every input must give a value or an error,
//! never a panic (a panic prints the input). Each generator runs for a fixed share of a
//! few seconds (deterministic seeded xorshift); for a longer local run:
//! `ROMDYN_FUZZ_SECONDS=60 ROMDYN_FUZZ_SEED=7 cargo test --test reliability reader_fuzz`. The
//! cargo-fuzz targets in fuzz/ cover the same readers with coverage guidance.

use std::path::Path;
use std::time::{Duration, Instant};

use romdyn::input::eigen_pencil::{pencil_from_script, PencilPorts};
use romdyn::input::matrix_market::parse_matrix;
use romdyn::input::octave_m::parse_octave_script;
use romdyn::input::pencil::parse_pencil;

use crate::common;

use common::fuzz::Rng;

fn budget() -> Duration {
    common::fuzz::budget(Duration::from_millis(1000))
}

/// A random edit of `text`: insert a word, delete or duplicate a span, replace a number.
fn mutate(r: &mut Rng, text: &str, words: &[&str]) -> String {
    let mut s: Vec<char> = text.chars().collect();
    for _ in 0..1 + r.below(4) {
        let at = r.below(s.len() + 1);
        match r.below(4) {
            0 => s.splice(at..at, r.pick(words).chars()).for_each(drop),
            1 => {
                let end = (at + r.below(12)).min(s.len());
                s.drain(at..end);
            }
            2 => {
                let end = (at + r.below(30)).min(s.len());
                let piece: Vec<char> = s[at..end].to_vec();
                s.splice(at..at, piece).for_each(drop);
            }
            _ => {
                if at < s.len() {
                    s[at] = r.pick(&["0", "9", "-", ".", "e", "\n", " ", "[", "]", ",", ";", "\"", "%"]).chars().next().unwrap_or(' ');
                }
            }
        }
    }
    s.into_iter().collect()
}

fn run(seed: u64, what: &str, mut make: impl FnMut(&mut Rng) -> String, read: impl Fn(&str)) -> usize {
    let mut r = Rng::seeded(seed);
    let start = Instant::now();
    let mut n = 0;
    while start.elapsed() < budget() {
        let text = make(&mut r);
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| read(&text))).is_err() {
            panic!("the {what} reader panicked on:\n-----\n{text}\n-----");
        }
        n += 1;
    }
    eprintln!("{what}: {n} inputs in {:?}", start.elapsed());
    n
}

const NUMBERS: &[&str] = &["0", "1", "-1", "2", "3", "1e308", "-1e308", "1e-320", "4294967297", "99999", "100000", "1.5", "NaN", "Inf", "-0", "7071"];

#[test]
fn matrix_market_never_panics() {
    let seeds = [
        "%%MatrixMarket matrix coordinate real symmetric\n% c\n3 3 3\n1 1 4\n2 1 -1\n3 3 2.5\n",
        "%%MatrixMarket matrix array real skew-symmetric\n3 3\n1\n2\n3\n",
        "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n",
        "%%MatrixMarket matrix coordinate pattern general\n2 3 2\n1 1\n2 3\n",
    ];
    let words: Vec<&str> = NUMBERS.iter().copied().chain(["coordinate", "array", "real", "integer", "pattern", "general", "symmetric", "skew-symmetric", "%%MatrixMarket matrix", "\n"]).collect();
    let n = run(0x5DEE_CE66_D1CE_4E5B, "Matrix Market", |r| {
        let seed = seeds[r.below(seeds.len())];
        mutate(r, seed, &words)
    }, |t| {
        let _ = parse_matrix(t, Path::new("f.mtx"));
    });
    assert!(n > 100, "only {n} inputs");
}

#[test]
fn octave_scripts_never_panic() {
    let seeds = [
        "dCoef = 0.5;\nT = [1 1 2.0; 2 2 -1; 3 1 1e-3];\nAplus = spconvert(T);\nAminus = zeros(3, 3);\n",
        "dCoef = 1;\nAplus = [1 0; 0 1];\nAminus = [1 0; 0 -1];\nalpha = [1+i*2, -Inf, NaN];\n",
    ];
    let words: Vec<&str> = NUMBERS.iter().copied().chain(["zeros(", "spconvert(", "Aplus", "Aminus", "dCoef", "T", "=", ";", "[", "]", "+i*", "%", "#", "\n"]).collect();
    let n = run(0x1234_5678_9ABC_DEF1, "Octave", |r| {
        let seed = seeds[r.below(seeds.len())];
        mutate(r, seed, &words)
    }, |t| {
        if let Ok(s) = parse_octave_script(t, Path::new("f.m")) {
            let _ = pencil_from_script(&s, &PencilPorts { input_rows: vec![1], output_cols: vec![2] });
        }
    });
    assert!(n > 100, "only {n} inputs");
}

#[test]
fn json_pencils_never_panic() {
    let seeds = [
        r#"{"Fyd": [[1, 0], [0, 1]], "Fy": [[0, -1], [4, 0]], "B": [[1], [0]], "C": [[1, 0]], "input_names": ["u"], "output_names": ["z"]}"#,
        r#"{"J": [[1, 0], [0, 1]], "Jstar": [[1, 0], [0, -1]], "dcoef": 0.5, "B": [[1], [0]], "C": [[0, 1]], "unknown_names": ["a", "b"]}"#,
    ];
    let words: Vec<&str> = NUMBERS.iter().copied().chain(["\"Fyd\"", "\"Fy\"", "\"J\"", "\"Jstar\"", "\"dcoef\"", "\"B\"", "\"C\"", "{\"matrix_market\": \"x.mtx\"}", "[", "]", "{", "}", ",", ":", "null", "true"]).collect();
    let n = run(0x0F0F_1234_ABCD_9876, "JSON pencil", |r| {
        let seed = seeds[r.below(seeds.len())];
        mutate(r, seed, &words)
    }, |t| {
        let _ = parse_pencil(t, Path::new("no-such-folder/f.json"));
    });
    assert!(n > 100, "only {n} inputs");
}

#[test]
fn ports_files_never_panic() {
    let seeds = [
        r#"{"names": {"1": "base", "3": "table"}, "inputs": ["3:Fz", {"name": "H1", "type": "actuator", "from": 1, "to": 2, "at": [0.95, 0, 0.5], "direction": [0, 1, 0]}], "outputs": [{"name": "g", "type": "velocity", "node": 3, "at": [0.9, 0, 1], "direction": [1, 0, 0]}, "2:rz"], "remove_springs": [901], "imposed": "1"}"#,
        r#"{"inputs": [{"type": "force", "node": 3, "offset": [0.5, 0, 0], "direction": [0, 0, 1], "frame": "node"}, {"type": "moment", "node": 3, "direction": [0, 1, 0]}], "outputs": [{"type": "relative", "from": 1, "to": 2, "direction": [0, 1, 0]}, {"type": "rotation", "node": 3, "direction": [0, 1, 0]}]}"#,
    ];
    let words: Vec<&str> = NUMBERS.iter().copied().chain(["\"names\"", "\"inputs\"", "\"outputs\"", "\"type\"", "\"actuator\"", "\"force\"", "\"velocity\"", "\"node\"", "\"direction\"", "\"at\"", "\"1:Fx\"", "\"2:ry\"", "[", "]", "{", "}", ",", ":"]).collect();
    let n = run(0x7777_1234_5555_AAAA, "ports", |r| {
        let seed = seeds[r.below(seeds.len())];
        mutate(r, seed, &words)
    }, |t| {
        let _ = romdyn::input::ports_file::parse_ports(t, Path::new("ports.json"));
    });
    assert!(n > 100, "only {n} inputs");
}
