//! Keyword tables: for one family of cards (element types, joint types, genel types, …)
//! every keyword MBDyn 1.7.3 knows, with whether romdyn reads it (issue 31 point 5). The
//! reader accepts the keywords marked [`Support::Read`]; the "supported" lists and the
//! refusals of every other keyword are written from the same table, so a keyword added to
//! the reader is listed, and a refusal says whether MBDyn runs the card (issue 38 point 4),
//! without a second list kept by hand.

use super::diagnostic::{mbdyn_runs_it, unknown_to_both};
use super::parser::same_keyword;

/// Whether romdyn reads a keyword, and if not, what MBDyn 1.7.3 does with it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// romdyn reads it.
    Read,
    /// romdyn refuses it; MBDyn 1.7.3 as built from its public source runs it.
    MbdynRuns,
    /// romdyn refuses it; MBDyn 1.7.3 runs it only when built or loaded as the phrase says,
    /// which the refusal writes in parentheses ("an MBDyn 1.7.3 built with RTAI runs it").
    MbdynRunsWhen(&'static str),
    /// romdyn refuses it, with its own message (MBDyn's behaviour is in the message).
    Refused(&'static str),
}

/// One keyword of a family.
#[derive(Clone, Copy, Debug)]
pub struct Keyword {
    pub name: &'static str,
    pub support: Support,
}

/// A read keyword.
pub const fn read(name: &'static str) -> Keyword {
    Keyword { name, support: Support::Read }
}

/// A keyword MBDyn 1.7.3 runs and romdyn refuses.
pub const fn mbdyn_only(name: &'static str) -> Keyword {
    Keyword { name, support: Support::MbdynRuns }
}

/// The keywords of one family of cards.
pub struct KeywordTable {
    /// What a keyword of the family is, for messages: "element type", "joint type".
    pub what: &'static str,
    pub keywords: &'static [Keyword],
}

impl KeywordTable {
    /// The keywords romdyn reads, in table order.
    pub fn read(&self) -> Vec<&'static str> {
        self.keywords.iter().filter(|k| k.support == Support::Read).map(|k| k.name).collect()
    }

    /// The entry of `word` (MBDyn's keyword comparison: case and blanks as the parser's).
    pub fn find(&self, word: &str) -> Option<&'static Keyword> {
        self.keywords.iter().find(|k| same_keyword(k.name, word))
    }

    /// Why `word` is not read: the table's reason, "(MBDyn 1.7.3 runs it)", or "unknown to
    /// both", followed by the keywords romdyn reads.
    pub fn refusal(&self, word: &str) -> String {
        let what = self.what;
        let reason = match self.find(word).map(|k| (k.name, k.support)) {
            Some((name, Support::MbdynRuns)) => mbdyn_runs_it(&format!("{what} '{name}'")),
            Some((name, Support::MbdynRunsWhen(phrase))) => format!("{what} '{name}' is not supported by romdyn ({phrase})"),
            Some((_, Support::Refused(reason))) => reason.to_string(),
            Some((name, Support::Read)) => format!("{what} '{name}' is read by romdyn, but not here"),
            None => unknown_to_both(what, word),
        };
        format!("{reason} (romdyn reads: {})", self.read().join(", "))
    }
}

/// Checks that a book chapter lists the keywords romdyn reads exactly as the table does, on
/// one line `<!-- keyword table: WHAT -->` followed by the list (the book's lists are
/// written from the tables, and a test fails when they drift).
#[cfg(test)]
pub fn check_documented(table: &KeywordTable, chapter: &str) -> Result<(), String> {
    let marker = format!("<!-- keyword table: {} -->", table.what);
    let line = chapter.lines().skip_while(|l| l.trim() != marker).nth(1).ok_or(format!("the chapter has no line after '{marker}'"))?;
    let want = table.read().iter().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ");
    if line.trim() == want { Ok(()) } else { Err(format!("the chapter's list after '{marker}' is\n{line}\nthe table's is\n{want}")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLE: KeywordTable = KeywordTable { what: "thing type", keywords: &[read("alpha"), mbdyn_only("beta"), read("gamma delta"), Keyword { name: "eps", support: Support::Refused("no eps here") }] };

    #[test]
    fn the_lists_and_refusals_come_from_the_table() {
        assert_eq!(TABLE.read(), ["alpha", "gamma delta"]);
        assert_eq!(TABLE.refusal("beta"), "thing type 'beta' is not supported by romdyn (MBDyn 1.7.3 runs it) (romdyn reads: alpha, gamma delta)");
        assert_eq!(TABLE.refusal("eps"), "no eps here (romdyn reads: alpha, gamma delta)");
        assert!(TABLE.refusal("zeta").starts_with("unknown thing type 'zeta': MBDyn 1.7.3 has none either"));
        assert!(TABLE.find("Gamma  Delta").is_some(), "keywords compare as MBDyn's parser does");
    }
}
