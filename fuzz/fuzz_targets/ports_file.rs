//! Any text must give ports or an error from the ports-file reader, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let _ = romdyn::input::ports_file::parse_ports(&text, std::path::Path::new("ports.json"));
});
