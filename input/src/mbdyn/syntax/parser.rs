//! Statements `keyword words: arg, arg, …;` grouped in `begin: NAME;` … `end: NAME;`
//! blocks (input manual, "Overview"), with the input-related cards handled as read
//! ("General", §Input Related Cards): `include: "file";`, `set: EXPR;`, `remark: …;`, and
//! the cards kept for the model (`reference:`, `drive caller:`, `constitutive law:`, …).
//!
//! Every argument is evaluated when its statement is read, in file order, as MBDyn does:
//! a `set:` further down does not change values above it.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use super::diagnostic::{MbdynError, Sources, Span};
use super::expr::{describe, reads_current, staticize_evals, Deferred, Evaluator, Reads, SetOverrides, Variables};
use super::lexer::{Lexer, Spanned, Token};
use super::value::TypedValue;
use crate::element::NodeKinematics;
use crate::limits::MAX_INCLUDE_DEPTH;

/// An evaluated argument.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Number(f64),
    /// One or more names, lowercased and joined by single spaces ("revolute hinge").
    Word(String),
    Str(String),
    /// An empty field (`1., , 3.`): MBDyn reads it as the default value, or zero.
    Empty,
    /// An argument of an element card that calls `model::current`, evaluated when the card
    /// reads it (see [`Deferred`]).
    Current(Box<Deferred>),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    pub value: Value,
    pub span: Span,
    /// The argument read as a keyword: set for names, even when a name is also a variable
    /// (keywords win where the syntax expects one, as in MBDyn).
    pub keyword: Option<String>,
    /// The argument's text as written (for messages).
    pub text: String,
}

/// `keyword: args;`, the keyword lowercased with single spaces.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    pub keyword: String,
    pub span: Span,
    pub args: Vec<Arg>,
    /// Where the terminating ';' is (for "missing argument" errors).
    pub end: Span,
    /// Position in the whole input (includes counted): entities defined by cards can only
    /// be used by statements that come later.
    pub seq: usize,
    /// The `driven: LABEL, DRIVE, …` head that wraps this element statement (its args up to
    /// the wrapped element's keyword), if any.
    pub driven: Option<Box<Statement>>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    pub name: String,
    pub span: Span,
    pub statements: Vec<Statement>,
}

/// A parsed input file.
#[derive(Debug, Default)]
pub struct Document {
    pub blocks: Vec<Block>,
    /// Cards that may appear anywhere: `reference`, `drive caller`, `constitutive law`, …
    pub cards: Vec<Statement>,
    pub sources: Sources,
    pub variables: Variables,
}

/// Cards allowed anywhere in the input ("General", §Input Related Cards), kept for `build`.
pub const CARDS: [&str; 10] = ["reference", "drive caller", "constitutive law", "template drive caller", "scalar function", "hydraulic fluid", "c81 data", "module load", "setenv", "print symbol table"];

/// Compares keywords the way MBDyn does: case and spaces do not matter
/// ("control data" = "Control Data" = "controldata").
pub fn same_keyword(a: &str, b: &str) -> bool {
    a.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_lowercase()).eq(b.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_lowercase()))
}

/// The phrase of `known` that `keyword` spells, if any.
pub fn known<'k>(keyword: &str, known: &[&'k str]) -> Option<&'k str> {
    known.iter().copied().find(|k| same_keyword(k, keyword))
}

