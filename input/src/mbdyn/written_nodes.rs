//! The reader's entry points: parse an MBDyn file while keeping the structural nodes written
//! so far, which the `model` namespace's state functions read at read time (`set:`,
//! `remark:`, the numbers of later statements), as MBDyn does, and the scalar function and
//! drive caller cards read so far, which `model::sf::NAME(x)` and `model::drive(LABEL, x)`
//! call there.

use std::collections::HashMap;
use std::path::Path;

use super::syntax::cursor::Cursor;
use super::syntax::diagnostic::{MbdynError, Sources};
use super::syntax::expr::{SetOverrides, Variables};
use super::nodes::structural::{node_statement, Nodes};
use super::syntax::parser::{known, parse_file_observed, parse_text_observed, same_keyword, Document, Statement, StatementObserver};
use super::syntax::references::{reference, Frames};
use crate::element::NodeKinematics;

/// The structural nodes as written so far (MBDyn's `StructNode::GetXCurr` while it reads is
/// the written position). Built with the same readers as the model; a statement they refuse
/// adds nothing here (the model's build reports it).
pub struct WrittenNodes {
    frames: Frames,
    nodes: Nodes,
    known: HashMap<u32, NodeKinematics>,
    /// The scalar function cards read so far, in `drives.functions` (a card the model's
    /// build refuses is left out): a view of the shared table.
    visible: super::syntax::card_tables::FunctionsBefore,
    /// The drive caller cards read so far (one the model's build refuses is left out).
    drives: super::drives::callers::Drives,
    drive_table: super::syntax::card_tables::DrivesBefore,
    /// The drive caller cards read so far (read again when the variables change).
    drive_cards: Vec<Statement>,
    /// The generation of the variables the cards were read with
    /// ([`Variables::generation`]), `None` before any.
    read_with: Option<u64>,
    /// How many of `drive_cards` are read.
    cards_read: usize,
    /// The bodies and joints read so far (`model::element::…`), built with the model's
    /// readers (without the constitutive law cards: a joint that names one is kept as the
    /// reason it could not be read).
    elements: super::syntax::model_namespace::ElementsRead,
}

impl StatementObserver for WrittenNodes {
    fn statement(&mut self, st: &Statement, sources: &Sources, in_nodes_block: bool, variables: &Variables) {
        let mut c = Cursor::new(st, sources);
        if known(&st.keyword, &["drive caller"]).is_some() {
            // Read when a `model::drive` call needs it ([`StatementObserver::refresh_drives`]):
            // most files never call one while they are read, and reading each card here with
            // the variables as they stand made N cards and N `set:` O(N²) to read.
            self.drive_cards.push(st.clone());
            return;
        }
        if !in_nodes_block && known(&st.keyword, &["body", "joint"]).is_some() {
            // The element's drives may name the cards read so far: those not read yet are
            // read with the variables as they stand (the others keep theirs until a
            // `model::drive` call refreshes them).
            if self.cards_read < self.drive_cards.len() && self.read_with != Some(variables.generation()) {
                self.drives.variables = variables.shared();
                self.read_with = None;
            }
            self.catch_up(sources);
            self.element(st, sources);
            return;
        }
        if known(&st.keyword, &["reference"]).is_some() {
            let _ = reference(st, &mut c, &mut self.frames);
        } else if known(&st.keyword, &["scalar function"]).is_some() {
            let _ = super::drives::scalar_functions::scalar_function_card(&mut c, &mut self.drives.functions, st.seq);
        } else if in_nodes_block && same_keyword(&st.keyword, "structural") && node_statement(st, &mut c, &self.frames, &mut self.nodes).is_ok() {
            if let Some(e) = self.nodes.0.last().filter(|e| !e.dummy) {
                let n = &e.node;
                self.drives.structural_nodes.insert(n.label);
                self.known.insert(n.label, NodeKinematics { x: n.position, r: n.orientation, xdot: n.velocity, omega: n.angular_velocity });
            }
        }
    }
    fn nodes(&self) -> &HashMap<u32, NodeKinematics> {
        &self.known
    }
    fn functions(&self) -> &super::syntax::card_tables::FunctionsBefore {
        &self.visible
    }
    fn drives(&self) -> &super::syntax::card_tables::DrivesBefore {
        &self.drive_table
    }
    /// A string drive reads the variables as they stand when it is called (MBDyn's
    /// `StringDriveCaller` keeps the parsed expression, not the values): after a `set:`
    /// changed them, the cards read so far are read again with the new values.
    fn refresh_drives(&mut self, variables: &Variables, sources: &Sources) {
        if self.read_with != Some(variables.generation()) {
            // One copy of the variables, shared by every string drive read with them.
            self.drives.variables = variables.shared();
            self.read_with = Some(variables.generation());
            self.drives.clear_cards();
            self.drive_table = self.drives.defined_before(usize::MAX);
            self.cards_read = 0;
        }
        self.catch_up(sources);
    }
    fn elements(&self) -> &super::syntax::model_namespace::ElementsRead {
        &self.elements
    }
}

impl Default for WrittenNodes {
    fn default() -> Self {
        let drives = super::drives::callers::Drives::default();
        WrittenNodes {
            frames: Frames::default(),
            nodes: Nodes::default(),
            known: HashMap::new(),
            visible: drives.functions.before(usize::MAX),
            drive_table: drives.defined_before(usize::MAX),
            drives,
            drive_cards: Vec::new(),
            read_with: None,
            cards_read: 0,
            elements: Default::default(),
        }
    }
}

impl WrittenNodes {
    /// Reads the drive caller cards not read yet (with the variables of the last refresh).
    fn catch_up(&mut self, sources: &Sources) {
        if self.cards_read == self.drive_cards.len() {
            return;
        }
        for old in &self.drive_cards[self.cards_read..] {
            let _ = super::drives::callers::drive_caller_card(old, &mut Cursor::new(old, sources), &mut self.drives);
        }
        self.cards_read = self.drive_cards.len();
    }

    /// Reads a body or joint card as the model does, for `model::element::…` further down.
    fn element(&mut self, st: &Statement, sources: &Sources) {
        let Some(super::syntax::parser::Arg { value: super::syntax::parser::Value::Number(x), .. }) = st.args.first() else { return };
        if *x < 0.0 || x.fract() != 0.0 || *x > u32::MAX as f64 {
            return;
        }
        let laws = super::elements::laws::Laws::default();
        let beams = super::elements::context::BeamNodes::new();
        let fluids = super::elements::context::Fluids::new();
        let beam_notes = std::cell::RefCell::new(Vec::new());
        let ctx = super::elements::context::ElementContext { nodes: &self.nodes, frames: &self.frames, drives: &self.drives, laws: &laws, fluids: &fluids, beams: &beams, seq: st.seq, static_model: false, beam_update: Default::default(), beam_notes: &beam_notes, hydraulic_output: false };
        let built = match super::elements::block::element(st, &mut Cursor::new(st, sources), &ctx) {
            Ok(super::elements::context::Parsed::Element(e)) => Ok(e),
            Ok(super::elements::context::Parsed::Body(b)) => Ok(Box::new(b) as Box<dyn crate::element::Element>),
            Ok(_) => Err("it is not an element with private data".to_string()),
            Err(e) => Err(e.message),
        };
        self.elements.insert((super::elements::block::label_space(&st.keyword), *x as u32), built);
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
