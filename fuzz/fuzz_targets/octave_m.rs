//! Any text must give a script or an error from the Octave reader, never a panic; a
//! script that parses is also read as an MBDyn eigenanalysis pencil.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(script) = romdyn::input::octave_m::parse_octave_script(&text, std::path::Path::new("fuzz.m")) {
        let _ = romdyn::input::eigen_pencil::pencil_from_script(&script, &romdyn::input::eigen_pencil::PencilPorts { input_rows: vec![1], output_cols: vec![2] });
    }
});
