//! The MBDyn reader's time per card (issue 32): generated files of 10^3, 10^4 and 10^5
//! cards of each kind (`set:`, `drive caller:` alone and alternating with `set:`, `string`
//! drives calling `model::drive`, `scalar function:`, structural nodes, elements, and
//! `include:` of one file per card), read into a model by `read_model_text`
//! (`read_model_with` for the includes). divan's items/s is cards per second: the reader
//! is linear when it is flat from 10^3 to 10^5 (issue 32 asks for within 2x).
//! `cargo bench --bench mbdyn_reader`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use romdyn::input::mbdyn::{read_model_text, read_model_with, SetOverrides};

fn main() {
    divan::main();
}

/// A model of one node and one body around `cards` (written before the blocks),
/// `nodes` (inside `begin: nodes;`) and `elements` (inside `begin: elements;`).
fn model(cards: &str, nodes: &str, elements: &str, structural: usize, bodies: usize, forces: usize) -> String {
    format!(
        "begin: data; problem: initial value; end: data;\n{cards}\
         begin: initial value; initial time: 0.; final time: 1.e-2; time step: 1.e-3; tolerance: 1.e-9; max iterations: 10; end: initial value;\n\
         begin: control data; structural nodes: {}; rigid bodies: {}; forces: {forces}; end: control data;\n\
         begin: nodes;\n    structural: 1, dynamic, null, eye, null, null;\n{nodes}end: nodes;\n\
         begin: elements;\n    body: 1, 1, 1., null, eye;\n{elements}end: elements;\n",
        structural + 1,
        bodies + 1
    )
}

/// The text of `n` cards of `kind`.
pub fn cards(kind: &str, n: usize) -> String {
    let mut s = String::new();
    match kind {
        "set" => {
            for k in 0..n {
                let _ = writeln!(s, "set: real v{k} = {k}. + 1.;");
            }
            model(&s, "", "", 0, 0, 0)
        }
        "drive caller" => {
            for k in 0..n {
                let _ = writeln!(s, "drive caller: {}, sine, 0., 1., {k}., forever, 0.;", k + 1);
            }
            model(&s, "", "", 0, 0, 0)
        }
        "set and string drive" => {
            // Issue 32: 800 such pairs took 24 s.
            for k in 0..n / 2 {
                let _ = writeln!(s, "set: real v{k} = {k}.;\ndrive caller: {}, string, \"v{k}*Time\";", k + 1);
            }
            model(&s, "", "", 0, 0, 0)
        }
        "string drive calling" => {
            // Each calls one of the 32 before it (depth within the limit).
            let _ = writeln!(s, "drive caller: 1, string, \"Time\";");
            for k in 1..n {
                let callee = if k % 32 == 0 { 1 } else { k };
                let _ = writeln!(s, "drive caller: {}, string, \"model::drive({callee}, Time) + 1.\";", k + 1);
            }
            model(&s, "", "", 0, 0, 0)
        }
        "scalar function" => {
            // Each adds one of the 32 before it to a constant (depth within the limit).
            let _ = writeln!(s, "scalar function: \"f0\", const, 1.;");
            for k in 1..n {
                let callee = if k % 32 == 0 { 0 } else { k - 1 };
                let _ = writeln!(s, "scalar function: \"f{k}\", sum, \"f{callee}\", \"f0\";");
            }
            model(&s, "", "", 0, 0, 0)
        }
        "nodes" => {
            let mut bodies = String::new();
            for k in 0..n {
                let _ = writeln!(s, "    structural: {}, dynamic, {}., 0., 0., eye, null, null;", k + 2, k + 1);
                let _ = writeln!(bodies, "    body: {}, {}, 1., null, eye;", k + 2, k + 2);
            }
            model("", &s, &bodies, n, n, 0)
        }
        "elements" => {
            for k in 0..n {
                let _ = writeln!(s, "    force: {}, absolute, 1, position, null, 1., 0., 0., const, {k}.;", k + 1);
            }
            model("", "", &s, 0, 0, n)
        }
        other => panic!("no card kind {other}"),
    }
}

/// `n` files of one `set:` card each, included one after the other by `main.mbd`, in a
/// fresh folder.
fn included(n: usize) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("romdyn-bench-include-{n}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temporary folder");
    let mut main = String::new();
    for k in 0..n {
        std::fs::write(dir.join(format!("inc{k}.mbd")), format!("set: real w{k} = {k}.;\n")).expect("include file");
        let _ = writeln!(main, "include: \"inc{k}.mbd\";");
    }
    std::fs::write(dir.join("main.mbd"), model(&main, "", "", 0, 0, 0)).expect("main file");
    dir
}

fn read(text: &str) {
    if let Err(e) = read_model_text(text, Path::new("bench.mbd"), &SetOverrides::new()) {
        panic!("{e}");
    }
}

const SIZES: [usize; 3] = [1_000, 10_000, 100_000];

#[divan::bench(args = SIZES, sample_count = 3)]
fn set(bencher: divan::Bencher, n: usize) {
    let text = cards("set", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn drive_caller(bencher: divan::Bencher, n: usize) {
    let text = cards("drive caller", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn set_and_string_drive(bencher: divan::Bencher, n: usize) {
    let text = cards("set and string drive", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn string_drive_calling(bencher: divan::Bencher, n: usize) {
    let text = cards("string drive calling", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn scalar_function(bencher: divan::Bencher, n: usize) {
    let text = cards("scalar function", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn nodes(bencher: divan::Bencher, n: usize) {
    let text = cards("nodes", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

#[divan::bench(args = SIZES, sample_count = 3)]
fn elements(bencher: divan::Bencher, n: usize) {
    let text = cards("elements", n);
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| read(&text));
}

/// One file per card: 10^5 files would be a folder of 10^5 files, so 10^3 and 10^4.
#[divan::bench(args = [1_000, 10_000], sample_count = 3)]
fn include(bencher: divan::Bencher, n: usize) {
    let dir = included(n);
    let main = dir.join("main.mbd");
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| {
        if let Err(e) = read_model_with(&main, &SetOverrides::new()) {
            panic!("{e}");
        }
    });
    let _ = std::fs::remove_dir_all(&dir);
}
