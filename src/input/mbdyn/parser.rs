//! Statements `keyword words: arg, arg, …;` grouped in `begin: NAME;` … `end: NAME;` blocks,
//! with `include: "file";` and `set: [const] real|integer NAME = EXPR;` handled as read.

use std::path::{Path, PathBuf};

use super::diagnostic::{MbdynError, Sources, Span};
use super::expr::{describe, is_expression_word, Evaluator, Variable, Variables};
use super::lexer::{tokenize, Spanned, Token};

/// An evaluated argument.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Number(f64),
    /// One or more words, lowercased and joined by single spaces ("revolute hinge").
    Word(String),
    Str(String),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Arg {
    pub value: Value,
    pub span: Span,
}

/// `keyword: args;`, the keyword lowercased with single spaces.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    pub keyword: String,
    pub span: Span,
    pub args: Vec<Arg>,
    /// Where the terminating ';' is (for "missing argument" errors).
    pub end: Span,
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
    pub sources: Sources,
    pub variables: Variables,
}

struct Reader {
    doc: Document,
    stack: Vec<PathBuf>,
    open: Option<Block>,
}

/// Reads and parses an MBDyn input file (and its includes).
pub fn parse_file(path: &Path) -> Result<Document, MbdynError> {
    let mut r = Reader { doc: Document::default(), stack: Vec::new(), open: None };
    r.read(path, None)?;
    if let Some(b) = r.open.take() {
        return Err(r.doc.sources.error(b.span, format!("block '{}' is never closed: expected 'end: {};'", b.name, b.name)));
    }
    Ok(r.doc)
}

/// Parses text as if it were the file `name` (includes resolve relative to its folder).
pub fn parse_text(text: &str, name: &Path) -> Result<Document, MbdynError> {
    let mut r = Reader { doc: Document::default(), stack: Vec::new(), open: None };
    r.read_text(text.to_string(), name)?;
    if let Some(b) = r.open.take() {
        return Err(r.doc.sources.error(b.span, format!("block '{}' is never closed: expected 'end: {};'", b.name, b.name)));
    }
    Ok(r.doc)
}

impl Reader {
    fn read(&mut self, path: &Path, from: Option<Span>) -> Result<(), MbdynError> {
        let text = std::fs::read_to_string(path).map_err(|e| match from {
            Some(span) => self.doc.sources.error(span, format!("cannot include \"{}\": {e}", path.display())),
            None => MbdynError { file: path.to_path_buf(), line: 0, column: 0, message: format!("cannot read: {e}"), source_line: String::new() },
        })?;
        self.read_text(text, path)
    }

    fn read_text(&mut self, text: String, path: &Path) -> Result<(), MbdynError> {
        let file = self.doc.sources.files.len();
        self.doc.sources.files.push((path.to_path_buf(), text.clone()));
        self.stack.push(path.to_path_buf());
        let tokens = tokenize(&text, file, &self.doc.sources)?;
        let mut i = 0;
        while i < tokens.len() {
            let end = tokens[i..].iter().position(|t| t.token == Token::Punct(';')).map(|k| i + k);
            let Some(end) = end else {
                let last = tokens.last().map_or(tokens[i].span, |t| t.span);
                return Err(self.doc.sources.error(last, "missing ';' at the end of this statement"));
            };
            self.statement(&tokens[i..end], tokens[end].span, path)?;
            i = end + 1;
        }
        self.stack.pop();
        Ok(())
    }

    fn statement(&mut self, toks: &[Spanned], end: Span, path: &Path) -> Result<(), MbdynError> {
        let src = &self.doc.sources;
        let Some(first) = toks.first() else { return Err(src.error(end, "empty statement: expected a keyword before ';'")) };
        let colon = toks.iter().position(|t| t.token == Token::Punct(':'));
        let head = &toks[..colon.unwrap_or(toks.len())];
        let mut words = Vec::new();
        for t in head {
            match &t.token {
                Token::Word(w) => words.push(w.to_lowercase()),
                other => return Err(src.error(t.span, format!("expected a keyword, found {}", describe(other)))),
            }
        }
        let keyword = words.join(" ");
        let body = colon.map_or(&[][..], |c| &toks[c + 1..]);
        match keyword.as_str() {
            "include" => return self.include(body, first.span, end, path),
            "set" => return self.set(body, end),
            "begin" | "end" => return self.block(&keyword, body, first.span, end),
            _ => {}
        }
        let args = self.args(body, end)?;
        let st = Statement { keyword, span: first.span, args, end };
        match self.open.as_mut() {
            Some(b) => b.statements.push(st),
            None => return Err(self.doc.sources.error(first.span, format!("statement '{}' outside of any block: expected 'begin: <block>;' first", st.keyword))),
        }
        Ok(())
    }

