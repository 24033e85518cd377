//! A ROM as an FMI 2.0 Functional Mock-up Unit (`romdyn rom … -o NAME.fmu`, Python's
//! `Rom.save("NAME.fmu")`): one archive with model exchange and co-simulation, of a
//! continuous-time ROM (`x' = A x + B u`, `z = C x + D u`) or a discrete-time one
//! (`x[k+1] = A x[k] + B u[k]` at every sampling time: time events in model exchange),
//! named inputs, outputs and states with their SI units.
//!
//! The archive holds `modelDescription.xml` ([`model_description`]), the C source
//! (`sources/ID.c`: the matrices, then romdyn's runtime `runtime.c`) and the binary built
//! from it with the machine's C compiler (`$CC`, else `cc`) for this platform
//! (`binaries/linux64/ID.so`, `binaries/darwin64/ID.dylib`). Without a compiler the FMU is
//! not written (an FMU without a binary would look complete and load nowhere that does not
//! compile it).
//!
//! A co-simulation step of a continuous ROM is exact for inputs held over the step (the
//! zero-order-hold solution `x(t+h) = e^{Ah} x(t) + ∫₀ʰ e^{As} ds B u`), so an FMU's step
//! response equals the ROM's own at the communication points to rounding.

mod model_description;

use std::path::Path;
use std::process::Command;

use faer::Mat;

use super::rom_export::RomExport;

/// Why an FMU could not be made.
#[derive(Debug, thiserror::Error)]
pub enum FmuError {
    #[error("a descriptor ROM (E x' = A x + B u with E not the identity) has no FMU here: export the ordinary form (E = I), e.g. `--form ordinary`")]
    Descriptor,
    #[error("the FMU's binary is built with a C compiler ($CC, else cc) and {0}")]
    Compiler(String),
    #[error("an FMU binary is built for Linux and macOS only (this is {0})")]
    Platform(&'static str),
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// The FMI platform folder and the shared library's extension of this machine.
fn platform() -> Result<(&'static str, &'static str), FmuError> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => Ok(("linux64", "so")),
        ("linux", "x86") => Ok(("linux32", "so")),
        ("macos", _) => Ok(("darwin64", "dylib")),
        (os, _) => Err(FmuError::Platform(os)),
    }
}

/// The FMU's model identifier: the file's stem as a C identifier (letters, digits and `_`,
/// not starting with a digit), which names the binary and the source.
pub fn model_identifier(path: &Path) -> String {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("rom");
    let mut id: String = stem.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if id.is_empty() || id.starts_with(|c: char| c.is_ascii_digit()) {
        id.insert_str(0, "rom_");
    }
    id
}

/// A 128-bit FNV-1a digest of the ROM's matrices and names as a GUID: the same ROM gives
/// the same GUID, another ROM another one.
fn guid(export: &RomExport) -> String {
    let mut h: u128 = 0x6c62272e07bb014262b821756295c58d;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= b as u128;
            h = h.wrapping_mul(0x0000000001000000000000000000013B);
        }
    };
    for m in [&export.a, &export.b, &export.c, &export.d] {
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                eat(&m[(i, j)].to_le_bytes());
            }
        }
    }
    for name in export.inputs.iter().chain(&export.outputs).chain(&export.states) {
        eat(name.as_bytes());
    }
    eat(&export.sample_time.unwrap_or(0.0).to_le_bytes());
    let x = format!("{h:032x}");
    format!("{{{}-{}-{}-{}-{}}}", &x[0..8], &x[8..12], &x[12..16], &x[16..20], &x[20..32])
}

/// The C source: the ROM's sizes and matrices, then the runtime.
pub fn c_source(export: &RomExport) -> String {
    let (n, m, p) = (export.a.nrows(), export.b.ncols(), export.c.nrows());
    let array = |name: &str, mat: &Mat<f64>| {
        let mut values: Vec<String> = (0..mat.nrows()).flat_map(|i| (0..mat.ncols()).map(move |j| (i, j))).map(|(i, j)| format!("{:.17e}", mat[(i, j)])).collect();
        values.push("0.0".into());
        format!("static const double {name}[] = {{{}}};\n", values.join(", "))
    };
    let mut s = String::from("/* A ROM written by romdyn: SI units; the variables' names and units are in modelDescription.xml. */\n");
    s += &format!("#define N {n}\n#define M {m}\n#define P {p}\n");
    s += &format!("#define DISCRETE {}\n#define SAMPLE_TIME {:.17e}\n", export.sample_time.is_some() as u8, export.sample_time.unwrap_or(1.0));
    s += &format!("#define GUID \"{}\"\n", guid(export));
    for (name, mat) in [("A", &export.a), ("B", &export.b), ("C", &export.c), ("D", &export.d)] {
        s += &array(name, mat);
    }
    s + "\n" + include_str!("runtime.c")
}

/// Whether `e` is the identity (an ordinary ROM's E).
fn is_identity(e: &Mat<f64>) -> bool {
    e.nrows() == e.ncols() && (0..e.nrows()).all(|i| (0..e.ncols()).all(|j| e[(i, j)] == if i == j { 1.0 } else { 0.0 }))
}

/// Compiles `source` into a shared library with the machine's C compiler: its bytes.
fn compile(id: &str, source: &str, extension: &str) -> Result<Vec<u8>, FmuError> {
    // One folder per build, also between threads of one process.
    static BUILDS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let build = BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("romdyn-fmu-{}-{build}-{id}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let result = (|| {
        let (c_file, library) = (dir.join(format!("{id}.c")), dir.join(format!("{id}.{extension}")));
        std::fs::write(&c_file, source)?;
        let compiler = std::env::var("CC").ok().filter(|c| !c.trim().is_empty()).unwrap_or_else(|| "cc".into());
        let shared = if extension == "dylib" { "-dynamiclib" } else { "-shared" };
        let out = Command::new(&compiler)
            .args([shared, "-fPIC", "-O2", "-fvisibility=hidden", "-o"])
            .arg(&library)
            .arg(&c_file)
            .arg("-lm")
            .output()
            .map_err(|e| FmuError::Compiler(format!("'{compiler}' could not be run ({e})")))?;
        if !out.status.success() {
            let why = String::from_utf8_lossy(&out.stderr);
            return Err(FmuError::Compiler(format!("'{compiler}' failed: {}", why.trim())));
        }
        Ok(std::fs::read(&library)?)
    })();
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// The FMU archive of `export`, its model identifier `id`.
pub fn fmu_bytes(export: &RomExport, id: &str) -> Result<Vec<u8>, FmuError> {
    if !is_identity(&export.e) {
        return Err(FmuError::Descriptor);
    }
    let (platform, extension) = platform()?;
    let source = c_source(export);
    let binary = compile(id, &source, extension)?;
    let xml = model_description::xml(export, id, &guid(export));
    let entries = vec![
        ("modelDescription.xml".to_string(), xml.into_bytes()),
        (format!("sources/{id}.c"), source.into_bytes()),
        (format!("binaries/{platform}/{id}.{extension}"), binary),
    ];
    Ok(super::zip::stored_archive(&entries))
}

#[cfg(test)]
mod tests;
