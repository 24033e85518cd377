//! The reader's entry points: parse an MBDyn file while keeping the structural nodes written
//! so far, which the `model` namespace's state functions read at read time (`set:`,
//! `remark:`, the numbers of later statements), as MBDyn does.

use std::collections::HashMap;
use std::path::Path;

use super::cursor::Cursor;
use super::diagnostic::{MbdynError, Sources};
use super::expr::SetOverrides;
use super::nodes::{node_statement, Nodes};
use super::parser::{known, parse_file_observed, parse_text_observed, same_keyword, Document, Statement, StatementObserver};
use super::references::{reference, Frames};
use crate::element::NodeKinematics;

/// The structural nodes as written so far (MBDyn's `StructNode::GetXCurr` while it reads is
/// the written position). Built with the same readers as the model; a statement they refuse
/// adds nothing here (the model's build reports it).
#[derive(Default)]
pub struct WrittenNodes {
    frames: Frames,
    nodes: Nodes,
    known: HashMap<u32, NodeKinematics>,
}

impl StatementObserver for WrittenNodes {
    fn statement(&mut self, st: &Statement, sources: &Sources, in_nodes_block: bool) {
        let mut c = Cursor::new(st, sources);
        if known(&st.keyword, &["reference"]).is_some() {
            let _ = reference(st, &mut c, &mut self.frames);
        } else if in_nodes_block && same_keyword(&st.keyword, "structural") && node_statement(st, &mut c, &self.frames, &mut self.nodes).is_ok() {
            if let Some(e) = self.nodes.0.last().filter(|e| !e.dummy) {
                let n = &e.node;
                self.known.insert(n.label, NodeKinematics { x: n.position, r: n.orientation, xdot: n.velocity, omega: n.angular_velocity });
            }
        }
    }
    fn nodes(&self) -> &HashMap<u32, NodeKinematics> {
        &self.known
    }
}

/// Reads and parses an MBDyn input file (and its includes).
pub fn parse_file(path: &Path) -> Result<Document, MbdynError> {
    parse_file_with(path, &SetOverrides::new())
}

/// Parses text as if it were the file `name` (includes resolve relative to its folder).
pub fn parse_text(text: &str, name: &Path) -> Result<Document, MbdynError> {
    parse_text_with(text, name, &SetOverrides::new())
}

/// [`parse_file`] with `set:` variables overridden (a design point); a name the file never
/// declares is an error.
pub fn parse_file_with(path: &Path, overrides: &SetOverrides) -> Result<Document, MbdynError> {
    parse_file_observed(path, overrides, Box::new(WrittenNodes::default()))
}

/// [`parse_text`] with `set:` variables overridden (a design point).
pub fn parse_text_with(text: &str, name: &Path, overrides: &SetOverrides) -> Result<Document, MbdynError> {
    parse_text_observed(text, name, overrides, Box::new(WrittenNodes::default()))
}
