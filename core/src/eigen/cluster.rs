//! Labels of (nearly) degenerate modes (issue 11, point 5).
//!
//! Identical substructures (HAM-SAS's four little pendulums, its four IP legs) give clusters
//! of modes whose eigenvalues agree to rounding. Inside a cluster the eigenvectors are an
//! arbitrary basis of the invariant subspace: one mode's kinetic-energy shares, and a label
//! naming one pendulum, depend on rounding. What does not depend on the basis is the
//! subspace itself; the shares of a cluster are the diagonal of the orthogonal projector
//! onto its mass-weighted velocity subspace, divided by its dimension: with
//! `W = [√m_j v_{q,j}]` (one column per member, rows the dynamic node components of
//! [`ModalEnergy`]) and `Q` an orthonormal basis of `range W`, the share of component `j` is
//! `Σ_q |Q_jq|² / rank W`. They sum to 1, are the same for any basis `W X` (`X`
//! invertible) and, for one mode, are [`ModalEnergy::shares`]: `m_j |v_j|² / Σ m_i |v_i|²`.

use super::energy::{motion_words, EnergyShare, ModalEnergy};
use super::Mode;
use faer::c64;

/// Two eigenvalues closer than this relative to their modulus belong to one cluster. The
/// vectors of modes a gap `δ` apart rotate into each other by about `ε/δ` for a rounding
/// perturbation `ε` of the eigenvalues; a change of the Hessenberg blocking moved HAM-SAS's
/// eigenvalues by about 1e-11 relative, so modes at least 1e-8 apart rotate by at most about
/// 1e-3, below the labels' 1 % resolution, while modes nearer keep no individual meaning.
pub const CLUSTER_RELATIVE_GAP: f64 = 1e-8;

/// Groups of two or more modes (indices into `modes`, ascending) whose eigenvalues agree
/// to within [`CLUSTER_RELATIVE_GAP`] (chained: each member is that near another member).
/// Only finite, nonzero eigenvalues with a right vector; complex-conjugate partners are
/// `2 |Im λ|` apart and so never in one cluster.
pub fn degenerate_clusters(modes: &[Mode]) -> Vec<Vec<usize>> {
    let eligible = |m: &Mode| m.right.is_some() && m.lambda.re.is_finite() && m.lambda.im.is_finite() && m.lambda.norm() > 0.0;
    let mut root: Vec<usize> = (0..modes.len()).collect();
    fn find(root: &mut [usize], mut i: usize) -> usize {
        while root[i] != i {
            root[i] = root[root[i]];
            i = root[i];
        }
        i
    }
    for i in 0..modes.len() {
        if !eligible(&modes[i]) {
            continue;
        }
        for j in i + 1..modes.len() {
            let (a, b) = (modes[i].lambda, modes[j].lambda);
            if eligible(&modes[j]) && (a - b).norm() <= CLUSTER_RELATIVE_GAP * a.norm().max(b.norm()) {
                let (ri, rj) = (find(&mut root, i), find(&mut root, j));
                root[ri.max(rj)] = ri.min(rj);
            }
        }
    }
    let mut groups: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for i in 0..modes.len() {
        let r = find(&mut root, i);
        groups.entry(r).or_default().push(i);
    }
    groups.into_values().filter(|g| g.len() > 1).collect()
}

impl ModalEnergy {
    /// Kinetic-energy shares of the subspace the modes span (module doc), largest first;
    /// empty without vectors or mass.
    pub fn subspace_shares(&self, modes: &[&Mode]) -> Vec<EnergyShare> {
        let mut basis: Vec<Vec<c64>> = Vec::new();
        for mode in modes {
            let Some(v) = &mode.right else { continue };
            let mut w: Vec<c64> = self.terms.iter().map(|&(_, _, j, mass)| v[j] * mass.sqrt()).collect();
            let norm0 = norm(&w);
            if norm0 <= 0.0 {
                continue;
            }
            // Modified Gram–Schmidt, twice (enough for orthogonality to rounding).
            for _ in 0..2 {
                for q in &basis {
                    let dot: c64 = q.iter().zip(&w).map(|(a, b)| a.conj() * b).sum();
                    w.iter_mut().zip(q).for_each(|(b, a)| *b -= dot * a);
                }
            }
            let n = norm(&w);
            if n > 1e-8 * norm0 {
                basis.push(w.iter().map(|x| x / n).collect());
            }
        }
        if basis.is_empty() {
            return Vec::new();
        }
        let rank = basis.len() as f64;
        let mut out: Vec<EnergyShare> = self
            .terms
            .iter()
            .enumerate()
            .map(|(t, &(node, component, _, _))| EnergyShare::of_node(node, component, basis.iter().map(|q| q[t].norm_sqr()).sum::<f64>() / rank))
            .collect();
        out.retain(|s| s.share > 0.0);
        out.sort_by(|a, b| b.share.total_cmp(&a.share));
        out
    }
}

