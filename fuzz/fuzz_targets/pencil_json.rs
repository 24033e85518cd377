//! Any text must give a pencil or an error from the JSON pencil reader, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = romdyn::input::pencil::parse_pencil(&text, std::path::Path::new("fuzz-nonexistent-dir/fuzz.json"));
});
