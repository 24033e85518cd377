//! Any text must give a model or an error from the MBDyn reader, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("fuzz.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d));
});