fn norm(w: &[c64]) -> f64 {
    w.iter().map(|x| x.norm_sqr()).sum::<f64>().sqrt()
}

/// The label of one mode of a cluster of `count` modes at `freq_hz` [Hz] from the cluster's
/// [`ModalEnergy::subspace_shares`]: the largest component and every node whose share of
/// that same component is at least half the largest, named together ("little pendulums"
/// for "little pendulum +x", "… -y": the names' common words plus "s"; else the names
/// listed), with their summed share: "little pendulums yaw (rz) 88 %, 1 of 4 modes at
/// 15.91 Hz". `None` without shares.
pub fn cluster_label(shares: &[EnergyShare], names: &std::collections::BTreeMap<u32, String>, gravity: &crate::kinematics::Vec3, count: usize, freq_hz: f64) -> Option<String> {
    let top = shares.iter().max_by(|a, b| a.share.total_cmp(&b.share))?;
    let group: Vec<&EnergyShare> = shares.iter().filter(|s| s.component == top.component && s.share >= 0.5 * top.share).collect();
    let name = |n: u32| names.get(&n).cloned().unwrap_or_else(|| format!("node {n}"));
    let listed: Vec<String> = group.iter().map(|s| name(s.node)).collect();
    let who = if listed.len() == 1 { listed[0].clone() } else { common_words(&group.iter().map(|s| names.get(&s.node)).collect::<Vec<_>>()).map_or_else(|| listed.join(", "), plural) };
    let share: f64 = group.iter().map(|s| s.share).sum();
    Some(format!("{who} {}, 1 of {count} modes at {} Hz", motion_words(top.component, share, gravity)?, significant(freq_hz, 4)))
}

/// The whole words every name starts with ("little pendulum" of "little pendulum +x" and
/// "little pendulum -y"); `None` if a node has no name or the names share no word.
fn common_words(names: &[Option<&String>]) -> Option<String> {
    let names: Vec<&String> = names.iter().copied().collect::<Option<_>>()?;
    let first: Vec<&str> = names.first()?.split_whitespace().collect();
    let n = (0..first.len()).take_while(|&k| names.iter().all(|s| s.split_whitespace().nth(k) == Some(first[k]))).count();
    let n = n.min(first.len().saturating_sub(1).max(1));
    (n > 0 && names.iter().all(|s| s.split_whitespace().count() > n)).then(|| first[..n].join(" "))
}

/// "little pendulums", "masses".
fn plural(word: String) -> String {
    if ["s", "x", "sh", "ch"].iter().any(|e| word.ends_with(e)) {
        format!("{word}es")
    } else {
        format!("{word}s")
    }
}

