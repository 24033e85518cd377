//! A character stream that knows the 1-based line and column of its next character, shared
//! by the text readers (MBDyn input, Octave scripts) for their diagnostics.

/// A saved cursor position (see [`CharStream::mark`]).
#[derive(Clone, Copy)]
pub struct Mark {
    pos: usize,
    line: usize,
    column: usize,
}

/// Characters of a text with a cursor.
pub struct CharStream {
    /// The text (UTF-8: one byte per ASCII character, where a `Vec<char>` took four).
    text: String,
    /// The byte offset of the next character.
    pos: usize,
    pub line: usize,
    pub column: usize,
}

impl CharStream {
    pub fn new(text: &str) -> Self {
        CharStream { text: text.to_string(), pos: 0, line: 1, column: 1 }
    }

    /// The character `k` places ahead of the cursor.
    pub fn peek_at(&self, k: usize) -> Option<char> {
        self.text[self.pos..].chars().nth(k)
    }

    pub fn peek(&self) -> Option<char> {
        self.peek_at(0)
    }

    /// Consumes one character, moving the line and column.
    pub fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.pos += c.len_utf8();
        if c == '\n' {
            self.line += 1;
            self.column = 1;
        } else {
            self.column += 1;
        }
        Some(c)
    }

    /// The cursor, to come back to with [`CharStream::reset`].
    pub fn mark(&self) -> Mark {
        Mark { pos: self.pos, line: self.line, column: self.column }
    }

    pub fn reset(&mut self, m: Mark) {
        (self.pos, self.line, self.column) = (m.pos, m.line, m.column);
    }

    /// Consumes the ASCII characters that `take` accepts, up to the first it refuses, and
    /// returns them: the words and numbers of a reader, sliced from the text instead of
    /// pushed into a string one character at a time. `take` must refuse `\n` (the column
    /// moves by one per byte taken, the line not at all).
    pub fn take_ascii_while(&mut self, take: impl Fn(u8) -> bool) -> &str {
        let start = self.pos;
        let len = self.text.as_bytes()[start..].iter().take_while(|&&b| b.is_ascii() && take(b)).count();
        debug_assert!(!self.text.as_bytes()[start..start + len].contains(&b'\n'), "take_ascii_while: a newline taken");
        self.pos += len;
        self.column += len;
        &self.text[start..start + len]
    }

    /// The text from `mark` to the cursor.
    pub fn since(&self, mark: Mark) -> &str {
        &self.text[mark.pos..self.pos]
    }

    /// Whether the text continues with `s`.
    pub fn starts_with(&self, s: &str) -> bool {
        self.text[self.pos..].starts_with(s)
    }
}
