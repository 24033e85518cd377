//! Right and left vectors put together, eigenvalue by eigenvalue, including repeated ones.
//!
//! A symmetric beam section bends alike in two planes: each bending eigenvalue is double.
//! A single-vector Krylov space holds one vector of such an eigenspace (the second only
//! through rounding), and the right run and the adjoint run each pick their own: matching
//! a right vector with the left vector of the nearest eigenvalue can pair the y-bending
//! right vector with the z-bending left one, whose `uᵀ E v ≈ 0` makes the error estimate
//! (and the ROM's projection) meaningless. Here the vectors of one eigenvalue (all within
//! [`CLUSTER`] of each other) are gathered from both runs (and from every round of
//! [`super::shifts`]' search), each side reduced to a basis of the eigenspace it found; a
//! cluster with as many independent right as left vectors becomes that many pairs,
//! bi-orthogonal in `E` (the two-sided Rayleigh–Ritz of the small pencil
//! `(Uᵀ K V, Uᵀ E V)`); any other cluster is reported unmatched.

use faer::linalg::solvers::DenseSolveCore;
use faer::{c64, Col, Mat};

use super::pencil::Pencil;
use crate::eigen::route::norm;
use crate::linear::{contiguous, contiguous_mut};

/// Ritz values closer than this, relative to their distance from the shift (or to |λ|),
/// are one cluster. Those far from the shift are only that accurate (the cantilever's
/// 5733 rad/s pair came out of the runs with real parts from −0.004 to 0.03 rad/s); the
/// cluster's inverse iteration sorts out what it holds, distinct eigenvalues included.
pub(super) const CLUSTER: f64 = 1e-5;

/// A Ritz direction of a cluster (or of another cluster of the same eigenvalue) whose part
/// outside the span of those kept is below this fraction of its norm adds nothing to the
/// eigenspace: it repeats it. The directions are accurate eigenvectors by then (each passed
/// [`RITZ_RESIDUAL`]); a new one of a repeated eigenvalue, from a random start, keeps a
/// part of order 1 outside the others.
const NEW_DIRECTION: f64 = 2e-2;

/// Pairs `(λ, v, u)` of eq. 29 ready for [`super::window::evaluate`], and the eigenvalues
/// of clusters whose two sides found different numbers of vectors (one entry per vector
/// one side has and the other lacks).
pub(super) struct Clusters {
    pub pairs: Vec<(c64, Col<c64>, Col<c64>)>,
    pub unmatched: Vec<c64>,
}

/// Eigenvalues within this distance of λ are one cluster ([`CLUSTER`] relative to λ's
/// distance from the shift σ, or to a thousandth of |λ|).
fn cluster_radius(lambda: c64, sigma: c64) -> f64 {
    CLUSTER * (lambda - sigma).norm().max(lambda.norm() * 1e-3).max(f64::MIN_POSITIVE)
}

/// Smallest `|uᵀ E v|` of unit vectors, relative to `‖E v‖`, that pairs them (a left and a
/// right vector of different eigenvectors of one eigenvalue give rounding, ~1e-16).
const FACING: f64 = 1e-8;

/// Orthonormal basis of the span of `vectors` (modified Gram–Schmidt, twice), dropping
/// each vector whose part outside those kept is at most `new_direction` of its norm.
fn basis(vectors: &[&Col<c64>], new_direction: f64) -> Vec<Col<c64>> {
    let mut q: Vec<Col<c64>> = Vec::new();
    for v in vectors {
        let nv = norm(v);
        if !(nv > 0.0) {
            continue;
        }
        let w = outside(v, &q);
        let nw = norm(&w);
        if nw > new_direction * nv {
            let mut w = w;
            contiguous_mut(w.as_mut()).iter_mut().for_each(|e| *e = *e / nw);
            q.push(w);
        }
    }
    q
}

