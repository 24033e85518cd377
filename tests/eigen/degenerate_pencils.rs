//! Property test: random regular pencils with a known dynamic pair, their rows and
//! columns scaled by random factors so entries span 1e-200 … 1e200. Row and column
//! scaling (`D_r (λ F_yd + F_y) D_c`) leaves every eigenvalue unchanged, so the pair must
//! still be labelled dynamic with the same value, or the eigenanalysis must return an
//! error; it may never come back with the pair labelled zero or infinite.
//!
//! Construction: `F_yd = P diag(1, 1, 1, …) Q`, `F_y = P blockdiag([[0, -w²], [1, 0]] …) Q`
//! (after a sign: `λ F_yd + F_y` singular at λ = ±j w) with random well-conditioned P, Q,
//! plus one infinite eigenvalue (a zero row/column pair of F_yd, a 1 in F_y).

use faer::Mat;
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::Jacobians;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random pencil of size 4 with eigenvalues ±j w (dynamic), -d (dynamic, real) and ∞.
fn pencil(r: &mut Rng, w: f64, d: f64) -> (Mat<f64>, Mat<f64>) {
    let n = 4;
    let mut e = Mat::<f64>::zeros(n, n);
    let mut a = Mat::<f64>::zeros(n, n);
    // λ E + A = 0: block [[λ, -1], [w², λ]] gives λ² + w² = 0 → λ = ±j w.
    e[(0, 0)] = 1.0;
    e[(1, 1)] = 1.0;
    a[(0, 1)] = -1.0;
    a[(1, 0)] = w * w;
    // λ + d = 0 → λ = -d.
    e[(2, 2)] = 1.0;
    a[(2, 2)] = d;
    // 0 λ + 1 = 0: infinite.
    a[(3, 3)] = 1.0;
    // Random well-conditioned P, Q: identity plus a small random part.
    let p = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 } + 0.3 * (r.next() - 0.5));
    let q = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 } + 0.3 * (r.next() - 0.5));
    (&p * &e * &q, &p * &a * &q)
}

fn scaled(m: &Mat<f64>, row: &[f64], col: &[f64]) -> Mat<f64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| row[i] * m[(i, j)] * col[j])
}

#[test]
fn scaled_regular_pencils_keep_their_labels_or_fail() {
    let mut r = Rng(0x2545_F491_4F6C_DD1D);
    let (mut labelled_right, mut errors) = (0, 0);
    for case in 0..200 {
        let w = 10f64.powf(4.0 * r.next() - 2.0);
        let d = 10f64.powf(2.0 * r.next() - 1.0);
        let (fyd, fy) = pencil(&mut r, w, d);
        // Row and column factors 10^±100 each: entries from about 1e-200 to 1e200.
        let row: Vec<f64> = (0..4).map(|_| 10f64.powf(200.0 * r.next() - 100.0)).collect();
        let col: Vec<f64> = (0..4).map(|_| 10f64.powf(200.0 * r.next() - 100.0)).collect();
        let jac = Jacobians::Derivatives { fyd: scaled(&fyd, &row, &col), fy: scaled(&fy, &row, &col) };
        for route in [EigenRoute::Direct, EigenRoute::Lambda] {
            // The Λ form needs a dCoef of the order of 1/|λ| (paper §4): 1/w.
            let result = ModalAnalysis::compute_with_dcoef(&jac, route, Some(1.0 / w));
            let Ok(modal) = result else {
                errors += 1;
                continue;
            };
            let dynamic: Vec<_> = modal.modes.iter().filter(|m| m.kind == ModeKind::Dynamic).collect();
            // The pair ±j w and the real -d, to 1e-6 relative (eigenvalue condition of a
            // well-conditioned P, Q stays O(1) after balancing).
            let pair = dynamic.iter().filter(|m| (m.lambda.im.abs() - w).abs() < 1e-6 * w && m.lambda.re.abs() < 1e-6 * w).count();
            assert_eq!(pair, 2, "case {case}, {route:?}, w = {w}, d = {d}, row {row:?}, col {col:?}: {:?}", modal.modes.iter().map(|m| (m.lambda, m.kind)).collect::<Vec<_>>());
            let real = dynamic.iter().filter(|m| (m.lambda.re + d).abs() < 1e-6 * d.max(w) && m.lambda.im == 0.0).count();
            assert_eq!(real, 1, "case {case}, {route:?}, w = {w}, d = {d}: {:?}", modal.modes.iter().map(|m| (m.lambda, m.kind)).collect::<Vec<_>>());
            labelled_right += 1;
        }
    }
    eprintln!("{labelled_right} analyses labelled right, {errors} refused");
    assert!(labelled_right > 300, "only {labelled_right} of 400 analyses answered");
}

#[test]
fn uniformly_huge_or_tiny_pencils_keep_their_labels() {
    // The whole pencil times 1e300 or 1e-300 (the "largest entry 1e308" case):
    // eigenvalues unchanged, ±2j rad/s and -1 rad/s (closed form of the blocks above).
    let mut r = Rng(7);
    let (fyd, fy) = pencil(&mut r, 2.0, 1.0);
    for s in [1e300, 1e-300, 1.7e308 / 4.0] {
        let jac = Jacobians::Derivatives { fyd: &fyd * faer::Scale(s), fy: &fy * faer::Scale(s) };
        let modal = ModalAnalysis::compute_with_dcoef(&jac, EigenRoute::Lambda, Some(0.5)).unwrap();
        let kinds: Vec<ModeKind> = modal.modes.iter().map(|m| m.kind).collect();
        assert_eq!(kinds, [ModeKind::Dynamic, ModeKind::Dynamic, ModeKind::Dynamic, ModeKind::Infinite], "s = {s}");
        // Sorted by |λ|: -1 first, then the pair ±2j.
        assert!((modal.modes[0].lambda.re + 1.0).abs() < 1e-9, "s = {s}: {:?}", modal.modes[0].lambda);
        assert!((modal.modes[1].lambda.im.abs() - 2.0).abs() < 1e-9, "s = {s}: {:?}", modal.modes[1].lambda);
    }
}
