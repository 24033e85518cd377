//! Any text must give a matrix or an error from the Matrix Market reader, never a panic
//! or an allocation beyond the budget.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = romdyn::input::matrix_market::parse_matrix(&text, std::path::Path::new("fuzz.mtx"));
});