/// What the layer above the parser learns from each statement as it is read, and gives back:
/// the structural nodes written so far, for the `model` namespace's state functions in
/// `set:`, `remark:` and the numbers of later statements (MBDyn evaluates them while it
/// reads, on the nodes it has read: `StructNode::GetXCurr` is the written position then).
/// Implemented by [`crate::mbdyn::written_nodes::WrittenNodes`] with the node readers, so the parser
/// does not depend on them.
pub trait StatementObserver {
    /// A statement just read (`in_nodes_block`: inside `begin: nodes;`), with the
    /// variables as they stand after it.
    fn statement(&mut self, st: &Statement, sources: &Sources, in_nodes_block: bool, variables: &Variables);
    /// The structural nodes written so far, by label.
    fn nodes(&self) -> &HashMap<u32, NodeKinematics>;
    /// The `scalar function:` cards read so far, by name (`model::sf::NAME(x)` in `set:`:
    /// MBDyn reads a card when it meets it).
    fn functions(&self) -> &super::card_tables::FunctionsBefore;
    /// The `drive caller:` cards read so far, by label (`model::drive(LABEL, x)` there).
    fn drives(&self) -> &super::card_tables::DrivesBefore;
    /// Makes [`StatementObserver::drives`] current for `variables` (the string drives of
    /// the cards read so far evaluate with the variables as they stand), before an
    /// evaluation calls `model::drive`: done only then, so that a file of N `set:` and
    /// N drive caller cards reads in O(N).
    fn refresh_drives(&mut self, variables: &Variables, sources: &Sources);
    /// The bodies and joints read so far (`model::element::TYPE(LABEL, "NAME")` there).
    fn elements(&self) -> &super::model_namespace::ElementsRead;
}

struct Reader {
    doc: Document,
    observer: Box<dyn StatementObserver>,
    /// The files being read, outermost first, each as given and canonical (for include
    /// loops: canonicalized once each, not at every include).
    stack: Vec<(PathBuf, PathBuf)>,
    open: Option<Block>,
    seq: usize,
    overrides: SetOverrides,
    /// The statement being read is an element card: an argument that calls
    /// `model::current` waits for the card's reader ([`Deferred`]).
    element_card: bool,
}

/// Reads and parses an MBDyn input file (and its includes), telling `observer` of each
/// statement; `set:` variables overridden by `overrides` (a name the file never declares is
/// an error).
pub fn parse_file_observed(path: &Path, overrides: &SetOverrides, observer: Box<dyn StatementObserver>) -> Result<Document, MbdynError> {
    let mut r = Reader::new(overrides, observer);
    r.read(path, None)?;
    r.finish(path)
}

/// [`parse_file_observed`] on text, as if it were the file `name` (includes resolve relative
/// to its folder).
pub fn parse_text_observed(text: &str, name: &Path, overrides: &SetOverrides, observer: Box<dyn StatementObserver>) -> Result<Document, MbdynError> {
    let mut r = Reader::new(overrides, observer);
    r.read_text(text.to_string(), name)?;
    r.finish(name)
}

impl Reader {
    fn new(overrides: &SetOverrides, observer: Box<dyn StatementObserver>) -> Self {
        Reader { doc: Document::default(), observer, stack: Vec::new(), open: None, seq: 0, overrides: overrides.clone(), element_card: false }
    }

    fn finish(mut self, path: &Path) -> Result<Document, MbdynError> {
        if let Some(b) = self.open.take() {
            return Err(self.doc.sources.error(b.span, format!("block '{}' is never closed: expected 'end: {};'", b.name, b.name)));
        }
        // An override of a variable the file never declares would change nothing: refuse it.
        self.doc.variables.check_declared(self.overrides.keys(), path)?;
        Ok(self.doc)
    }

    fn read(&mut self, path: &Path, from: Option<Span>) -> Result<(), MbdynError> {
        let text = crate::text_file::read_text_file(path).map_err(|e| match (from, e.at) {
            (Some(span), _) => self.doc.sources.error(span, format!("cannot include \"{}\": {}", path.display(), e.message)),
            (None, Some((line, column))) => MbdynError { file: path.to_path_buf(), line, column, message: e.message, source_line: String::new() },
            // Line 0: the error is about the whole file (printed without a position).
            (None, None) => MbdynError { file: path.to_path_buf(), line: 0, column: 0, message: e.message, source_line: String::new() },
        })?;
        self.read_text(text, path)
    }

