//! The dimensions of MBDyn's template drive callers other than the 3-vector, and their
//! terms (read in [`super::templates`], kept in [`super::callers::Drives`]).

use crate::element::drive::Drive;

/// The dimension of a template drive caller other than the 3-vector.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TemplateDim {
    Scalar,
    Vec6,
    Mat3x3,
    Mat6x6,
}

impl TemplateDim {
    /// The dimension as a card writes it (`1`, `6`, `"3x3"`, `"6x6"`).
    pub fn name(self) -> &'static str {
        match self {
            TemplateDim::Scalar => "1",
            TemplateDim::Vec6 => "6",
            TemplateDim::Mat3x3 => "3x3",
            TemplateDim::Mat6x6 => "6x6",
        }
    }
    /// Rows and columns of the value.
    pub(in crate::mbdyn) fn shape(self) -> (usize, usize) {
        match self {
            TemplateDim::Scalar => (1, 1),
            TemplateDim::Vec6 => (6, 1),
            TemplateDim::Mat3x3 => (3, 3),
            TemplateDim::Mat6x6 => (6, 6),
        }
    }
    /// The dimension a card names, `None` for "3" and anything else.
    pub fn from_name(name: &str) -> Option<Self> {
        match name.to_ascii_lowercase().as_str() {
            "1" => Some(TemplateDim::Scalar),
            "6" => Some(TemplateDim::Vec6),
            "3x3" => Some(TemplateDim::Mat3x3),
            "6x6" => Some(TemplateDim::Mat6x6),
            _ => None,
        }
    }
}

/// One term of a template drive caller: its value (entries by rows) times a drive.
pub type Term = (Vec<f64>, Drive);