/// The part of `v` outside the span of the orthonormal `q` (modified Gram–Schmidt, twice;
/// on the vectors' slices: indexing the columns entry by entry took 0.28 s of the 96,024-
/// equation spring chain's cluster refinement, the same sums in the same order).
fn outside(v: &Col<c64>, q: &[Col<c64>]) -> Col<c64> {
    let mut w = v.clone();
    for _ in 0..2 {
        for b in q {
            let (bs, ws) = (contiguous(b.as_ref()), contiguous_mut(w.as_mut()));
            let d = bs.iter().zip(ws.iter()).fold(c64::new(0.0, 0.0), |s, (x, y)| s + x.conj() * y);
            for (wi, bi) in ws.iter_mut().zip(bs) {
                *wi -= bi * d;
            }
        }
    }
    w
}

/// `‖x − P x‖ / ‖x‖`, `P` the orthogonal projector on the span of `vectors`: how far `x` is
/// from repeating them (0 when it lies in their span).
pub(super) fn outside_span<'a>(x: &Col<c64>, vectors: impl Iterator<Item = &'a Col<c64>>) -> f64 {
    let q = basis(&vectors.collect::<Vec<_>>(), DEPENDENT);
    norm(&outside(x, &q)) / norm(x).max(f64::MIN_POSITIVE)
}

/// Inverse iterations per completed eigenspace.
const INVERSE_ITERATIONS: usize = 3;

/// Most start vectors a cluster's inverse iteration takes from the Krylov runs.
const MAX_STARTS: usize = 8;

/// A Ritz direction of the inverse-iterated block belongs to the cluster's eigenspace when
/// its eigenvalue (`μ − 1/θ`, θ its Ritz value of `(K + μ E)⁻¹ E`) lies within
/// [`cluster_radius`] of the block's dominant one and its residual `‖T x − θ x‖` is at most
/// this fraction of `|θ| ‖x‖`. The block's other directions are what the iteration has not
/// removed yet: the transients of the non-normal operator (the θ = 0 Jordan blocks of the
/// constrained variables) and the parts along other eigenvalues, whose Ritz values are far
/// or unconverged (another eigenvalue is its own cluster's). A threshold on the bare part of
/// each direction outside the others (what [`basis`] alone judged by before) took those for
/// new directions: the 32-element cantilever's 13614 rad/s torsion mode (simple) kept two
/// right directions and one left one, was left unpaired, and the count never closed.
const RITZ_RESIDUAL: f64 = 1e-6;

/// A cluster's eigenspaces after inverse subspace iteration: the dominant Ritz value λ (the
/// refined eigenvalue) and orthonormal bases of the right and left directions whose Ritz
/// values pass [`RITZ_RESIDUAL`].
struct Refined {
    lambda: c64,
    right: Vec<Col<c64>>,
    left: Vec<Col<c64>>,
}

