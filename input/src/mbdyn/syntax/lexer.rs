//! Tokens of MBDyn's input language (input manual, "General", §Types): integers (digits
//! without a dot), reals (with a dot or an exponent), names, double-quoted strings with
//! backslash escapes, and operators; `#` comments to the end of the line and `/* … */`
//! comments.

use super::diagnostic::{MbdynError, Sources, Span};
use crate::chars::CharStream;

#[derive(Clone, Debug, PartialEq)]
pub enum Token {
    /// A literal without a dot or exponent: MBDyn types it `integer` (so `1/3` is 0).
    Integer(i64),
    Real(f64),
    Word(String),
    Str(String),
    /// Punctuation and operators: `: , ; ( ) [ ] + - * / % ^ = == != < <= > >= ! && || ~| ::`.
    Symbol(&'static str),
}

impl Token {
    /// The token as it could be written in a file (strings quoted), read back as the same
    /// token: a real keeps its dot or exponent (`{:?}`: "3.0", "1e-7"), since `3` would read
    /// as an integer, with MBDyn's integer arithmetic (`1/2` is 0).
    pub fn text(&self) -> String {
        let mut out = String::new();
        self.write_text(&mut out);
        out
    }

    /// Appends [`Self::text`] to `out` (no allocation of its own).
    pub fn write_text(&self, out: &mut String) {
        use std::fmt::Write;
        let _ = match self {
            Token::Integer(i) => write!(out, "{i}"),
            Token::Real(x) => write!(out, "{x:?}"),
            Token::Word(w) => Ok(out.push_str(w)),
            Token::Str(s) => write!(out, "\"{s}\""),
            Token::Symbol(s) => Ok(out.push_str(s)),
        };
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Spanned {
    pub token: Token,
    pub span: Span,
}

const SYMBOLS: [&str; 24] = ["::", "==", "!=", "<=", ">=", "&&", "||", "~|", ":", ",", ";", "(", ")", "[", "]", "+", "-", "*", "/", "%", "^", "=", "<", ">"];

/// Characters with line and column, in file `file` of the sources.
struct Scanner {
    text: CharStream,
    file: usize,
}

impl Scanner {
    fn peek(&self, k: usize) -> Option<char> {
        self.text.peek_at(k)
    }
    fn span(&self) -> Span {
        Span { file: self.file, line: self.text.line, column: self.text.column }
    }
    fn bump(&mut self) -> Option<char> {
        self.text.bump()
    }
    fn starts_with(&self, s: &str) -> bool {
        self.text.starts_with(s)
    }
}

/// A file's tokens, one at a time: the reader keeps one statement's tokens, not the
/// whole file's (issue 32: memory, and so time, per card flat in the file's size).
pub struct Lexer {
    s: Scanner,
}

impl Lexer {
    pub fn new(text: &str, file: usize) -> Self {
        Lexer { s: Scanner { text: CharStream::new(text), file } }
    }

    /// The next token, `None` at the end of the text.
    pub fn next_token(&mut self, sources: &Sources) -> Result<Option<Spanned>, MbdynError> {
        let s = &mut self.s;
        while let Some(c) = s.peek(0) {
            let span = s.span();
            if c.is_whitespace() {
                s.bump();
            } else if c == '#' {
                while s.peek(0).is_some_and(|c| c != '\n') {
                    s.bump();
                }
            } else if s.starts_with("/*") {
                s.bump();
                s.bump();
                loop {
                    if s.peek(0).is_none() {
                        return Err(sources.error(span, "unterminated comment: expected '*/' to close the '/*' opened here"));
                    }
                    if s.starts_with("*/") {
                        s.bump();
                        s.bump();
                        break;
                    }
                    s.bump();
                }
            } else if c == '"' {
                return Ok(Some(Spanned { token: Token::Str(string(s, span, sources)?), span }));
            } else if c.is_ascii_digit() || (c == '.' && s.peek(1).is_some_and(|d| d.is_ascii_digit())) {
                return Ok(Some(Spanned { token: number(s, span, sources)?, span }));
            } else if c.is_ascii_alphabetic() || c == '_' {
                let w = s.text.take_ascii_while(|b| b.is_ascii_alphanumeric() || b == b'_');
                return Ok(Some(Spanned { token: Token::Word(w.to_string()), span }));
            } else if let Some(sym) = SYMBOLS.iter().find(|sym| s.starts_with(sym)) {
                for _ in 0..sym.len() {
                    s.bump();
                }
                return Ok(Some(Spanned { token: Token::Symbol(sym), span }));
            } else if c == '!' {
                s.bump();
                return Ok(Some(Spanned { token: Token::Symbol("!"), span }));
            } else {
                return Err(sources.error(span, format!("unexpected character '{}'", c.escape_default())));
            }
        }
        Ok(None)
    }
}

/// Splits a text into tokens.
pub fn tokenize(text: &str, file: usize, sources: &Sources) -> Result<Vec<Spanned>, MbdynError> {
    let mut lexer = Lexer::new(text, file);
    let mut out = Vec::new();
    while let Some(t) = lexer.next_token(sources)? {
        out.push(t);
    }
    Ok(out)
}

/// A double-quoted string, which may span lines; `\\` and `\"` escape, a backslash before a
/// newline joins lines (the newline is dropped),
/// `\hh` (two hex digits) is a character code.
fn string(s: &mut Scanner, span: Span, sources: &Sources) -> Result<String, MbdynError> {
    s.bump();
    let mut text = String::new();
    loop {
        match s.bump() {
            // A newline inside the quotes is part of the string, as in MBDyn's reader.
            None => return Err(sources.error(span, "unterminated string: expected a closing '\"' before the end of the file")),
            Some('"') => return Ok(text),
            Some('\\') => match s.peek(0) {
                Some('\n') => {
                    s.bump();
                }
                Some(c @ ('\\' | '"')) => {
                    text.push(c);
                    s.bump();
                }
                Some(h) if h.is_ascii_hexdigit() && s.peek(1).is_some_and(|l| l.is_ascii_hexdigit()) => {
                    let code = h.to_digit(16).unwrap_or(0) * 16 + s.peek(1).and_then(|l| l.to_digit(16)).unwrap_or(0);
                    text.push(char::from_u32(code).unwrap_or('?'));
                    s.bump();
                    s.bump();
                }
                _ => text.push('\\'),
            },
            Some(c) => text.push(c),
        }
    }
}

fn number(s: &mut Scanner, span: Span, sources: &Sources) -> Result<Token, MbdynError> {
    let start = s.text.mark();
    let mut real = s.text.take_ascii_while(|b| b.is_ascii_digit() || b == b'.').contains('.');
    if matches!(s.peek(0), Some('e' | 'E')) {
        let sign = matches!(s.peek(1), Some('+' | '-'));
        let first_digit = if sign { 2 } else { 1 };
        if s.peek(first_digit).is_some_and(|d| d.is_ascii_digit()) {
            real = true;
            for _ in 0..first_digit {
                s.bump();
            }
            s.text.take_ascii_while(|b| b.is_ascii_digit());
        }
    }
    // The number's text as written: a slice of the file (no string built per number).
    let text = s.text.since(start);
    if s.peek(0).is_some_and(|c| c.is_ascii_alphabetic() || c == '_') {
        return Err(sources.error(span, format!("'{text}{}' is not a valid number", s.peek(0).unwrap_or(' '))));
    }
    if real {
        text.parse::<f64>().map(Token::Real).map_err(|_| sources.error(span, format!("'{text}' is not a valid number")))
    } else {
        text.parse::<i64>().map(Token::Integer).map_err(|_| sources.error(span, format!("the integer {text} is too large (write it with a dot, '{text}.', to make it real)")))
    }
}