    fn read_text(&mut self, mut text: String, path: &Path) -> Result<(), MbdynError> {
        // A UTF-8 byte-order mark (editors on Windows write one) is not part of the text.
        if text.starts_with('\u{feff}') {
            text.drain(..'\u{feff}'.len_utf8());
        }
        let preprocess = text.lines().position(|l| l.trim() == "#beginpreprocess").map(|k| k + 1);
        self.read_tokens(text, path).map_err(|mut e| {
            if let Some(line) = preprocess.filter(|&l| e.file == path && e.line >= l) {
                e.message = python_preprocessor_note(&e.message, line);
            }
            e
        })
    }

    fn read_tokens(&mut self, text: String, path: &Path) -> Result<(), MbdynError> {
        let file = self.doc.sources.files.len();
        self.doc.sources.files.push((path.to_path_buf(), text));
        self.stack.push((path.to_path_buf(), canonical(path)));
        // One statement's tokens at a time (the file's would be held together otherwise).
        // A statement ends at the first ';' outside parentheses (semicolons inside separate
        // the expressions of a statement list, `(real a = 1.; 2.*a)`); a ':' inside them
        // shows that the next statement began before a ')'.
        let mut lexer = Lexer::new(&self.doc.sources.files[file].1, file);
        let mut statement: Vec<Spanned> = Vec::new();
        let mut open: Vec<Span> = Vec::new();
        let unbalanced = "unbalanced parenthesis: expected ')' to close this '('";
        while let Some(t) = lexer.next_token(&self.doc.sources)? {
            match t.token {
                Token::Symbol("(" | "[") => open.push(t.span),
                Token::Symbol(")" | "]") => {
                    open.pop();
                }
                Token::Symbol(";") if open.is_empty() => {
                    self.statement(&statement, t.span, path)?;
                    statement.clear();
                    continue;
                }
                // A statement's ':' inside parentheses: a ')' is missing before it.
                Token::Symbol(":") if !open.is_empty() => return Err(self.doc.sources.error(open[0], unbalanced)),
                _ => {}
            }
            statement.push(t);
        }
        if let Some(last) = statement.last() {
            return Err(match open.first() {
                Some(&paren) => self.doc.sources.error(paren, unbalanced),
                None => self.doc.sources.error(last.span, "missing ';' at the end of this statement"),
            });
        }
        self.stack.pop();
        Ok(())
    }

    fn statement(&mut self, toks: &[Spanned], end: Span, path: &Path) -> Result<(), MbdynError> {
        let Some(first) = toks.first() else { return Err(self.doc.sources.error(end, "empty statement: expected a keyword before ';'")) };
        let colon = toks.iter().position(|t| t.token == Token::Symbol(":"));
        let head = &toks[..colon.unwrap_or(toks.len())];
        let mut keyword = String::with_capacity(24);
        for t in head {
            match &t.token {
                Token::Word(w) => {
                    if !keyword.is_empty() {
                        keyword.push(' ');
                    }
                    keyword.extend(w.chars().flat_map(char::to_lowercase));
                }
                other => return Err(self.doc.sources.error(t.span, format!("expected a keyword, found {}", describe(other)))),
            }
        }
        let body = colon.map_or(&[][..], |c| &toks[c + 1..]);
        self.seq += 1;
        match known(&keyword, &["include", "set", "begin", "end", "remark"]) {
            Some("include") => return self.include(body, first.span, end, path),
            Some("set") => {
                if body.is_empty() {
                    return Err(self.doc.sources.error(end, "set: expected an expression, e.g. 'set: real L = 1.;'"));
                }
                if calls_model_drive(body) {
                    self.observer.refresh_drives(&self.doc.variables, &self.doc.sources);
                }
                Evaluator::new(body, &mut self.doc.variables, &self.doc.sources, end).with_overrides(&self.overrides).with_reads(Reads::Nodes(self.observer.nodes()), None).with_functions(self.observer.functions()).with_drives(self.observer.drives()).with_elements(self.observer.elements()).evaluate()?;
                return Ok(());
            }
            Some(kw @ ("begin" | "end")) => return self.block(kw, body, first.span, end),
            Some(_) => {
                self.args(body, end)?;
                return Ok(());
            }
            None => {}
        }
        if known(&keyword, &["driven"]).is_some() {
            return self.driven(first.span, body, end, path);
        }
        self.element_card = known(&keyword, &CARDS).is_none() && self.open.as_ref().is_some_and(|b| same_keyword(&b.name, "elements"));
        let args = self.args(body, end);
        self.element_card = false;
        let st = Statement { keyword, span: first.span, args: args?, end, seq: self.seq, driven: None };
        let in_nodes_block = self.open.as_ref().is_some_and(|b| same_keyword(&b.name, "nodes"));
        self.observer.statement(&st, &self.doc.sources, in_nodes_block, &self.doc.variables);
        if known(&st.keyword, &CARDS).is_some() {
            self.doc.cards.push(st);
            return Ok(());
        }
        match self.open.as_mut() {
            Some(b) => b.statements.push(st),
            None => return Err(self.doc.sources.error(first.span, format!("statement '{}' outside of any block: expected 'begin: <block>;' first", st.keyword))),
        }
        Ok(())
    }