/// Orthonormal bases of λ's right and left eigenspaces by inverse subspace iteration with
/// the operator factored at `μ = λ + δ`, `|δ|` a millionth of |λ − σ| or ten times the
/// cluster's `width` (the Ritz values' spread about λ), whichever is larger (each iteration
/// shrinks the parts along the other eigenvalues by `|δ|/gap`, below 1e-5 on a beam's
/// bending pairs), then a Rayleigh–Ritz step on each side's block: the directions of the
/// cluster's eigenvalues are the Ritz vectors whose eigenvalues lie next to the dominant one
/// (see [`RITZ_RESIDUAL`]), the bases' sizes the multiplicity each side sees. The vectors come out
/// as accurate as the factorization allows, also those of Ritz pairs far from the shift. `None`
/// when μ cannot be factored.
fn refine(pencil: &Pencil, lambda: c64, sigma: c64, width: f64, starts: &[&Col<c64>], extra: usize) -> Option<Refined> {
    let d = (1e-6 * (lambda - sigma).norm().max(lambda.norm() * 1e-3)).max(10.0 * width).max(f64::MIN_POSITIVE);
    let mu = lambda + c64::new(d * std::f64::consts::FRAC_1_SQRT_2, d * std::f64::consts::FRAC_1_SQRT_2);
    let op = super::operator::ShiftInvert::new(pencil, mu).ok()?;
    let mut ws = op.workspace();
    let n = pencil.dim();
    let mut seed = 0x9E37_79B9_7F4A_7C15u64 ^ (lambda.im.to_bits().rotate_left(17));
    let mut random = || {
        Col::<c64>::from_fn(n, |_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            c64::new((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5, 0.0)
        })
    };
    let randoms: Vec<Col<c64>> = (0..extra).map(|_| random()).collect();
    let mut side = |transpose: bool| -> Option<Vec<(c64, Col<c64>)>> {
        // The block at once: the factors read once per iteration, not once per vector.
        let mut apply = |q: &[Col<c64>]| -> Vec<Col<c64>> { op.apply_block(q, transpose, &mut ws) };
        let mut q: Vec<Col<c64>> = basis(&starts.iter().copied().chain(randoms.iter()).collect::<Vec<_>>(), DEPENDENT);
        for _ in 0..INVERSE_ITERATIONS {
            q = basis(&apply(&q).iter().collect::<Vec<_>>(), DEPENDENT);
        }
        ritz_directions(&q, &apply(&q))
    };
    let right = side(false)?;
    let left = side(true)?;
    // The refined eigenvalue: the right block's dominant Ritz value (the left one's agrees).
    let theta = right.first().or(left.first())?.0;
    let lambda = op.lambda(theta);
    let radius = cluster_radius(lambda, sigma);
    let keep = |list: Vec<(c64, Col<c64>)>| -> Vec<Col<c64>> {
        let vectors: Vec<Col<c64>> = list.into_iter().filter(|(t, _)| (op.lambda(*t) - lambda).norm() <= radius).map(|(_, x)| x).collect();
        basis(&vectors.iter().collect::<Vec<_>>(), NEW_DIRECTION)
    };
    Some(Refined { lambda, right: keep(right), left: keep(left) })
}

/// Vectors whose part outside the span of those kept is below this fraction of their norm
/// are numerically dependent on them (dropped from a block before it is iterated on).
const DEPENDENT: f64 = 1e-8;

/// The Ritz pairs `(θ, Q z)` of the block `Q` (orthonormal) with `Y = T Q`, largest |θ|
/// first, that pass [`RITZ_RESIDUAL`]; `None` when the small
/// eigenproblem fails.
fn ritz_directions(q: &[Col<c64>], y: &[Col<c64>]) -> Option<Vec<(c64, Col<c64>)>> {
    let m = q.len();
    if m == 0 {
        return Some(Vec::new());
    }
    let n = q[0].nrows();
    let dot = |a: &Col<c64>, b: &Col<c64>| a.iter().zip(b.iter()).fold(c64::new(0.0, 0.0), |s, (x, y)| s + x.conj() * y);
    let h = Mat::<c64>::from_fn(m, m, |i, j| dot(&q[i], &y[j]));
    let e = h.eigen().ok()?;
    let thetas: Vec<c64> = e.S().column_vector().iter().copied().collect();
    let mut out: Vec<(c64, Col<c64>)> = Vec::new();
    for (k, &theta) in thetas.iter().enumerate() {
        if !(theta.norm() > 0.0) {
            continue;
        }
        let z = e.U().col(k);
        let x = combination(q, |j| z[j]);
        let tx = combination(y, |j| z[j]);
        let r = (0..n).map(|i| (tx[i] - theta * x[i]).norm_sqr()).sum::<f64>().sqrt();
        if r <= RITZ_RESIDUAL * theta.norm() * norm(&x) {
            out.push((theta, x));
        }
    }
    out.sort_by(|a, b| b.0.norm().total_cmp(&a.0.norm()));
    Some(out)
}

