//! `model::element::TYPE(LABEL, "NAME")` inside a `string` drive (modelns.cc `model_elem`:
//! the element's `dGetPrivData` when the expression is evaluated, during the run). The
//! drive's check while the file is read notes each read; the reader fills each one's cell
//! from the element after the elements block (`element_reads.rs`), and the run reads the
//! datum from the state the drive is evaluated in.

use std::cell::RefCell;
use std::sync::{Arc, OnceLock};

use crate::element::private_data::PrivateDatum;
use crate::element::ElementState;
use crate::model::Label;
use crate::mbdyn::syntax::model_namespace;

/// Where a datum read by a drive waits for the elements block.
pub type Cell = Arc<OnceLock<PrivateDatum>>;

/// A `model::element::TYPE(LABEL, "NAME")` of a string drive: the element, the datum's name
/// and the cell that holds the datum once the elements are read.
pub struct StringRead {
    pub(in crate::mbdyn) element: (&'static str, Label),
    pub(in crate::mbdyn) name: String,
    pub(in crate::mbdyn) cell: Cell,
}

/// What `model::element::…` reads inside a string drive.
#[derive(Clone, Copy)]
pub enum RunElements<'a> {
    /// The drive's check while the file is read: each read is noted, and gives 0.
    Note(&'a RefCell<Vec<StringRead>>),
    /// During the run: the noted reads, filled after the elements block, at this state.
    Read(&'a [StringRead], &'a dyn ElementState),
}

/// `model::element::KIND(LABEL, "NAME")` in a string drive (modelns.cc `model_elem`:
/// `dGetPrivData` of the element at evaluation time).
pub fn string_read(kind: &str, label_arg: f64, name: &str, run: RunElements) -> Result<f64, String> {
    let call = format!("model::element::{kind}({label_arg}, \"{name}\")");
    let element = model_namespace::element_key(kind, label_arg, &call)?;
    match run {
        RunElements::Note(noted) => {
            let mut noted = noted.borrow_mut();
            if !noted.iter().any(|r| r.element == element && r.name == name) {
                noted.push(StringRead { element, name: name.to_string(), cell: Arc::default() });
            }
            Ok(0.0)
        }
        RunElements::Read(reads, st) => {
            let read = reads.iter().find(|r| r.element == element && r.name == name);
            let datum = read.and_then(|r| r.cell.get()).ok_or_else(|| format!("{call}: not among the reads romdyn found when it checked the drive (a label or name that changes during the run is not supported)"))?;
            datum.value(st).ok_or_else(|| format!("{call}: a node of the element is not in the state"))
        }
    }
}