    /// `driven: LABEL, DRIVE, [hint, "…", …,] ELEMENT_TYPE: …;` (input manual, §Driven
    /// Element): the wrapped element's statement, read as any other, carries the head
    /// (label, drive, hints) in `driven`. The element's keyword is the phrase after the last
    /// top-level comma before the second colon.
    fn driven(&mut self, span: Span, body: &[Spanned], end: Span, path: &Path) -> Result<(), MbdynError> {
        let expected = "driven: expected the wrapped element after the drive, e.g. 'driven: 1, string, \"Time < 1.\", joint: 1, …;'";
        let Some(colon) = body.iter().position(|t| t.token == Token::Symbol(":")) else { return Err(self.doc.sources.error(end, expected)) };
        let mut depth = 0i32;
        let mut comma = None;
        for (k, t) in body[..colon].iter().enumerate() {
            match t.token {
                Token::Symbol("(" | "[") => depth += 1,
                Token::Symbol(")" | "]") => depth -= 1,
                Token::Symbol(",") if depth <= 0 => comma = Some(k),
                _ => {}
            }
        }
        let Some(comma) = comma else { return Err(self.doc.sources.error(body[colon].span, expected)) };
        let inner = &body[comma + 1..];
        let inner_words: Vec<String> = inner.iter().take_while(|t| t.token != Token::Symbol(":")).map(|t| t.token.text().to_lowercase()).collect();
        match inner_words.join(" ").as_str() {
            "existing" => return Err(self.doc.sources.error(inner[0].span, "driven: wrapping an 'existing' element is not supported by romdyn (MBDyn 1.7.3 runs it) (write the element's card inside the driven card)")),
            "driven" => return Err(self.doc.sources.error(inner[0].span, "driven: a driven element cannot wrap another driven element")),
            _ => {}
        }
        let args = self.args(&body[..comma], body[comma].span)?;
        let head = Statement { keyword: "driven".into(), span, args, end: body[comma].span, seq: self.seq, driven: None };
        let before = self.open.as_ref().map_or(0, |b| b.statements.len());
        self.statement(inner, end, path)?;
        match self.open.as_mut() {
            Some(b) if b.statements.len() == before + 1 => {
                if let Some(st) = b.statements.last_mut() {
                    st.driven = Some(Box::new(head));
                }
                Ok(())
            }
            _ => Err(self.doc.sources.error(inner[0].span, "driven: expected an element card (e.g. 'joint: …') inside an elements block")),
        }
    }