/// `Σⱼ xⱼ cⱼ` over the vectors `xs` (at least one), each entry summed from zero in the
/// order of j: the sums of a fold over j entry by entry (the same bits), on the vectors'
/// slices (indexing the columns entry by entry took a fifth of the 96,024-equation spring
/// chain's cluster refinement).
fn combination(xs: &[Col<c64>], c: impl Fn(usize) -> c64) -> Col<c64> {
    let mut out = Col::<c64>::zeros(xs[0].nrows());
    let o = contiguous_mut(out.as_mut());
    for (j, x) in xs.iter().enumerate() {
        let cj = c(j);
        for (oi, xi) in o.iter_mut().zip(contiguous(x.as_ref())) {
            *oi = *oi + xi * cj;
        }
    }
    out
}

/// `xᵀ y` (no conjugation).
fn dot_t(x: &Col<c64>, y: &Col<c64>) -> c64 {
    x.iter().zip(y.iter()).fold(c64::new(0.0, 0.0), |s, (a, b)| s + a * b)
}


/// Groups the right and left pairs (`Im λ ≥ 0`, each an eigenpair that passed its own
/// residual) by eigenvalue and pairs their vectors.
pub(super) fn pair_clusters(pencil: &Pencil, sigma: c64, right: &[(c64, Col<c64>)], left: &[(c64, Col<c64>)], extra: usize) -> Clusters {
    // Every candidate, sorted by λ's distance to σ; a cluster is a run of candidates each
    // within CLUSTER of the cluster's first.
    let mut all: Vec<(c64, bool, usize)> = right.iter().enumerate().map(|(i, p)| (p.0, false, i)).chain(left.iter().enumerate().map(|(i, p)| (p.0, true, i))).collect();
    all.sort_by(|a, b| (a.0 - sigma).norm().total_cmp(&(b.0 - sigma).norm()).then(a.0.im.total_cmp(&b.0.im)));
    let close = |a: c64, b: c64| (a - b).norm() <= cluster_radius(a, sigma);
    let mut used = vec![false; all.len()];
    let mut out = Clusters { pairs: Vec::new(), unmatched: Vec::new() };
    // The eigenspaces found: refined λ, right and left bases.
    let mut spaces: Vec<Refined> = Vec::new();
    for i in 0..all.len() {
        if used[i] {
            continue;
        }
        let head = all[i].0;
        let members: Vec<usize> = (i..all.len()).filter(|&j| !used[j] && close(head, all[j].0)).collect();
        for &j in &members {
            used[j] = true;
        }
        let rights: Vec<&Col<c64>> = members.iter().filter(|&&j| !all[j].1).map(|&j| &right[all[j].2].1).collect();
        let lefts: Vec<&Col<c64>> = members.iter().filter(|&&j| all[j].1).map(|&j| &left[all[j].2].1).collect();
        // The cluster's eigenvalue: the first right Ritz value (else the left one).
        let lambda = members.iter().find(|&&j| !all[j].1).map_or(head, |&j| all[j].0);
        // Both sides' eigenspaces by inverse subspace iteration next to λ, started from every
        // vector either run found of it and `extra` random ones (a direction of a repeated
        // eigenvalue that neither run saw).
        let starts: Vec<&Col<c64>> = rights.iter().chain(&lefts).copied().take(MAX_STARTS).collect();
        let width = members.iter().map(|&j| (all[j].0 - lambda).norm()).fold(0.0, f64::max);
        let Some(r) = refine(pencil, lambda, sigma, width, &starts, extra) else {
            out.unmatched.push(lambda);
            continue;
        };
        // Two clusters of Ritz values of one eigenvalue (far from the shift they spread
        // wider than CLUSTER: the 64-element cantilever's 16477.26 rad/s pair came out of
        // the right run as 16476.32 and 16478.21) refine to one eigenspace: united, each
        // direction once.
        // Refined eigenvalues within the cluster radius are one group: its bases united by
        // [`basis`] (a direction already in the span is a duplicate, whatever eigenvalue its
        // Ritz value said); distinct eigenvalues of a group are told apart by [`pairs_of`].
        // A tighter test by value (1e-7) let the 128-element cantilever's double pairs at
        // EA/EJ = 1e7, refined only to ~1e-6 there, through twice.
        match spaces.iter_mut().find(|g| (g.lambda - r.lambda).norm() <= cluster_radius(r.lambda, sigma)) {
            Some(g) => {
                g.right = basis(&g.right.iter().chain(&r.right).collect::<Vec<_>>(), NEW_DIRECTION);
                g.left = basis(&g.left.iter().chain(&r.left).collect::<Vec<_>>(), NEW_DIRECTION);
            }
            None => spaces.push(r),
        }
    }
    for g in spaces {
        let (mr, ml) = (g.right.len(), g.left.len());
        if mr.min(ml) == 0 {
            out.unmatched.extend(std::iter::repeat_n(g.lambda, mr.max(ml).max(1)));
            continue;
        }
        match pairs_of(pencil, g.lambda, g.right, g.left) {
            Some(p) => {
                out.unmatched.extend(std::iter::repeat_n(g.lambda, mr.max(ml) - p.len()));
                out.pairs.extend(p)
            }
            // Uᵀ E V singular: the two sides found different vectors of the eigenspace.
            None => out.unmatched.extend(std::iter::repeat_n(g.lambda, mr.max(ml))),
        }
    }
    out
}

