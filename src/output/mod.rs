//! Writing results: MATLAB v5 `.mat`, NumPy `.npz`, JSON, CSV, Bode plots; every file is
//! written atomically (temporary file, then rename).