    /// Splits at top-level commas and evaluates each piece, in order.
    fn args(&mut self, body: &[Spanned], end: Span) -> Result<Vec<Arg>, MbdynError> {
        if let Some(k) = body.iter().position(|t| t.token == Token::Symbol(":")) {
            // A second ':' means the previous statement was not closed: point at the keyword
            // of the next one (its first word when it starts a line, else the last word).
            let mut at = k.saturating_sub(1);
            let mut start = at;
            while start > 0 && matches!(body[start - 1].token, Token::Word(_)) && matches!(body[start].token, Token::Word(_)) {
                start -= 1;
            }
            if let Some(first) = (start..at).find(|&i| i > 0 && body[i - 1].span.line < body[i].span.line) {
                at = first;
            }
            let what = if let Token::Word(w) = &body[at].token { format!("'{w}'") } else { "this".into() };
            return Err(self.doc.sources.error(body[at].span, format!("missing ';' before {what}")));
        }
        let mut pieces: Vec<(&[Spanned], Span)> = Vec::new();
        let (mut depth, mut start) = (0i32, 0);
        for (k, t) in body.iter().enumerate() {
            match t.token {
                Token::Symbol("(" | "[") => depth += 1,
                Token::Symbol(")" | "]") => depth -= 1,
                Token::Symbol(",") if depth <= 0 => {
                    let span = body.get(start).filter(|_| start < k).map_or(t.span, |s| s.span);
                    pieces.push((&body[start..k], span));
                    start = k + 1;
                }
                _ => {}
            }
        }
        if !body.is_empty() {
            pieces.push((&body[start..], body.get(start).map_or(end, |t| t.span)));
        }
        let mut args = Vec::with_capacity(pieces.len());
        for (p, span) in pieces {
            args.push(self.piece(p, span, end)?);
        }
        Ok(args)
    }

    fn piece(&mut self, p: &[Spanned], span: Span, end: Span) -> Result<Arg, MbdynError> {
        let mut text = String::with_capacity(12 * p.len());
        for (k, t) in p.iter().enumerate() {
            if k > 0 {
                text.push(' ');
            }
            t.token.write_text(&mut text);
        }
        let Some(first) = p.first() else {
            return Ok(Arg { value: Value::Empty, span, keyword: None, text });
        };
        let is_variable = |t: &Spanned| matches!(&t.token, Token::Word(w) if self.doc.variables.get(w).is_some());
        // A phrase of names (and integers, as in "euler 321") that is not an expression.
        let phrase = matches!(first.token, Token::Word(_)) && p.iter().all(|t| matches!(t.token, Token::Word(_) | Token::Integer(_))) && !(p.len() == 1 && is_variable(first));
        if phrase {
            let lower = text.to_lowercase();
            return Ok(Arg { value: Value::Word(lower.clone()), span, keyword: Some(lower), text });
        }
        if self.element_card && reads_current(p) {
            let value = Value::Current(Box::new(Deferred::new(p, end, &self.doc.variables)));
            return Ok(Arg { value, span, keyword: None, text });
        }
        if calls_model_drive(p) {
            self.observer.refresh_drives(&self.doc.variables, &self.doc.sources);
        }
        let value = match Evaluator::new(p, &mut self.doc.variables, &self.doc.sources, end).with_reads(Reads::Nodes(self.observer.nodes()), None).with_functions(self.observer.functions()).with_drives(self.observer.drives()).with_elements(self.observer.elements()).evaluate()? {
            // A string written as such may be a string drive's expression: its `TYPE_eval`
            // calls take their values now (see [`staticize_evals`]).
            TypedValue::Str(s) if matches!(p, [Spanned { token: Token::Str(_), .. }]) => {
                Value::Str(staticize_evals(&s, &mut self.doc.variables, Some(Reads::Nodes(self.observer.nodes())), Some(self.observer.drives())).unwrap_or(s))
            }
            TypedValue::Str(s) => Value::Str(s),
            v => Value::Number(v.real().unwrap_or(0.0)),
        };
        let keyword = (p.len() == 1 && matches!(first.token, Token::Word(_))).then(|| text.to_lowercase());
        Ok(Arg { value, span, keyword, text })
    }