    /// Splits at top-level commas and evaluates each piece.
    fn args(&self, body: &[Spanned], end: Span) -> Result<Vec<Arg>, MbdynError> {
        let src = &self.doc.sources;
        if let Some(k) = body.iter().position(|t| t.token == Token::Punct(':')) {
            // A second ':' means the previous statement was not closed.
            let at = if k > 0 { &body[k - 1] } else { &body[k] };
            let what = if let Token::Word(w) = &at.token { format!("'{w}'") } else { "this".into() };
            return Err(src.error(at.span, format!("missing ';' before {what}")));
        }
        let mut pieces: Vec<&[Spanned]> = Vec::new();
        let (mut depth, mut start) = (0i32, 0);
        for (k, t) in body.iter().enumerate() {
            match t.token {
                Token::Punct('(') => depth += 1,
                Token::Punct(')') => depth -= 1,
                Token::Punct(',') if depth == 0 => {
                    pieces.push(&body[start..k]);
                    start = k + 1;
                }
                _ => {}
            }
        }
        if !body.is_empty() {
            pieces.push(&body[start..]);
        }
        let mut args = Vec::with_capacity(pieces.len());
        for (k, p) in pieces.iter().enumerate() {
            let span = match p.first() {
                Some(t) => t.span,
                None => return Err(src.error(if k == 0 { end } else { body[body.len().min(1) - 1].span }, "empty argument: expected a value between the commas")),
            };
            let all_words = p.iter().all(|t| matches!(&t.token, Token::Word(w) if !is_expression_word(&w.to_lowercase(), &self.doc.variables) && !is_expression_word(w, &self.doc.variables)));
            let value = match (&p[0].token, p.len()) {
                (Token::Str(s), 1) => Value::Str(s.clone()),
                _ if all_words => Value::Word(p.iter().map(|t| if let Token::Word(w) = &t.token { w.to_lowercase() } else { String::new() }).collect::<Vec<_>>().join(" ")),
                _ => Value::Number(Evaluator::new(p, &self.doc.variables, src, end).evaluate()?),
            };
            args.push(Arg { value, span });
        }
        Ok(args)
    }

    fn include(&mut self, body: &[Spanned], span: Span, end: Span, path: &Path) -> Result<(), MbdynError> {
        let src = &self.doc.sources;
        let name = match body {
            [Spanned { token: Token::Str(s), .. }] => s.clone(),
            _ => return Err(src.error(body.first().map_or(end, |t| t.span), "include: expected a file name in double quotes")),
        };
        let target = path.parent().unwrap_or(Path::new(".")).join(&name);
        let canonical = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
        if self.stack.iter().any(|p| canonical(p) == canonical(&target)) {
            return Err(src.error(span, format!("include loop: \"{name}\" is already being read")));
        }
        self.read(&target, Some(body[0].span))
    }

    fn set(&mut self, body: &[Spanned], end: Span) -> Result<(), MbdynError> {
        let src = &self.doc.sources;
        let mut k = 0;
        let word = |k: usize| body.get(k).and_then(|t| if let Token::Word(w) = &t.token { Some(w.to_lowercase()) } else { None });
        let constant = word(k).as_deref() == Some("const");
        if constant {
            k += 1;
        }
        let integer = match word(k).as_deref() {
            Some("real") => false,
            Some("integer") => true,
            _ => return Err(src.error(body.get(k).map_or(end, |t| t.span), "set: expected 'real' or 'integer' (optionally after 'const')")),
        };
        let Some(Token::Word(name)) = body.get(k + 1).map(|t| &t.token) else {
            return Err(src.error(body.get(k + 1).map_or(end, |t| t.span), "set: expected a variable name"));
        };
        if body.get(k + 2).map(|t| &t.token) != Some(&Token::Punct('=')) {
            return Err(src.error(body.get(k + 2).map_or(end, |t| t.span), format!("set: expected '=' after '{name}'")));
        }
        if let Some(old) = self.doc.variables.0.get(name.as_str()) {
            if old.constant {
                return Err(src.error(body[k + 1].span, format!("'{name}' is a constant and cannot be set again")));
            }
        }
        let mut value = Evaluator::new(&body[k + 3..], &self.doc.variables, src, end).evaluate()?;
        if integer {
            value = value.trunc();
        }
        self.doc.variables.0.insert(name.clone(), Variable { value, integer, constant });
        Ok(())
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
        let name = name.join(" ");
        if keyword == "begin" {
            if let Some(open) = &self.open {
                return Err(src.error(span, format!("begin: {name} inside block '{}': expected 'end: {};' first", open.name, open.name)));
            }
            self.open = Some(Block { name, span, statements: Vec::new() });
            return Ok(());
        }
        match self.open.take() {
            Some(b) if b.name == name => {
                self.doc.blocks.push(b);
                Ok(())
            }
            Some(b) => Err(src.error(body[0].span, format!("end: {name} does not match the open block: expected 'end: {};'", b.name))),
            None => Err(src.error(span, format!("end: {name} without a matching 'begin: {name};'"))),
        }
    }
}
