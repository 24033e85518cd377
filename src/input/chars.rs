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
    chars: Vec<char>,
    pos: usize,
    pub line: usize,
    pub column: usize,
}

impl CharStream {
    pub fn new(text: &str) -> Self {
        CharStream { chars: text.chars().collect(), pos: 0, line: 1, column: 1 }
    }

    /// The character `k` places ahead of the cursor.
    pub fn peek_at(&self, k: usize) -> Option<char> {
        self.chars.get(self.pos + k).copied()
    }

    pub fn peek(&self) -> Option<char> {
        self.peek_at(0)
    }

    /// Consumes one character, moving the line and column.
    pub fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.pos += 1;
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

    /// Whether the text continues with `s`.
    pub fn starts_with(&self, s: &str) -> bool {
        s.chars().enumerate().all(|(k, c)| self.peek_at(k) == Some(c))
    }
}
