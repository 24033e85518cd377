//! Tokens of MBDyn's input language: numbers, words, strings and punctuation; `#` comments
//! to the end of the line and `/* … */` comments.

use super::diagnostic::{MbdynError, Sources, Span};

#[derive(Clone, Debug, PartialEq)]
pub enum Token {
    Number(f64),
    Word(String),
    Str(String),
    /// One of `: , ; ( ) + - * / ^ = < > !`.
    Punct(char),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Spanned {
    pub token: Token,
    pub span: Span,
}

/// Splits a file's text into tokens.
pub fn tokenize(text: &str, file: usize, sources: &Sources) -> Result<Vec<Spanned>, MbdynError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line, mut col) = (0, 1, 1);
    let advance = |i: &mut usize, line: &mut usize, col: &mut usize, c: char| {
        *i += 1;
        if c == '\n' {
            *line += 1;
            *col = 1;
        } else {
            *col += 1;
        }
    };
    while i < chars.len() {
        let c = chars[i];
        let span = Span { file, line, column: col };
        if c.is_whitespace() {
            advance(&mut i, &mut line, &mut col, c);
        } else if c == '#' {
            while i < chars.len() && chars[i] != '\n' {
                { let ch = chars[i]; advance(&mut i, &mut line, &mut col, ch); }
            }
        } else if c == '/' && chars.get(i + 1) == Some(&'*') {
            advance(&mut i, &mut line, &mut col, '/');
            advance(&mut i, &mut line, &mut col, '*');
            loop {
                if i >= chars.len() {
                    return Err(sources.error(span, "unterminated comment: expected '*/' to close the '/*' opened here"));
                }
                if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    advance(&mut i, &mut line, &mut col, '*');
                    advance(&mut i, &mut line, &mut col, '/');
                    break;
                }
                { let ch = chars[i]; advance(&mut i, &mut line, &mut col, ch); }
            }
        } else if c == '"' {
            advance(&mut i, &mut line, &mut col, c);
            let mut s = String::new();
            loop {
                match chars.get(i) {
                    None | Some('\n') => return Err(sources.error(span, "unterminated string: expected a closing '\"' on the same line")),
                    Some('"') => {
                        advance(&mut i, &mut line, &mut col, '"');
                        break;
                    }
                    Some(&ch) => {
                        s.push(ch);
                        advance(&mut i, &mut line, &mut col, ch);
                    }
                }
            }
            out.push(Spanned { token: Token::Str(s), span });
        } else if c.is_ascii_digit() || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit())) {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                { let ch = chars[i]; advance(&mut i, &mut line, &mut col, ch); }
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let sign = matches!(chars.get(i + 1), Some('+') | Some('-'));
                let digit_at = if sign { i + 2 } else { i + 1 };
                if chars.get(digit_at).is_some_and(|d| d.is_ascii_digit()) {
                    for _ in i..digit_at {
                        advance(&mut i, &mut line, &mut col, 'e');
                    }
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        { let ch = chars[i]; advance(&mut i, &mut line, &mut col, ch); }
                    }
                }
            }
            let text: String = chars[start..i].iter().collect();
            let value = text.parse::<f64>().map_err(|_| sources.error(span, format!("'{text}' is not a valid number")))?;
            out.push(Spanned { token: Token::Number(value), span });
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                { let ch = chars[i]; advance(&mut i, &mut line, &mut col, ch); }
            }
            out.push(Spanned { token: Token::Word(chars[start..i].iter().collect()), span });
        } else if ":,;()+-*/^=<>!".contains(c) {
            advance(&mut i, &mut line, &mut col, c);
            out.push(Spanned { token: Token::Punct(c), span });
        } else {
            return Err(sources.error(span, format!("unexpected character '{c}'")));
        }
    }
    Ok(out)
}
