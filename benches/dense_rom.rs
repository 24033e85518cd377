//! Dense eigenanalysis + ROM extraction on random well-conditioned pencils
//! (issue 2 benchmark): `cargo bench --bench dense_rom`.

use faer::Mat;
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::linear::{Jacobians, LinearDae};
use romdyn::rom::{select_modes, DescriptorRom, ModeSelection};

fn main() {
    divan::main();
}

/// Deterministic pseudo-random numbers in [-0.5, 0.5) (xorshift64*).
fn noise(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed.max(1);
    move || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545F4914F6CDD1D) >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

/// `F_yd = I + R₁/√n`, `F_y = diag(1..n) + R₂/√n`: well-conditioned, distinct eigenvalues.
fn pencil(n: usize) -> LinearDae {
    let mut r = noise(n as u64);
    let s = 1.0 / (n as f64).sqrt();
    let fyd = Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 } + s * r());
    let fy = Mat::from_fn(n, n, |i, j| if i == j { (i + 1) as f64 } else { 0.0 } + s * r());
    let b = Mat::from_fn(n, 1, |i, _| if i == n - 1 { 1.0 } else { 0.0 });
    let c = Mat::from_fn(1, n, |_, j| if j == n - 1 { 1.0 } else { 0.0 });
    LinearDae {
        jacobians: Jacobians::Derivatives { fyd, fy },
        b,
        c,
        unknown_names: vec![],
        input_names: vec!["u".into()],
        output_names: vec!["z".into()],
        constraint_form: None,
        multipliers: Vec::new(),
        c_rate: None,
    }
}

#[divan::bench(args = [100, 500, 2000], sample_count = 3, sample_size = 1)]
fn eigen_and_rom(bencher: divan::Bencher, n: usize) {
    let dae = pencil(n);
    bencher.bench(|| {
        let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Direct).unwrap();
        let sel = select_modes(&modal, &ModeSelection::Lowest(5)).unwrap();
        let rom = DescriptorRom::project(&dae, &modal, &sel, true).unwrap();
        divan::black_box(rom.to_ordinary().unwrap())
    });
}
