//! The documentation against the program (issue 31): README.md and the book (docs/src/**/*.md).
//!
//! - Every `romdyn …` command line of a `sh`, `bash`, `shell` or `console` code block (and
//!   every `$ romdyn …` line of a `text` block) parses with the current CLI: the binary is
//!   run with `ROMDYN_PARSE_ONLY=1`, which stops once clap has parsed the arguments.
//! - Every input file such a command names exists in the repository, or is one the book
//!   says how to make (`GENERATED`).
//! - Every relative link and image of those files points to an existing file, and every
//!   `#anchor` to a heading of its target (mdBook's and GitHub's heading ids); the book's
//!   links stay inside docs/src (the HTML book holds nothing else); every chapter file is
//!   listed in SUMMARY.md.
//! - The cheapest documented commands (`SHOWN`) are run, and the output the book shows under
//!   them is what romdyn prints: line by line, numbers to 1e-6 relative (rounding-level
//!   values below 1e-9 agree with each other), `…` standing for lines or words left out.
//!
//! Failures name the file and line. No mdBook, Python or network: mdBook's build runs in
//! .ci/run.

use std::collections::BTreeSet;
use std::path::{Component, Path, PathBuf};
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Input files the book's commands name that are not in the repository, and where each
/// comes from: an earlier documented command, or a test that writes it.
enum Source {
    /// The `romdyn` arguments of a documented command that writes the file.
    Command(&'static str),
    /// A file of the repository that writes it, and a string it must contain.
    Writer(&'static str, &'static str),
}

const GENERATED: &[(&str, Source)] = &[
    ("out/pendulum_0.m", Source::Command("run examples/pendulum.mbd -o out")),
    ("chain_100.mbd", Source::Writer("tests/eigen/sparse_cli.rs", "chain_{n}.mbd")),
    ("m.mbd", Source::Writer("tests/mbdyn/mbdyn_errors.rs", "m.mbd")),
];

/// Options whose value is a file romdyn writes (not an input that must exist).
const OUTPUT_OPTIONS: &[&str] = &["-o", "--out", "--bode", "--report", "--grid", "--transmissibility", "--imposed-out", "--table", "--plot", "--interpolated"];

/// Extensions of the files romdyn reads or writes; a token with one of these (or a `/`) is a path.
const FILE_EXTENSIONS: &[&str] = &[".mbd", ".json", ".m", ".mtx", ".mat", ".npz", ".csv"];

/// Commands run in order in one scratch folder (with `examples/` beside them); the output the
/// book shows under each one marked `true` must be what it prints. Cheap: a few seconds in all.
const SHOWN: &[(&str, bool)] = &[
    ("eig examples/pendulum.mbd", true),
    ("eig examples/double_pendulum.mbd", true),
    ("eig --pencil examples/two_masses.json --route direct", true),
    ("check examples/pendulum.mbd", true),
    ("rom examples/pendulum.mbd --input 2:Mz --output 2:rz --count 1 -o out/pendulum_rom.npz", true),
    ("freq examples/pendulum.mbd --input 2:Mz --output 2:rz --count 1 -o out/pendulum_freq", true),
    ("rom examples/simply_supported_beam.mbd --static --input 5:Fy --output 5:y --count 1 --residualize-modes 7 -o out/beam_rom.mat --bode out/beam_bode", true),
    ("run examples/pendulum.mbd -o out", false),
    ("rom --pencil out/pendulum_0.m --input-row 18 --output-col 12 --count 1 -o out/pendulum_pencil_rom.mat", true),
];

/// A Markdown file of the documentation, by its path relative to the repository.
struct Doc {
    path: PathBuf,
    text: String,
}

impl Doc {
    fn at(&self, line: usize) -> String {
        format!("{}:{line}", self.path.display())
    }
}

fn docs() -> Vec<Doc> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "md") {
                out.push(p);
            }
        }
    }
    let root = Path::new(ROOT);
    let mut paths = vec![root.join("README.md")];
    walk(&root.join("docs/src"), &mut paths);
    paths.into_iter().map(|p| Doc { text: std::fs::read_to_string(&p).unwrap(), path: p.strip_prefix(root).unwrap().to_path_buf() }).collect()
}