/// `x` with `digits` significant digits ("15.91", "0.004957").
fn significant(x: f64, digits: i32) -> String {
    if !(x.is_finite() && x > 0.0) {
        return format!("{x}");
    }
    let decimals = (digits - 1 - x.log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    //! Closed form: four identical masses `m` on identical springs `k` along x (gravity
    //! along −z) and a fifth on a spring `k5`. `M = m I`, `K = diag(k, k, k, k, k5)`: the
    //! eigenvalues are `±i √(k/m)`, four-fold, and `±i √(k5/m)`; the first cluster's
    //! invariant subspace is span{e₁…e₄}, so its shares are exactly 1/4 per mass whatever
    //! basis of it the eigensolver returns.
    use super::*;
    use crate::eigen::mode_label;
    use crate::kinematics::Vec3;
    use crate::eigen::{Classification, ModeKind};
    use faer::Col;

    const M: f64 = 2.0;
    const K: f64 = 800.0;
    const K5: f64 = 1800.0;

    fn mode(lambda: c64, v: Vec<c64>) -> Mode {
        let classification = Classification { kind: ModeKind::Dynamic, alpha: lambda, beta: 1.0, to_zero: 1.0, to_infinity: 1.0, uncertainty: 0.0 };
        Mode { lambda, kind: ModeKind::Dynamic, error: 0.0, classification, right: Some(Col::from_fn(v.len(), |i| v[i])), left: None, partner: None }
    }

    /// The four cluster vectors `E Q` (columns of `q`, 4 x 4) at ±iω, then the fifth mass.
    fn modes(q: &[[c64; 4]; 4], lambda: c64) -> Vec<Mode> {
        let mut out = Vec::new();
        for sign in [1.0, -1.0] {
            for c in 0..4 {
                let v: Vec<c64> = (0..5).map(|r| if r < 4 { if sign > 0.0 { q[r][c] } else { q[r][c].conj() } } else { c64::new(0.0, 0.0) }).collect();
                out.push(mode(if sign > 0.0 { lambda } else { lambda.conj() }, v));
            }
        }
        let w5 = (K5 / M).sqrt();
        let e5: Vec<c64> = (0..5).map(|r| c64::new(if r == 4 { 1.0 } else { 0.0 }, 0.0)).collect();
        out.push(mode(c64::new(0.0, w5), e5.clone()));
        out.push(mode(c64::new(0.0, -w5), e5));
        out
    }

    fn energy() -> ModalEnergy {
        ModalEnergy { terms: (0..5).map(|n| (n as u32 + 1, "x", n, M)).collect(), ..Default::default() }
    }

    fn names() -> std::collections::BTreeMap<u32, String> {
        (1..=5).map(|n| (n, format!("mass {n}"))).collect()
    }

    fn labels(modes: &[Mode]) -> Vec<String> {
        let e = energy();
        let gravity = Vec3::new(0.0, 0.0, -9.81);
        let mut out: Vec<String> = modes.iter().map(|m| mode_label(&e.shares(m), &names(), &gravity).unwrap()).collect();
        for c in degenerate_clusters(modes) {
            let shares = e.subspace_shares(&c.iter().map(|&i| &modes[i]).collect::<Vec<_>>());
            for &i in &c {
                out[i] = cluster_label(&shares, &names(), &gravity, c.len(), modes[i].freq_hz()).unwrap();
            }
        }
        out
    }

    /// A unitary 4 x 4 matrix from Gram–Schmidt on fixed pseudo-random complex entries
    /// (a linear congruential sequence), its columns also scaled by 0.3…1.2 (any basis).
    fn rotation(seed: u64, scaled: bool) -> [[c64; 4]; 4] {
        let mut x = seed;
        let mut next = || {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut cols: Vec<Vec<c64>> = (0..4).map(|_| (0..4).map(|_| c64::new(next(), next())).collect()).collect();
        for c in 0..4 {
            for p in 0..c {
                let dot: c64 = (0..4).map(|r| cols[p][r].conj() * cols[c][r]).sum();
                for r in 0..4 {
                    let sub = dot * cols[p][r];
                    cols[c][r] -= sub;
                }
            }
            let n = norm(&cols[c]);
            let scale = if scaled { 0.3 + 0.3 * c as f64 } else { 1.0 };
            cols[c].iter_mut().for_each(|z| *z *= scale / n);
        }
        std::array::from_fn(|r| std::array::from_fn(|c| cols[c][r]))
    }

    #[test]
    fn a_fourfold_cluster_is_labelled_alike_in_any_basis() {
        let omega = (K / M).sqrt();
        let lambda = c64::new(0.0, omega);
        let identity: [[c64; 4]; 4] = std::array::from_fn(|r| std::array::from_fn(|c| c64::new(if r == c { 1.0 } else { 0.0 }, 0.0)));
        let plain = modes(&identity, lambda);
        assert_eq!(degenerate_clusters(&plain), vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]]);
        // Closed form: f = √(k/m)/2π = 3.183 Hz; 1/4 of the energy per mass, 100 % together.
        let expected = "masses horizontal (x) 100 %, 1 of 4 modes at 3.183 Hz";
        let reference = labels(&plain);
        assert!(reference[..8].iter().all(|l| l == expected), "{reference:?}");
        let shares = energy().subspace_shares(&plain[..4].iter().collect::<Vec<_>>());
        assert_eq!(shares.len(), 4);
        assert!(shares.iter().all(|s| (s.share - 0.25).abs() < 1e-14), "{shares:?}");
        // The non-degenerate mode keeps its own label.
        assert_eq!(reference[8], "mass 5 horizontal (x) 100 %");
        for (seed, scaled) in [(1, false), (7, true), (42, false)] {
            let q = rotation(seed, scaled);
            let rotated = modes(&q, lambda);
            // One rotated vector alone would name one mass with an arbitrary share.
            let alone = mode_label(&energy().shares(&rotated[0]), &names(), &Vec3::new(0.0, 0.0, -9.81)).unwrap();
            assert!(!alone.ends_with("100 %"), "{alone}");
            assert_eq!(labels(&rotated), reference, "seed {seed}");
            let shares = energy().subspace_shares(&rotated[..4].iter().collect::<Vec<_>>());
            assert!(shares.iter().all(|s| (s.share - 0.25).abs() < 1e-12), "{shares:?}");
            // A split of the cluster by rounding (1e-12 relative) changes nothing.
            let mut split = rotated.clone();
            split.iter_mut().take(8).enumerate().for_each(|(i, m)| m.lambda *= 1.0 + 1e-12 * i as f64);
            assert_eq!(labels(&split), reference, "seed {seed}");
        }
    }
}