/// The pairs of one balanced cluster: `V = Q_r Z`, `U = Q_l M⁻ᵀ Z⁻ᵀ` with `M = Q_lᵀ E Q_r`
/// and `Z` the eigenvectors of `G = −M⁻¹ Q_lᵀ K Q_r`, whose eigenvalues are the cluster's λ
/// (so `Uᵀ E V = I`, `Uᵀ K V = −diag λ`);
/// an exactly repeated eigenvalue (`G` a multiple of the identity to rounding) keeps
/// `Z = I`. `None` when `M` is singular.
fn pairs_of(pencil: &Pencil, lambda: c64, qr: Vec<Col<c64>>, ql: Vec<Col<c64>>) -> Option<Vec<(c64, Col<c64>, Col<c64>)>> {
    let (m, ml) = (qr.len(), ql.len());
    if m == 1 && ml == 1 {
        let (v, u) = (qr.into_iter().next()?, ql.into_iter().next()?);
        let ev = pencil.e.mul_complex(&v);
        if !(dot_t(&u, &ev).norm() > FACING * norm(&ev)) {
            return None;
        }
        return Some(vec![(lambda, v, u)]);
    }
    let ev: Vec<Col<c64>> = qr.iter().map(|v| pencil.e.mul_complex(v)).collect();
    let me = Mat::<c64>::from_fn(ml, m, |i, j| dot_t(&ql[i], &ev[j]));
    // A direction one side has and the other lacks faces nothing on the other side: M's
    // singular values split into those of the eigenspace (alike: the 64-element
    // cantilever's double bending modes gave equal pairs) and rounding. Only the dominant
    // singular subspaces are kept (`Q_r V_k`, `Q_l conj(U_k)`); the caller counts the rest
    // as unmatched.
    let svd = me.svd().ok()?;
    let sv: Vec<f64> = (0..m.min(ml)).map(|i| svd.S()[i].re).collect();
    let top = sv.iter().copied().fold(0.0, f64::max);
    let k = sv.iter().filter(|&&x| x > 1e-3 * top).count();
    if k == 0 {
        return None;
    }
    if k < m || k < ml {
        let (u, v) = (svd.U(), svd.V());
        let qr2: Vec<Col<c64>> = (0..k).map(|c| combination(&qr, |j| v[(j, c)])).collect();
        let ql2: Vec<Col<c64>> = (0..k).map(|c| combination(&ql, |j| u[(j, c)].conj())).collect();
        return pairs_of(pencil, lambda, qr2, ql2);
    }
    let (ev, kv): (Vec<Col<c64>>, Vec<Col<c64>>) = qr.iter().map(|v| (pencil.e.mul_complex(v), pencil.k.mul_complex(v))).unzip();
    let me = Mat::<c64>::from_fn(m, m, |i, j| dot_t(&ql[i], &ev[j]));
    let mk = Mat::<c64>::from_fn(m, m, |i, j| dot_t(&ql[i], &kv[j]));
    // M's smallest singular value against its largest: the two bases must face each other.
    let sv = me.singular_values().ok()?;
    let (big, small) = (sv.iter().copied().fold(0.0, f64::max), sv.iter().copied().fold(f64::INFINITY, f64::min));
    let scale = ev.iter().map(norm).fold(0.0, f64::max);
    if !(small > 1e-8 * big && small > FACING * scale) {
        return None;
    }
    let minv = me.partial_piv_lu().inverse();
    let g = -(&minv * &mk);
    let e = g.eigen().ok()?;
    let mu: Vec<c64> = e.S().column_vector().iter().copied().collect();
    let mean = mu.iter().fold(c64::new(0.0, 0.0), |s, x| s + x) / m as f64;
    let spread = mu.iter().map(|x| (x - mean).norm()).fold(0.0, f64::max);
    let repeated = spread <= 1e-9 * mean.norm().max(lambda.norm());
    let z = if repeated { Mat::<c64>::identity(m, m) } else { e.U().to_owned() };
    let zinv = z.partial_piv_lu().inverse();
    // U = Q_l (Z⁻¹ M⁻¹)ᵀ.
    let w = &zinv * &minv;
    let mut pairs = Vec::with_capacity(m);
    for k in 0..m {
        let v = combination(&qr, |j| z[(j, k)]);
        let u = combination(&ql, |j| w[(k, j)]);
        let l = if repeated { lambda } else { mu[k] };
        pairs.push((l, v, u));
    }
    Some(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-normal operator `T` on ℝ³: the eigenvalue θ = 10 on e₁ and a nilpotent block
    /// (θ = 0 twice, `T e₃ = 1e4 e₂`), as the constrained variables' Jordan blocks make the
    /// shift-invert operator. A block holding e₁ and w = (e₂ + e₃)/√2 after an iteration:
    /// `T w` is orthogonal to e₁ and large, so a bare threshold on the part outside e₁ kept
    /// w as a second direction of θ = 10; its Ritz pair (θ = 5e3, residual equal to θ) is no
    /// eigenpair, and only e₁ is a direction of the cluster.
    #[test]
    fn a_non_normal_transient_is_no_direction_of_the_cluster() {
        let t = |x: &Col<c64>| Col::from_fn(3, |i| match i {
            0 => x[0] * 10.0,
            1 => x[2] * 1e4,
            _ => c64::new(0.0, 0.0),
        });
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let q = vec![Col::from_fn(3, |i| c64::new(if i == 0 { 1.0 } else { 0.0 }, 0.0)), Col::from_fn(3, |i| c64::new(if i == 0 { 0.0 } else { s }, 0.0))];
        let y: Vec<Col<c64>> = q.iter().map(t).collect();
        // The bare threshold keeps both.
        assert_eq!(basis(&y.iter().collect::<Vec<_>>(), NEW_DIRECTION).len(), 2);
        let kept = ritz_directions(&q, &y).unwrap();
        assert_eq!(kept.len(), 1, "{:?}", kept.iter().map(|k| k.0).collect::<Vec<_>>());
        assert!((kept[0].0 - c64::new(10.0, 0.0)).norm() < 1e-12 && (kept[0].1[0].norm() - 1.0).abs() < 1e-12);
    }

    /// Undamped oscillators ω = 1, 2, 5, 2, 3 as the first-order pencil `λ E + K` (E = I, K
    /// blocks [[0, −1], [ω², 0]]): `λ = 2j` is double, its right eigenvectors `(1, λ)` and
    /// left ones `(λ, 1)` on the two ω = 2 blocks (closed form). The cluster is given one
    /// right vector, the first block's, off by 1e-9 elsewhere, as a single-vector Krylov
    /// run gives it; its inverse iteration (one random start) must return both pairs of the
    /// eigenspace: λ = 2j, each vector on the two ω = 2 blocks alone with the closed form's
    /// ratio, the two independent, `Uᵀ E V = I`.
    #[test]
    fn a_double_eigenvalue_gets_both_pairs_from_one_vector() {
        let omegas = [1.0, 2.0, 5.0, 2.0, 3.0];
        let n = 2 * omegas.len();
        let pencil = crate::eigen::krylov::pencil::oscillators(&omegas);
        let lambda = c64::new(0.0, 2.0);
        let start = Col::<c64>::from_fn(n, |i| match i {
            2 => c64::new(1.0, 0.0),
            3 => lambda,
            _ => c64::new(1e-9 * (i as f64 + 1.0), 0.0),
        });
        let out = pair_clusters(&pencil, c64::new(0.0, 0.0), &[(lambda * (1.0 + 1e-12), start)], &[], 1);
        assert!(out.unmatched.is_empty(), "{:?}", out.unmatched);
        assert_eq!(out.pairs.len(), 2);
        let blocks = [1usize, 3];
        for (l, v, u) in &out.pairs {
            assert!((l - lambda).norm() <= 1e-13 * 2.0, "λ = {l}");
            let (nv, nu) = (norm(v), norm(u));
            for i in (0..omegas.len()).filter(|i| !blocks.contains(i)) {
                assert!(v[2 * i].norm().max(v[2 * i + 1].norm()) <= 1e-13 * nv && u[2 * i].norm().max(u[2 * i + 1].norm()) <= 1e-13 * nu, "oscillator {i}");
            }
            for &b in &blocks {
                assert!((v[2 * b + 1] - lambda * v[2 * b]).norm() <= 1e-13 * nv, "right, block {b}");
                assert!((u[2 * b] - lambda * u[2 * b + 1]).norm() <= 1e-13 * nu, "left, block {b}");
            }
        }
        // Independent: the two right vectors' coefficients on the blocks' (1, λ).
        let (va, vb) = (&out.pairs[0].1, &out.pairs[1].1);
        let det = va[2] * vb[6] - va[6] * vb[2];
        assert!(det.norm() >= 1e-3 * norm(va) * norm(vb), "det {det}");
        for (i, p) in out.pairs.iter().enumerate() {
            for (j, q) in out.pairs.iter().enumerate() {
                let d = dot_t(&p.2, &q.1);
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((d - c64::new(want, 0.0)).norm() <= 1e-12, "u{i}ᵀ E v{j} = {d}");
            }
        }
    }

    /// A vector in the span of two others repeats them; one with a part of order 1 outside
    /// does not (the test that unites two clusters' eigenspaces and drops a band's duplicate).
    #[test]
    fn a_vector_in_the_span_is_a_duplicate() {
        let e = |k: usize| Col::from_fn(4, |i| c64::new(if i == k { 1.0 } else { 0.0 }, 0.0));
        let (a, b) = (e(0), Col::from_fn(4, |i| c64::new([1.0, 1.0, 0.0, 0.0][i], 0.0)));
        let inside = Col::from_fn(4, |i| c64::new([3.0, -2.0, 0.0, 0.0][i], 0.0));
        assert!(outside_span(&inside, [&a, &b].into_iter()) < 1e-15);
        let outside = Col::from_fn(4, |i| c64::new([3.0, -2.0, 1.0, 0.0][i], 0.0));
        assert!((outside_span(&outside, [&a, &b].into_iter()) - 1.0 / 14f64.sqrt()).abs() < 1e-15);
    }
}
