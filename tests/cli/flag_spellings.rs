//! The library's messages name settings by the command line's flags, and the Python package
//! respells them as its keyword arguments (`romdyn::study::python_spelling`, issue 31). This
//! holds the two together: every flag a library message spells (a string literal anywhere in
//! `src/` outside the CLI) is a flag the command line has, and one the respelling knows —
//! a setting of `romdyn::study::Setting` or a flag marked as the command line's own. A flag
//! added to a message without its Python name, or misspelt (`--amplitude` for
//! `--amplitudes`), fails here.

use std::collections::BTreeSet;
use std::path::Path;

use romdyn::study::{Setting, COMMAND_LINE_ONLY};

use crate::common::cli::romdyn;

const SUBCOMMANDS: [&str; 8] = ["run", "check", "eig", "rom", "freq", "sweep", "validate", "cms"];

/// The string literals of a Rust source, without comments (a small lexer: `"…"` with `\`
/// escapes, `r"…"`/`r#"…"#`, `'"'` and `//`, `/* */` comments skipped).
fn string_literals(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let (mut i, mut out) = (0, Vec::new());
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => i = text[i..].find('\n').map_or(b.len(), |n| i + n),
            b'/' if b.get(i + 1) == Some(&b'*') => i = text[i + 2..].find("*/").map_or(b.len(), |n| i + n + 4),
            b'\'' if b.get(i + 2) == Some(&b'\'') => i += 3,
            b'\'' if b.get(i + 1) == Some(&b'\\') => i = text[i + 3..].find('\'').map_or(b.len(), |n| i + n + 4),
            b'r' if matches!(b.get(i + 1), Some(b'"') | Some(b'#')) && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) => {
                let hashes = b[i + 1..].iter().take_while(|c| **c == b'#').count();
                let open = i + 1 + hashes;
                if b.get(open) != Some(&b'"') {
                    i += 1;
                    continue;
                }
                let close = format!("\"{}", "#".repeat(hashes));
                let end = text[open + 1..].find(&close).map_or(b.len(), |n| open + 1 + n);
                out.push(text[open + 1..end.min(b.len())].to_string());
                i = end + close.len();
            }
            b'"' => {
                let mut j = i + 1;
                while j < b.len() && b[j] != b'"' {
                    j += if b[j] == b'\\' { 2 } else { 1 };
                }
                out.push(text[i + 1..j.min(b.len())].to_string());
                i = j + 1;
            }
            _ => i += 1,
        }
    }
    out
}

/// `--word` flags in a text (a word of lowercase letters, digits and inner hyphens after
/// `--` that does not follow a letter: not `x--y`, not a bare `--`).
fn flags(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    let mut rest = text;
    let mut before: Option<char> = None;
    while let Some(at) = rest.find("--") {
        let prev = rest[..at].chars().last().or(if at == 0 { before } else { None });
        let name: String = rest[at + 2..].chars().take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '-').collect();
        let name = name.trim_end_matches('-');
        if !name.is_empty() && name.starts_with(|c: char| c.is_ascii_lowercase()) && !prev.is_some_and(|c| c.is_alphanumeric() || c == '-') {
            found.push(format!("--{name}"));
        }
        before = Some('-');
        rest = &rest[at + 2..];
    }
    found
}

/// The library's Rust sources under `dir` (`src/`, `core/src/`, `input/src/`; not the command line's
/// `src/cli`, not `main.rs`).
pub(crate) fn library_sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if !path.ends_with("cli") {
                library_sources(&path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") && !path.ends_with("main.rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_lexer_and_the_flag_finder_see_what_they_should() {
    let src = "let a = \"use --count 3\"; // not --this\n/* nor --that */ let c = '\"'; let r = r#\"raw --solver \"x\"\"#; f(\"a -- b, x--y\");";
    let lits = string_literals(src);
    assert_eq!(lits, ["use --count 3", "raw --solver \"x\"", "a -- b, x--y"]);
    let all: Vec<String> = lits.iter().flat_map(|l| flags(l)).collect();
    assert_eq!(all, ["--count", "--solver"]);
}

#[test]
fn every_flag_a_library_message_spells_is_a_flag_python_can_respell() {
    // The command line's flags, from each subcommand's --help.
    let mut cli = BTreeSet::new();
    for sub in SUBCOMMANDS {
        let (ok, out, err) = romdyn(&[sub, "--help"]);
        assert!(ok, "romdyn {sub} --help: {err}");
        cli.extend(flags(&out));
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    // The three crates' sources: the root's src/, the core's core/src/, the readers' input/src/.
    for dir in ["src", "core/src", "input/src"] {
        library_sources(&root.join(dir), &mut files);
    }
    assert!(files.len() > 100, "{} library files found under {}", files.len(), root.display());
    let mut unknown = Vec::new();
    let mut seen = BTreeSet::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for flag in string_literals(&text).iter().flat_map(|l| flags(l)) {
            seen.insert(flag.clone());
            let respelt = Setting::from_cli_flag(&flag).is_some() || COMMAND_LINE_ONLY.contains(&flag.as_str());
            if !cli.contains(&flag) || !respelt {
                unknown.push(format!("{}: {flag} ({})", file.strip_prefix(&root).unwrap().display(), if cli.contains(&flag) { "no Python spelling" } else { "not a flag of the command line" }));
            }
        }
    }
    assert!(unknown.is_empty(), "flags in library messages:\n{}", unknown.join("\n"));
    // The scan sees the library's advice (a scan that finds nothing cannot fail).
    for flag in ["--residualize", "--dcoef", "--amplitudes", "--below-band"] {
        assert!(seen.contains(flag), "{flag} not found in the library's messages: {seen:?}");
    }
}

#[test]
fn every_setting_and_command_line_flag_exists_on_the_command_line() {
    let mut cli = BTreeSet::new();
    for sub in SUBCOMMANDS {
        cli.extend(flags(&romdyn(&[sub, "--help"]).1));
    }
    for s in Setting::ALL {
        assert!(cli.contains(s.cli_flag()), "{s:?}: {} is no flag of the command line", s.cli_flag());
    }
    for flag in COMMAND_LINE_ONLY {
        assert!(cli.contains(flag), "{flag} is no flag of the command line");
    }
}