/// A fenced code block: its language and its lines with their 1-based line numbers.
struct Block {
    lang: String,
    lines: Vec<(usize, String)>,
}

/// The fenced code blocks of a Markdown text, and the lines outside them.
fn split_blocks(text: &str) -> (Vec<Block>, Vec<(usize, String)>) {
    let (mut blocks, mut prose) = (Vec::new(), Vec::new());
    let mut open: Option<Block> = None;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let fence = line.trim_start().starts_with("```");
        match open.take() {
            Some(b) if fence => blocks.push(b),
            Some(mut b) => {
                b.lines.push((n, line.to_string()));
                open = Some(b);
            }
            None if fence => open = Some(Block { lang: line.trim_start().trim_start_matches('`').trim().to_string(), lines: Vec::new() }),
            None => prose.push((n, line.to_string())),
        }
    }
    assert!(open.is_none(), "a code block is not closed");
    (blocks, prose)
}

/// Splits a shell line into words (single and double quotes, backslash escapes) and cuts it
/// at `&&`, `||`, `;` and `|` outside quotes, and at a `#` comment.
fn shell_commands(line: &str) -> Vec<Vec<String>> {
    let (mut commands, mut words, mut word) = (Vec::new(), Vec::new(), String::new());
    let (mut in_word, mut quote) = (false, None::<char>);
    let mut chars = line.chars().peekable();
    let end_word = |words: &mut Vec<String>, word: &mut String, in_word: &mut bool| {
        if *in_word {
            words.push(std::mem::take(word));
            *in_word = false;
        }
    };
    while let Some(c) = chars.next() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                in_word = true;
            }
            (None, '\\') => {
                if let Some(n) = chars.next() {
                    word.push(n);
                    in_word = true;
                }
            }
            (None, '#') if !in_word => break,
            (None, ';' | '&' | '|') => {
                end_word(&mut words, &mut word, &mut in_word);
                while chars.peek().is_some_and(|&n| n == '&' || n == '|') {
                    chars.next();
                }
                commands.push(std::mem::take(&mut words));
            }
            (None, c) if c.is_whitespace() => end_word(&mut words, &mut word, &mut in_word),
            (None, c) => {
                word.push(c);
                in_word = true;
            }
        }
    }
    end_word(&mut words, &mut word, &mut in_word);
    commands.push(words);
    commands.into_iter().filter(|w| !w.is_empty()).collect()
}

/// Lines shown under a command: where each is, and its text.
type Shown = Vec<(String, String)>;

/// A documented `romdyn` command: where it is, its arguments, and the output shown under it.
struct DocCommand {
    at: String,
    args: Vec<String>,
    shown: Shown,
}

fn commands(doc: &Doc) -> Vec<DocCommand> {
    let (blocks, _) = split_blocks(&doc.text);
    let mut out = Vec::new();
    for b in blocks {
        let shell = matches!(b.lang.as_str(), "sh" | "bash" | "shell" | "console");
        let prompted = b.lines.iter().any(|(_, l)| l.starts_with("$ "));
        if !(shell || (b.lang == "text" && prompted)) {
            continue;
        }
        // Command lines (continuations joined) with the lines shown after each.
        let mut entries: Vec<(usize, String, Shown)> = Vec::new();
        let mut continued = false;
        for (n, line) in &b.lines {
            if continued {
                let last = entries.last_mut().unwrap();
                last.1 = format!("{} {}", last.1.trim_end_matches('\\'), line.trim());
            } else if prompted {
                match line.strip_prefix("$ ") {
                    Some(cmd) => entries.push((*n, cmd.to_string(), Vec::new())),
                    None => {
                        if let Some(last) = entries.last_mut() {
                            last.2.push((doc.at(*n), line.clone()));
                        }
                    }
                }
            } else if !line.trim().is_empty() && !line.trim_start().starts_with('#') {
                entries.push((*n, line.clone(), Vec::new()));
            } else {
                continue;
            }
            continued = entries.last().is_some_and(|e| e.1.ends_with('\\'));
        }
        for (n, line, shown) in entries {
            for words in shell_commands(&line) {
                if words[0] == "romdyn" {
                    out.push(DocCommand { at: doc.at(n), args: words[1..].to_vec(), shown: shown.clone() });
                }
            }
        }
    }
    out
}

