//! The tables of the cards read so far that expressions look into while the file is read
//! (`model::sf::NAME(x)`, `model::drive(LABEL, x)` in `set:` and string drives): scalar
//! functions by name, drive callers by label, each shared (an `Arc`) with the views a
//! statement keeps of the cards before it. Below the readers that fill them
//! (`scalar_functions`, `drives`) and the evaluator that reads them (`expr`), so that
//! neither imports the other through them.

use std::collections::HashMap;
use std::sync::{Arc, RwLock};

use super::diagnostic::Span;
use crate::element::drive::{Drive, EvaluationCost, ScalarFunction};

/// A card: the function (shared by every use), its statement, its place and its cost.
pub(in crate::mbdyn) type Card = (Arc<ScalarFunction>, usize, Span, EvaluationCost);

/// The scalar functions defined so far, by name, with the statement defining them. The
/// table is shared (an `Arc`) with the views string drives keep ([`FunctionsBefore`]):
/// a drive does not copy the table (which made N drives O(N²)).
#[derive(Clone, Default)]
pub struct ScalarFunctions {
    pub(in crate::mbdyn) table: Arc<RwLock<HashMap<Arc<str>, Card>>>,
    /// The names looked up by name since the last [`ScalarFunctions::take_used`] (what the
    /// statement being read uses), and the functions a `drive caller:` card uses by name:
    /// run-time messages name the cards an element's law evaluates. (A scalar function
    /// card's operands are found from its function and [`Self::by_address`].)
    used: Arc<RwLock<Vec<String>>>,
    operands: Arc<RwLock<HashMap<String, Vec<String>>>>,
    /// The places of the `drive caller:` cards an element can evaluate through a reference
    /// (noted as used under [`drive_key`]), which messages name: "drive caller 3 (f.mbd:5:1)".
    drive_cards: Arc<RwLock<HashMap<u32, Span>>>,
    /// Each defined card's cost and name by the address of its function (the table keeps
    /// every function alive, so an address is never reused while it is here): a new card's
    /// cost is found from its operands' without walking what they are made of, and a card's
    /// operands are named from its function (no list of names kept per card, issue 32).
    by_address: Arc<RwLock<HashMap<usize, (EvaluationCost, Arc<str>)>>>,
}

const DRIVE_KEY: &str = "#drive caller ";

/// The key of `drive caller:` card `label` among the names noted as used.
pub(in crate::mbdyn) fn drive_key(label: u32) -> String {
    format!("{DRIVE_KEY}{label}")
}

/// The scalar functions a statement sees: those of cards before it (`model::sf::NAME`).
#[derive(Clone, Default)]
pub struct FunctionsBefore {
    functions: ScalarFunctions,
    seq: usize,
}

impl FunctionsBefore {
    /// The function `name`, if a card before the statement defines it, with its cost.
    pub fn get(&self, name: &str) -> Option<(Arc<ScalarFunction>, EvaluationCost)> {
        self.functions.card(name).filter(|c| c.1 < self.seq).map(|c| (c.0, c.3))
    }
}

impl ScalarFunctions {
    pub(in crate::mbdyn) fn card(&self, name: &str) -> Option<Card> {
        self.table.read().unwrap_or_else(|e| e.into_inner()).get(name).cloned()
    }

    /// Defines card `name` (its function, statement, place and cost).
    pub(in crate::mbdyn) fn define(&self, name: String, card: Card) {
        // One copy of the name, shared by the table and the address map.
        let name: Arc<str> = Arc::from(name);
        self.by_address.write().unwrap_or_else(|e| e.into_inner()).insert(Arc::as_ptr(&card.0) as usize, (card.3, name.clone()));
        self.table.write().unwrap_or_else(|e| e.into_inner()).insert(name, card);
    }

    /// The cost of `f` if it is a defined card's function.
    pub(in crate::mbdyn) fn known_cost(&self, f: &Arc<ScalarFunction>) -> Option<EvaluationCost> {
        self.by_address.read().unwrap_or_else(|e| e.into_inner()).get(&(Arc::as_ptr(f) as usize)).map(|(c, _)| *c)
    }

    /// Notes that the statement being read uses the function `name`.
    pub(in crate::mbdyn) fn note_used(&self, name: &str) {
        self.used.write().unwrap_or_else(|e| e.into_inner()).push(name.to_string());
    }

    /// The names noted since the last call, in order, without repeats.
    pub(in crate::mbdyn) fn take_used(&self) -> Vec<String> {
        let names = std::mem::take(&mut *self.used.write().unwrap_or_else(|e| e.into_inner()));
        if names.len() < 2 {
            return names;
        }
        // Few names per statement: keep each first occurrence, without copying them.
        let mut kept: Vec<String> = Vec::with_capacity(names.len());
        for n in names {
            if !kept.contains(&n) {
                kept.push(n);
            }
        }
        kept
    }