    fn include(&mut self, body: &[Spanned], span: Span, end: Span, path: &Path) -> Result<(), MbdynError> {
        let src = &self.doc.sources;
        let name = match body {
            [Spanned { token: Token::Str(s), .. }] => s.clone(),
            _ => return Err(src.error(body.first().map_or(end, |t| t.span), "include: expected a file name in double quotes")),
        };
        let target = path.parent().unwrap_or(Path::new(".")).join(&name);
        let target_canonical = canonical(&target);
        if self.stack.iter().any(|(_, p)| *p == target_canonical) {
            return Err(src.error(span, format!("include loop: \"{name}\" is already being read")));
        }
        // Each level is a few stack frames and a file held: a chain without end would
        // overflow the stack (a 5000-deep chain took over a minute, issue 32).
        if self.stack.len() >= MAX_INCLUDE_DEPTH {
            return Err(src.error(span, format!("include: \"{name}\" would make a chain of {} files (a file including a file including …), more than romdyn's limit of {MAX_INCLUDE_DEPTH}", self.stack.len() + 1)));
        }
        self.read(&target, Some(body[0].span))
    }

    fn block(&mut self, keyword: &str, body: &[Spanned], span: Span, end: Span) -> Result<(), MbdynError> {
        let src = &self.doc.sources;
        let mut name = Vec::new();
        for t in body {
            match &t.token {
                Token::Word(w) => name.push(w.to_lowercase()),
                other => return Err(src.error(t.span, format!("{keyword}: expected a block name, found {}", describe(other)))),
            }
        }
        if name.is_empty() {
            return Err(src.error(end, format!("{keyword}: expected a block name")));
        }
        let mut name = name.join(" ");
        if same_keyword(&name, "multistep") {
            // MBDyn's deprecated name of the initial value block (solver.cc, Solver::ReadData).
            name = "initial value".into();
        }
        if keyword == "begin" {
            if let Some(open) = &self.open {
                return Err(src.error(span, format!("begin: {name} inside block '{}': expected 'end: {};' first", open.name, open.name)));
            }
            self.open = Some(Block { name, span, statements: Vec::new() });
            return Ok(());
        }
        match self.open.take() {
            Some(b) if same_keyword(&b.name, &name) => {
                self.doc.blocks.push(b);
                Ok(())
            }
            Some(b) => Err(src.error(body[0].span, format!("end: {name} does not match the open block: expected 'end: {};'", b.name))),
            None => Err(src.error(span, format!("end: {name} without a matching 'begin: {name};'"))),
        }
    }
}

/// An error in a file of MBDyn's Python preprocessor (contrib/PythonPreprocessor: Python
/// between `#beginpreprocess` and `#endpreprocess`, which its MBDynPreprocess.py expands
/// into MBDyn input). To MBDyn's reader the directive is a comment and the Python after it
/// is read as input, where it stops too.
fn python_preprocessor_note(message: &str, line: usize) -> String {
    format!(
        "{message}; this file is the input of MBDyn's Python preprocessor ('#beginpreprocess' at line {line} starts Python code, contrib/PythonPreprocessor), \
         which romdyn does not read, nor does MBDyn 1.7.3 (its reader takes the directive for a comment and stops on the Python code): \
         run 'python MBDynPreprocess.py FILE > FILE.mbd' first and give romdyn its output"
    )
}

/// `path` with links and `..` resolved, or as given where it cannot be (a missing file:
/// reading it reports that).
fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

/// Whether the tokens call `model::drive` (in a string too: a string drive's `_eval`).
fn calls_model_drive(tokens: &[Spanned]) -> bool {
    tokens.windows(3).any(|w| matches!((&w[0].token, &w[1].token, &w[2].token), (Token::Word(m), Token::Symbol("::"), Token::Word(d)) if m == "model" && d == "drive"))
        || tokens.iter().any(|t| matches!(&t.token, Token::Str(s) if s.contains("_eval")))
}