fn all_commands() -> Vec<DocCommand> {
    let cmds: Vec<DocCommand> = docs().iter().flat_map(commands).collect();
    // The extraction itself: the README's two commands and the book's are found.
    assert!(cmds.len() >= 20, "only {} romdyn commands found in the documentation", cmds.len());
    cmds
}

fn romdyn() -> Command {
    Command::new(env!("CARGO_BIN_EXE_romdyn"))
}

#[test]
fn every_documented_command_parses() {
    let cmds = all_commands();
    for c in &cmds {
        let out = romdyn().args(&c.args).env("ROMDYN_PARSE_ONLY", "1").current_dir(ROOT).output().unwrap();
        assert!(out.status.success(), "{}: `romdyn {}` does not parse with the current CLI:\n{}", c.at, c.args.join(" "), String::from_utf8_lossy(&out.stderr));
        assert!(out.stdout.is_empty(), "{}: ROMDYN_PARSE_ONLY printed something for `romdyn {}`", c.at, c.args.join(" "));
    }
    // The switch is what the test relies on: a wrong option still fails under it.
    let bad = romdyn().args(["eig", "examples/pendulum.mbd", "--no-such-option"]).env("ROMDYN_PARSE_ONLY", "1").output().unwrap();
    assert_eq!(bad.status.code(), Some(2), "{}", String::from_utf8_lossy(&bad.stderr));
}

/// Whether a command word is a file path: it contains a `/` or ends with a file extension.
fn is_path(word: &str) -> bool {
    !word.starts_with('-') && (word.contains('/') || FILE_EXTENSIONS.iter().any(|e| word.ends_with(e)))
}

#[test]
fn every_file_a_documented_command_reads_exists() {
    let cmds = all_commands();
    let documented: BTreeSet<String> = cmds.iter().map(|c| c.args.join(" ")).collect();
    for (path, source) in GENERATED {
        match source {
            Source::Command(args) => assert!(documented.contains(*args), "{path}: the command said to write it, `romdyn {args}`, is no longer in the documentation"),
            Source::Writer(file, needle) => {
                let text = std::fs::read_to_string(Path::new(ROOT).join(file)).unwrap_or_default();
                assert!(text.contains(needle), "{path}: {file} no longer writes it (no `{needle}` in it)");
            }
        }
    }
    for c in &cmds {
        let mut words = c.args.iter().peekable();
        while let Some(w) = words.next() {
            if OUTPUT_OPTIONS.contains(&w.as_str()) {
                words.next();
                continue;
            }
            if OUTPUT_OPTIONS.iter().any(|o| w.starts_with(&format!("{o}="))) {
                continue;
            }
            let value = w.split_once('=').filter(|_| w.starts_with("--")).map_or(w.as_str(), |(_, v)| v);
            if is_path(value) && !Path::new(ROOT).join(value).exists() && !GENERATED.iter().any(|(p, _)| p == &value) {
                panic!("{}: `romdyn {}` reads {value}, which is not in the repository (a file the book makes goes in GENERATED, with where it comes from)", c.at, c.args.join(" "));
            }
        }
    }
}

