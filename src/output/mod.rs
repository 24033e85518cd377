//! Writing results: MATLAB v5 `.mat`, NumPy `.npz`, JSON, CSV, Bode plots; every file is
//! written atomically (temporary file, then rename).

pub mod atomic;
pub mod bode;
pub mod mat5;
pub mod matrix_market;
pub mod modal;
pub mod motion;
pub mod npz;
pub mod response_csv;
pub mod rom_file;
