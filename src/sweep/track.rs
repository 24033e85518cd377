//! Modes followed across design points: each of the lowest modes of the first point is
//! matched at every other point to one of that point's candidate modes by the modal
//! assurance criterion (MAC) of its shape with the mode's shape at the nearest earlier
//! point, frequency continuity breaking ties, by an optimal assignment (Hungarian
//! algorithm on `1 − MAC + w·Δλ`). A mode that changed its place in the frequency order
//! has crossed another (flagged `crossing`); a best match with a low MAC is a veering (two
//! modes exchanging shapes) or points too far apart (flagged `ambiguous`).

use faer::c64;

/// Largest number of components of a stored mode shape: a larger shape is folded into this
/// many (a count sketch, [`sketch`]) so a sweep of a large model keeps points x modes x
/// components within memory (100 points of 15 candidate modes: 74 MB at most).
pub const MAX_SHAPE: usize = 1024;

/// A MAC at or above this is a confident match: the mode kept its shape.
pub const CONFIDENT_MAC: f64 = 0.8;

/// Weight of the relative eigenvalue distance `|λ₁ − λ₂| / max(|λ₁|, |λ₂|)` (at most 1) in the
/// assignment's cost `1 − MAC + w·distance`: it decides between candidates of equal MAC
/// (a degenerate pair at a crossing) and never outweighs a clear difference of shapes.
pub const FREQUENCY_WEIGHT: f64 = 0.1;

/// One mode (a complex pair or a ±a real pair counts once) of a design point, as the
/// tracking and the consistent ROM basis need it.
#[derive(Clone, Debug, PartialEq)]
pub struct PointMode {
    /// The eigenvalue of the unit's first member (`Im λ ≥ 0`, or `+a` of a `±a` pair) [rad/s].
    pub lambda: c64,
    /// The modal table's label ("node 2 x 100 %").
    pub label: String,
    /// 1-based modal-table indices of the unit's members, the first the one `lambda` is.
    pub members: Vec<usize>,
    /// Each member's right vector restricted to the model's motion unknowns (structural
    /// nodes' positions and rotations, scalar nodes, element coordinates and states), in the
    /// eigensolver's scaling (unit norm over all unknowns, largest entry real positive);
    /// folded to [`MAX_SHAPE`] components when longer. Empty without a vector.
    pub shapes: Vec<Vec<c64>>,
    /// The first member's adjoint vector restricted to the equations of the same unknowns.
    pub adjoint: Vec<c64>,
}

/// Folds a long vector into [`MAX_SHAPE`] components: component `i` adds, with a sign, to
/// bucket `h(i) mod MAX_SHAPE` (a count sketch with a fixed hash: the same fold at every
/// design point, so inner products, hence MACs, are kept to about `1/√MAX_SHAPE` of the
/// norms). Shorter vectors are returned as they are.
pub fn sketch(v: Vec<c64>) -> Vec<c64> {
    if v.len() <= MAX_SHAPE {
        return v;
    }
    let mut out = vec![c64::new(0.0, 0.0); MAX_SHAPE];
    for (i, x) in v.into_iter().enumerate() {
        // SplitMix64 of the index: bucket from the high bits, sign from the lowest.
        let mut z = (i as u64).wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        let bucket = ((z >> 1) % MAX_SHAPE as u64) as usize;
        out[bucket] += if z & 1 == 0 { x } else { -x };
    }
    out
}

/// The modal assurance criterion of two complex vectors, `|aᴴ b|² / ((aᴴ a)(bᴴ b))`: 1 for
/// the same shape (whatever complex factor scales either), 0 for orthogonal shapes, 0 when
/// either is empty or zero or their lengths differ.
pub fn mac(a: &[c64], b: &[c64]) -> f64 {
    if a.len() != b.len() || a.is_empty() {
        return 0.0;
    }
    let ab: c64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let (aa, bb): (f64, f64) = (a.iter().map(|x| x.norm_sqr()).sum(), b.iter().map(|x| x.norm_sqr()).sum());
    if aa > 0.0 && bb > 0.0 { (ab.norm_sqr() / (aa * bb)).min(1.0) } else { 0.0 }
}

/// The MAC of two modes: of their right vectors, and where both have adjoint vectors the
/// geometric mean with the adjoints' (a non-symmetric model's left vectors tell apart
/// modes whose right vectors look alike).
pub fn mode_mac(a: &PointMode, b: &PointMode) -> f64 {
    let right = match (a.shapes.first(), b.shapes.first()) {
        (Some(x), Some(y)) => mac(x, y),
        _ => 0.0,
    };
    if a.adjoint.is_empty() || b.adjoint.is_empty() { right } else { (right * mac(&a.adjoint, &b.adjoint)).sqrt() }
}

/// Relative distance of two eigenvalues, at most 1.
fn eigenvalue_distance(a: c64, b: c64) -> f64 {
    let scale = a.norm().max(b.norm());
    if scale > 0.0 { ((a - b).norm() / scale).min(1.0) } else { 0.0 }
}