/// mdBook's heading id (GitHub's is the same for these headings): the heading's text without
/// its Markdown marks, lowercased, spaces to `-`, everything else but letters, digits, `-`
/// and `_` dropped; a repeated id gets `-1`, `-2`, ….
fn heading_ids(text: &str) -> BTreeSet<String> {
    let (_, prose) = split_blocks(text);
    let mut ids = BTreeSet::new();
    for (_, line) in prose {
        let Some(rest) = line.strip_prefix('#') else { continue };
        let title = rest.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let plain: String = title.trim().chars().filter(|c| *c != '`' && *c != '*').collect();
        let id: String = plain.chars().filter_map(|c| if c.is_alphanumeric() || c == '_' || c == '-' { Some(c.to_lowercase().next().unwrap()) } else if c.is_whitespace() { Some('-') } else { None }).collect();
        let mut unique = id.clone();
        let mut k = 1;
        while ids.contains(&unique) {
            unique = format!("{id}-{k}");
            k += 1;
        }
        ids.insert(unique);
    }
    ids
}

/// The targets of the Markdown links and images of a line, outside inline code spans.
fn link_targets(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut outside = String::new();
    for (i, part) in line.split('`').enumerate() {
        outside.push_str(if i % 2 == 0 { part } else { " " });
    }
    let mut rest = outside.as_str();
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        let Some(end) = after.find(')') else { break };
        out.push(after[..end].trim().to_string());
        rest = &after[end..];
    }
    out
}

