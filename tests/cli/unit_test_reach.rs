//! Unit tests stay local to their module (ARCHITECTURE.md, "A test"): the unit tests are
//! compiled into a binary of their own with every piece of the library they reach, so one
//! unit test that reads a model or solves its reference state compiles the reader, the
//! element constructors, the solvers and the outputs a second time (issue 36 point 5: one
//! such test took the unit-test binary from 26,192 to 48,922 monomorphized items, measured
//! with `-Zprint-mono-items`, and `cargo test`'s build from 150 to 196 CPU-seconds). This
//! finds the whole-model entry points in the `#[cfg(test)]` parts of `src/`, `core/src/` and
//! `input/src/` (each crate's unit tests are a binary of their own, the same way); such a test
//! belongs in `tests/`.

use std::path::Path;

use super::flag_spellings::library_sources;

/// Calls that read a model, run the reader or solve a whole analysis.
const WHOLE_MODEL_CALLS: [&str; 9] = ["read_model(", "read_model_text(", "read_model_with(", "parse_file(", "parse_text(", "parse_file_with(", "parse_text_with(", "reference_state(", "reference_state_with_warnings("];

/// The whole-model calls in the text after `#[cfg(test)]` (a module's tests sit at its end),
/// with their line numbers (1-based).
fn whole_model_calls_in_tests(text: &str) -> Vec<(usize, &'static str)> {
    let Some(start) = text.find("#[cfg(test)]") else { return Vec::new() };
    let first_line = text[..start].lines().count();
    text[start..]
        .lines()
        .enumerate()
        .filter(|(_, line)| !line.trim_start().starts_with("//"))
        .flat_map(|(k, line)| WHOLE_MODEL_CALLS.iter().filter(move |call| line.contains(*call) && !line.contains(&format!("_{call}"))).map(move |call| (first_line + k + 1, *call)))
        .collect()
}

/// The finder on a planted source: a call before the tests is the module's own code, one in
/// the tests is found with its line, a comment and a longer name that ends alike are not.
#[test]
fn the_finder_sees_a_whole_model_call_in_tests_only() {
    let src = "fn build() { read_model_text(t); }\n\n#[cfg(test)]\nmod tests {\n    // read_model(p) in a comment\n    fn t() { my_read_model(x); }\n    fn u() { let m = read_model_text(&text, p, &o); }\n}\n";
    assert_eq!(whole_model_calls_in_tests(src), vec![(7, "read_model_text(")]);
    assert!(whole_model_calls_in_tests("fn f() { parse_text(x) }").is_empty());
}

#[test]
fn no_unit_test_reads_a_model_or_solves_its_reference() {
    let mut files = Vec::new();
    for dir in ["src", "core/src", "input/src"] {
        library_sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join(dir), &mut files);
    }
    assert!(files.len() > 100, "{} sources found", files.len());
    let found: Vec<String> = files
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(f).unwrap();
            whole_model_calls_in_tests(&text).into_iter().map(move |(line, call)| format!("{}:{line}: {call}", f.display()))
        })
        .collect();
    assert!(found.is_empty(), "unit tests that read a model or solve a whole analysis (move them to tests/):\n{}", found.join("\n"));
}