/// Minimum-cost assignment of `n` rows to distinct columns of an `n x m` cost matrix
/// (`n ≤ m`, row-major): the column of each row. Kuhn–Munkres with potentials, O(n² m).
pub fn assign(cost: &[f64], n: usize, m: usize) -> Vec<usize> {
    assert!(n <= m && cost.len() == n * m);
    // 1-based rows and columns; column 0 is the virtual start.
    let (mut u, mut v) = (vec![0.0; n + 1], vec![0.0; m + 1]);
    let (mut row_of, mut way) = (vec![0usize; m + 1], vec![0usize; m + 1]);
    for i in 1..=n {
        row_of[0] = i;
        let mut j0 = 0;
        let mut min = vec![f64::INFINITY; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = row_of[j0];
            let (mut delta, mut j1) = (f64::INFINITY, 0);
            for j in 1..=m {
                if !used[j] {
                    let c = cost[(i0 - 1) * m + (j - 1)] - u[i0] - v[j];
                    if c < min[j] {
                        min[j] = c;
                        way[j] = j0;
                    }
                    if min[j] < delta {
                        delta = min[j];
                        j1 = j;
                    }
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[row_of[j]] += delta;
                    v[j] -= delta;
                } else {
                    min[j] -= delta;
                }
            }
            j0 = j1;
            if row_of[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            row_of[j0] = row_of[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut col = vec![0; n];
    for j in 1..=m {
        if row_of[j] > 0 {
            col[row_of[j] - 1] = j - 1;
        }
    }
    col
}

/// What tracking says of one mode at one design point.
#[derive(Clone, Debug, PartialEq)]
pub struct Match {
    /// Index into the point's candidate modes.
    pub candidate: usize,
    /// MAC with the mode's shape at the point it was matched against (1 at the first point).
    pub mac: f64,
    /// It changed places in the frequency order with another tracked mode since that point.
    pub crossing: bool,
}

impl Match {
    /// A best match below [`CONFIDENT_MAC`]: a veering or points too far apart.
    pub fn ambiguous(&self) -> bool {
        self.mac < CONFIDENT_MAC
    }
}

/// The tracked modes of a sweep.
#[derive(Clone, Debug, Default)]
pub struct Tracking {
    /// Each tracked mode's label at the first design point that succeeded.
    pub labels: Vec<String>,
    /// Per design point (`None` where it failed), per tracked mode, its match (`None`
    /// when the point had fewer candidates than modes tracked).
    pub matches: Vec<Option<Vec<Option<Match>>>>,
    /// Per design point, the earlier point it was matched against (nearest in the
    /// parameters scaled by their ranges).
    pub neighbour: Vec<Option<usize>>,
    /// Per tracked mode, the component of its shape that the consistent basis makes real
    /// positive at every point (the largest at the first point).
    pub reference: Vec<usize>,
}

/// The nearest earlier point with modes, by the distance of the parameters each scaled by
/// its range over the sweep (the latest of equally near ones).
fn nearest_earlier(points: &[Vec<f64>], done: &[usize], p: usize) -> Option<usize> {
    let dims = points.first().map_or(0, |v| v.len());
    let range: Vec<f64> = (0..dims)
        .map(|j| {
            let (lo, hi) = points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v[j]), b.max(v[j])));
            if hi > lo { hi - lo } else { 1.0 }
        })
        .collect();
    let distance = |q: usize| (0..dims).map(|j| ((points[p][j] - points[q][j]) / range[j]).powi(2)).sum::<f64>();
    done.iter().copied().min_by(|&a, &b| distance(a).total_cmp(&distance(b)).then(b.cmp(&a)))
}

/// Follows the lowest `count` modes of the first point that has modes through every point of
/// `modes` (`None`: a failed point), `points` their parameter values.
pub fn track(points: &[Vec<f64>], modes: &[Option<&[PointMode]>], count: usize) -> Tracking {
    let k = modes.len();
    let mut t = Tracking { matches: vec![None; k], neighbour: vec![None; k], ..Tracking::default() };
    let Some(first) = (0..k).find(|&p| modes[p].is_some_and(|m| !m.is_empty())) else { return t };
    let start = modes[first].unwrap_or_default();
    let n = count.min(start.len());
    t.labels = start[..n].iter().map(|m| m.label.clone()).collect();
    t.reference = start[..n].iter().map(|m| m.shapes.first().map_or(0, |s| largest(s))).collect();
    t.matches[first] = Some((0..n).map(|c| Some(Match { candidate: c, mac: 1.0, crossing: false })).collect());
    // Each mode's last confident shape: (point, candidate) where its MAC was high.
    let mut confident: Vec<Vec<Option<(usize, usize)>>> = vec![vec![None; n]; k];
    confident[first] = (0..n).map(|c| Some((first, c))).collect();
    let mut done = vec![first];
    for p in first + 1..k {
        let Some(here) = modes[p].filter(|m| !m.is_empty()) else { continue };
        let Some(q) = nearest_earlier(points, &done, p) else { continue };
        t.neighbour[p] = Some(q);
        let previous = t.matches[q].clone().unwrap_or_default();
        let m = here.len().max(n);
        // Rows: tracked modes; columns: this point's candidates, then absent slots.
        let mut cost = vec![2.0 + FREQUENCY_WEIGHT; n * m];
        let reference = |j: usize| confident[q][j].and_then(|(r, c)| modes[r].and_then(|list| list.get(c)));
        for j in 0..n {
            let Some(old) = reference(j) else { continue };
            let lambda = previous[j].as_ref().and_then(|mt| modes[q].and_then(|l| l.get(mt.candidate))).map_or(old.lambda, |x| x.lambda);
            for (c, new) in here.iter().enumerate() {
                cost[j * m + c] = 1.0 - mode_mac(old, new) + FREQUENCY_WEIGHT * eigenvalue_distance(lambda, new.lambda);
            }
        }
        let columns = assign(&cost, n, m);
        let mut row: Vec<Option<Match>> = columns
            .iter()
            .enumerate()
            .map(|(j, &c)| (c < here.len()).then(|| Match { candidate: c, mac: reference(j).map_or(0.0, |old| mode_mac(old, &here[c])), crossing: false }))
            .collect();
        // A crossing: two modes whose order in frequency differs from the neighbour's.
        for a in 0..n {
            for b in a + 1..n {
                let order = |list: &[Option<Match>], modes: &[PointMode], x: usize| list[x].as_ref().map(|mt| modes[mt.candidate].lambda.norm());
                let (qa, qb) = (order(&previous, modes[q].unwrap_or_default(), a), order(&previous, modes[q].unwrap_or_default(), b));
                let (pa, pb) = (order(&row, here, a), order(&row, here, b));
                if let (Some(qa), Some(qb), Some(pa), Some(pb)) = (qa, qb, pa, pb)
                    && (qa < qb) != (pa < pb)
                    && qa != qb
                    && pa != pb
                {
                    for x in [a, b] {
                        if let Some(mt) = row[x].as_mut() {
                            mt.crossing = true;
                        }
                    }
                }
            }
        }
        confident[p] = (0..n).map(|j| match &row[j] {
            Some(mt) if !mt.ambiguous() => Some((p, mt.candidate)),
            _ => confident[q][j],
        }).collect();
        t.matches[p] = Some(row);
        done.push(p);
    }
    t
}

/// Index of the entry of largest modulus (the first of equal ones).
pub fn largest(v: &[c64]) -> usize {
    v.iter().enumerate().fold((0, -1.0), |(bi, bm), (i, x)| if x.norm() > bm { (i, x.norm()) } else { (bi, bm) }).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn assignment_is_the_minimum_over_all_permutations() {
        // 3 x 4 costs; brute force over the 24 injective maps.
        let cost = [4.0, 1.0, 3.0, 9.0, 2.0, 0.0, 5.0, 1.0, 3.0, 2.0, 2.0, 7.0];
        let got = assign(&cost, 3, 4);
        let total = |c: &[usize]| c.iter().enumerate().map(|(i, &j)| cost[i * 4 + j]).sum::<f64>();
        let mut best = f64::INFINITY;
        for a in 0..4 {
            for b in (0..4).filter(|&b| b != a) {
                for c in (0..4).filter(|&c| c != a && c != b) {
                    best = best.min(total(&[a, b, c]));
                }
            }
        }
        assert_eq!(total(&got), best);
        assert_eq!(got.len(), 3);
    }

    #[test]
    fn mac_ignores_complex_scaling_and_sees_orthogonality() {
        let a = vec![c64::new(1.0, 0.0), c64::new(0.0, 2.0)];
        let b: Vec<c64> = a.iter().map(|x| x * c64::new(-0.3, 0.7)).collect();
        assert!((mac(&a, &b) - 1.0).abs() < 1e-15);
        let c = vec![c64::new(0.0, 2.0), c64::new(1.0, 0.0)];
        // aᴴ c = 1·(2j) + (−2j)·1 = 0.
        assert_eq!(mac(&a, &c), 0.0);
        assert_eq!(mac(&a, &a[..1]), 0.0);
    }

    #[test]
    fn a_sketch_keeps_inner_products_to_about_one_over_root_its_size() {
        // Two vectors of 20000 entries, the second the first plus as much of another.
        let n = 20000;
        let a: Vec<c64> = (0..n).map(|i| c64::new(((i * 7919) % 101) as f64 - 50.0, 0.0)).collect();
        let noise: Vec<c64> = (0..n).map(|i| c64::new(0.0, ((i * 104729) % 97) as f64 - 48.0)).collect();
        let scale = (a.iter().map(|x| x.norm_sqr()).sum::<f64>() / noise.iter().map(|x| x.norm_sqr()).sum::<f64>()).sqrt();
        let b: Vec<c64> = a.iter().zip(&noise).map(|(x, y)| x + y * scale).collect();
        let exact = mac(&a, &b);
        let folded = mac(&sketch(a), &sketch(b));
        // 1/√1024 = 0.03; three times that.
        assert!((exact - folded).abs() < 0.1, "exact {exact}, folded {folded}");
        assert!(exact > 0.2 && exact < 0.8, "{exact}");
    }
}