/// `a/./b/../c` as `a/c`, without touching the file system.
fn normalize(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

#[test]
fn every_link_and_image_points_to_a_file_and_anchor() {
    let root = Path::new(ROOT);
    let book = Path::new("docs/src");
    let mut checked = 0;
    for doc in docs() {
        let (_, prose) = split_blocks(&doc.text);
        for (n, line) in prose {
            for target in link_targets(&line) {
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                let (file, anchor) = target.split_once('#').map_or((target.as_str(), None), |(f, a)| (f, Some(a)));
                let resolved = if file.is_empty() { doc.path.clone() } else { normalize(&doc.path.parent().unwrap().join(file)) };
                assert!(root.join(&resolved).is_file(), "{}: the link `{target}` points to {}, which does not exist", doc.at(n), resolved.display());
                if doc.path.starts_with(book) {
                    assert!(resolved.starts_with(book), "{}: the link `{target}` leaves docs/src, which the HTML book does not hold", doc.at(n));
                }
                if let Some(anchor) = anchor {
                    let text = std::fs::read_to_string(root.join(&resolved)).unwrap();
                    assert!(heading_ids(&text).contains(anchor), "{}: `{target}`: {} has no heading with the id `{anchor}` (ids: {:?})", doc.at(n), resolved.display(), heading_ids(&text));
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 50, "only {checked} links found");
    // Every chapter file is in the book's summary.
    let summary = std::fs::read_to_string(root.join("docs/src/SUMMARY.md")).unwrap();
    let listed: BTreeSet<PathBuf> = summary.lines().flat_map(link_targets).map(|t| book.join(t)).collect();
    for doc in docs().iter().filter(|d| d.path.starts_with(book) && !d.path.ends_with("SUMMARY.md")) {
        assert!(listed.contains(&doc.path), "{}: not listed in docs/src/SUMMARY.md, so mdBook leaves it out", doc.path.display());
    }
}

/// A shown word matches a printed one: equal, or numbers within 1e-6 relative (both below
/// 1e-9 in size when they are rounding: error estimates, zero real parts).
fn word_matches(shown: &str, printed: &str) -> bool {
    if shown == printed {
        return true;
    }
    let number = |w: &str| w.trim_start_matches(['±', '(']).trim_end_matches([',', ';', ')', ':']).parse::<f64>().ok();
    let affixes = |w: &str| (w.chars().take_while(|c| *c == '±' || *c == '(').collect::<String>(), w.chars().rev().take_while(|c| matches!(c, ',' | ';' | ')' | ':')).collect::<String>());
    match (number(shown), number(printed)) {
        (Some(a), Some(b)) if affixes(shown) == affixes(printed) => (a - b).abs() <= 1e-6 * a.abs().max(b.abs()) || (a.abs() < 1e-9 && b.abs() < 1e-9),
        _ => false,
    }
}

/// A shown line matches a printed one word by word; a `…` word stands for any words.
fn line_matches(shown: &[&str], printed: &[&str]) -> bool {
    match shown.split_first() {
        None => printed.is_empty(),
        Some((&"…", rest)) => (0..=printed.len()).any(|k| line_matches(rest, &printed[k..])),
        Some((w, rest)) => printed.split_first().is_some_and(|(p, prest)| word_matches(w, p) && line_matches(rest, prest)),
    }
}

/// The shown lines must be printed in order, each right after the previous one unless a
/// line `…` stands between them for lines left out.
fn check_shown(cmd: &str, shown: &[(String, String)], printed: &str) {
    let printed: Vec<&str> = printed.lines().collect();
    let mut next = 0;
    let mut skipping = false;
    for (at, line) in shown {
        if line.trim() == "…" {
            skipping = true;
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let found = (next..printed.len()).take(if skipping { usize::MAX } else { 1 }).find(|&k| line_matches(&words, &printed[k].split_whitespace().collect::<Vec<_>>()));
        let Some(k) = found else {
            panic!("{at}: the book shows\n    {line}\nbut `romdyn {cmd}` prints{}:\n{}", if skipping { " (none of its next lines match)" } else { " here" }, printed[next.min(printed.len())..].iter().take(12).map(|l| format!("    {l}")).collect::<Vec<_>>().join("\n"));
        };
        next = k + 1;
        skipping = false;
    }
}

#[test]
fn the_output_shown_for_the_cheapest_commands_is_what_romdyn_prints() {
    let cmds = all_commands();
    let dir = std::env::temp_dir().join(format!("romdyn-docs-commands-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("out")).unwrap();
    std::os::unix::fs::symlink(Path::new(ROOT).join("examples"), dir.join("examples")).unwrap();
    for (args, compare) in SHOWN {
        let shown: Vec<&DocCommand> = cmds.iter().filter(|c| c.args.join(" ") == *args && !c.shown.is_empty()).collect();
        if *compare {
            assert!(!shown.is_empty(), "`romdyn {args}` with its output is no longer in the documentation: update SHOWN in tests/cli/docs_commands.rs");
        }
        // Standard output and error into one file, interleaved as a terminal shows them
        // (romdyn's summaries go to standard error when standard output may carry JSON).
        let log = dir.join("printed.txt");
        let file = std::fs::File::create(&log).unwrap();
        let status = romdyn().args(args.split(' ')).current_dir(&dir).stdout(file.try_clone().unwrap()).stderr(file).status().unwrap();
        let printed = std::fs::read_to_string(&log).unwrap();
        assert!(status.success(), "`romdyn {args}` failed:\n{printed}");
        if *compare {
            for c in shown {
                check_shown(args, &c.shown, &printed);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_extraction_reads_shell_lines_as_a_shell_would() {
    let words = |l: &str| shell_commands(l);
    assert_eq!(words("cargo install --path . && romdyn rom a.mbd -o out/x.mat # comment"), vec![vec!["cargo", "install", "--path", "."], vec!["romdyn", "rom", "a.mbd", "-o", "out/x.mat"]]);
    assert_eq!(words("octave-cli --eval 'source(\"a.m\"); size(A)' | head"), vec![vec!["octave-cli", "--eval", "source(\"a.m\"); size(A)"], vec!["head"]]);
    assert_eq!(words("romdyn sweep f.mbd --set N=0:8000:17"), vec![vec!["romdyn", "sweep", "f.mbd", "--set", "N=0:8000:17"]]);
    assert!(line_matches(&["a", "1.0e0", "…"], &["a", "1.0000001e0", "b", "c"]));
    assert!(!line_matches(&["a", "1.0e0"], &["a", "1.1e0"]));
    assert!(line_matches(&["1.8e-14"], &["2.3e-14"]));
    assert!(heading_ids("# A\n## The beam update: `--beam-update`\n## MBDyn's x\n").contains("the-beam-update---beam-update"));
    assert!(heading_ids("## MBDyn's x\n").contains("mbdyns-x"));
}
