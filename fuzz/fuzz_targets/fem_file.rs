//! MBDyn's FEM file of the modal element (issue 35): any text is read into a FEM file or
//! refused with file:line:column, never a panic, an abort, a hang or an allocation the
//! file's length does not justify; a file that reads gives finite numbers and consistent
//! sizes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    match romdyn::input::fem::parse_fem(&text, std::path::Path::new("fuzz.fem")) {
        Ok(fem) => {
            let (n, m) = (fem.nodes(), fem.modes());
            assert!(fem.positions.len() == n && fem.shapes.len() == m && fem.shapes.iter().all(|s| s.len() == n));
            assert!(fem.stiffness.nrows() == m && fem.mass.ncols() == m);
            assert!(fem.positions.iter().flatten().all(|x| x.is_finite()));
            let _ = fem.rigid_body_inertia();
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.fem:"), "{e}"),
    }
});