    /// Records the functions `drive caller:` card `name` ([`drive_key`]) uses (nothing when
    /// none).
    pub(in crate::mbdyn) fn set_operands(&self, name: &str, operands: Vec<String>) {
        if !operands.is_empty() {
            self.operands.write().unwrap_or_else(|e| e.into_inner()).insert(name.to_string(), operands);
        }
    }

    /// Records where `drive caller:` card `label` is written.
    pub(in crate::mbdyn) fn set_drive_card(&self, label: u32, at: Span) {
        self.drive_cards.write().unwrap_or_else(|e| e.into_inner()).insert(label, at);
    }

    /// `names` and the functions they are made of, each once, as `scalar function "NAME"
    /// (at)` with `at(span)` its card's place.
    pub(in crate::mbdyn) fn described(&self, names: &[String], at: impl Fn(Span) -> String) -> Vec<String> {
        let operands = self.operands.read().unwrap_or_else(|e| e.into_inner());
        let (mut queue, mut seen, mut out) = (names.to_vec(), std::collections::HashSet::new(), Vec::new());
        while let Some(name) = (!queue.is_empty()).then(|| queue.remove(0)) {
            if !seen.insert(name.clone()) {
                continue;
            }
            if let Some(card) = self.card(&name) {
                out.push(format!("scalar function \"{name}\" ({})", at(card.2)));
                // Its `sum`/`sub`/`mul`/`div` operands, by the names of their cards.
                let by_address = self.by_address.read().unwrap_or_else(|e| e.into_inner());
                queue.extend(card.0.operands().into_iter().flatten().filter_map(|g| by_address.get(&(Arc::as_ptr(g) as usize)).map(|(_, n)| n.to_string())));
            } else if let Some(label) = name.strip_prefix(DRIVE_KEY).and_then(|l| l.parse::<u32>().ok()) {
                if let Some(&span) = self.drive_cards.read().unwrap_or_else(|e| e.into_inner()).get(&label) {
                    out.push(format!("drive caller {label} ({})", at(span)));
                }
            }
            queue.extend(operands.get(&name).into_iter().flatten().cloned());
        }
        out
    }

    /// The functions defined before statement `seq` (what `sf::NAME` sees), shared.
    pub fn before(&self, seq: usize) -> FunctionsBefore {
        FunctionsBefore { functions: self.clone(), seq }
    }
}

/// A `drive caller:` card: its drive, statement and place.
#[derive(Clone)]
pub(in crate::mbdyn) struct DriveCard {
    pub(in crate::mbdyn) drive: Arc<Drive>,
    pub(in crate::mbdyn) seq: usize,
    pub(in crate::mbdyn) span: Span,
}

/// The `drive caller:` cards, by label, shared (an `Arc`) with the views string drives
/// keep ([`DrivesBefore`]): a string drive does not copy the table (which made N cards
/// O(N²) to read).
#[derive(Clone, Default)]
pub struct DriveTable(Arc<RwLock<HashMap<u32, DriveCard>>>);

impl DriveTable {
    pub(in crate::mbdyn) fn get(&self, label: u32) -> Option<DriveCard> {
        self.0.read().unwrap_or_else(|e| e.into_inner()).get(&label).cloned()
    }
    pub(in crate::mbdyn) fn insert(&self, label: u32, card: DriveCard) {
        self.0.write().unwrap_or_else(|e| e.into_inner()).insert(label, card);
    }
    /// The costs of the cards before statement `seq` (a `model::drive` whose label is
    /// computed may call any of them).
    pub(in crate::mbdyn) fn costs_before(&self, seq: usize) -> Vec<EvaluationCost> {
        self.0.read().unwrap_or_else(|e| e.into_inner()).values().filter(|d| d.seq < seq).map(|d| d.drive.cost()).collect()
    }
    /// The cards a statement at `seq` sees.
    pub fn before(&self, seq: usize) -> DrivesBefore {
        DrivesBefore { table: self.clone(), seq }
    }
}

/// The `drive caller:` cards a statement sees: those before it (`model::drive(LABEL, x)`).
#[derive(Clone, Default)]
pub struct DrivesBefore {
    table: DriveTable,
    seq: usize,
}

impl DrivesBefore {
    /// The drive of card `label`, if it comes before the statement.
    pub fn get(&self, label: u32) -> Option<Arc<Drive>> {
        self.table.get(label).filter(|d| d.seq < self.seq).map(|d| d.drive)
    }
}
