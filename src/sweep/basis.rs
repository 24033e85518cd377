//! A design point's ROM in the sweep's consistent modal basis: states in the order of the
//! tracked modes ([`super::track`]) and every mode's shape scaled by the same phase
//! convention at every point, so that `A[:,:,k]`, `B[:,:,k]`, `C[:,:,k]` vary smoothly with
//! the parameters and can be interpolated.
//!
//! A complex pair's states are `[Re q, Im q]` of the modal coordinate of `v` (the ROM's
//! `V = [Re v, Im v]`, eq. 42). The eigensolver makes `v`'s largest entry real positive,
//! and which entry is largest can change from one point to the next; here each tracked mode
//! instead has its reference component (the largest of its shape at the first point) made
//! real positive at every point: `v' = v e^{−jφ}` with `φ = arg v_ref` turns the pair's
//! states by `[[cos φ, sin φ], [−sin φ, cos φ]]` (`V' = V Tᵀ`, and `W' = W Tᵀ` for the
//! adjoint `u' = u e^{jφ}`); a real mode's state changes sign when `v_ref < 0`. The
//! transformation `T` is orthogonal: `E' = T E Tᵀ`, `A' = T A Tᵀ`, `B' = T B`, `C' = C Tᵀ`,
//! `D' = D`, the transfer function unchanged.

use faer::Mat;

use crate::output::rom_file::RomExport;

use super::track::{Match, PointMode};

/// A ROM in the consistent basis, with the tracked mode (1-based) of each state (0: a state
/// of a mode not tracked, or a static state).
#[derive(Clone, Debug)]
pub struct ConsistentRom {
    pub rom: RomExport,
    pub state_tracks: Vec<usize>,
}

/// The ROM of a point whose tracked modes are `matches` (candidates in `modes`),
/// `reference` the component of each tracked mode's shape made real positive.
pub fn consistent_rom(rom: &RomExport, modes: &[PointMode], matches: &[Option<Match>], reference: &[usize]) -> ConsistentRom {
    let ns = rom.a.nrows();
    let mut t = Mat::<f64>::zeros(ns, ns);
    let mut order: Vec<usize> = Vec::with_capacity(ns);
    let mut state_tracks = Vec::with_capacity(ns);
    let mut names = Vec::with_capacity(ns);
    for (j, m) in matches.iter().enumerate() {
        let Some(mode) = m.as_ref().map(|m| &modes[m.candidate]) else { continue };
        for (k, &member) in mode.members.iter().enumerate() {
            let states: Vec<usize> = (0..ns).filter(|&s| rom.state_modes[s] == member && !order.contains(&s)).collect();
            let value = mode.shapes.get(k).and_then(|v| v.get(reference[j]).copied()).unwrap_or_default();
            let size = mode.shapes.get(k).map_or(0.0, |v| v.iter().map(|x| x.norm()).fold(0.0, f64::max));
            let phase = if value.norm() > 1e-12 * size { value.arg() } else { 0.0 };
            let r = order.len();
            match states[..] {
                [re, im] => {
                    let (s, c) = phase.sin_cos();
                    t[(r, re)] = c;
                    t[(r, im)] = s;
                    t[(r + 1, re)] = -s;
                    t[(r + 1, im)] = c;
                    names.extend([format!("mode {} re", j + 1), format!("mode {} im", j + 1)]);
                }
                // A real mode: φ is 0 or π (a negative reference entry).
                [one] => {
                    t[(r, one)] = if phase.cos() < 0.0 { -1.0 } else { 1.0 };
                    names.push(if mode.members.len() > 1 { format!("mode {} member {}", j + 1, k + 1) } else { format!("mode {}", j + 1) });
                }
                _ => continue,
            }
            order.extend(&states);
            state_tracks.extend(std::iter::repeat_n(j + 1, states.len()));
        }
    }
    // The other states (modes not tracked, static states) follow, as they were.
    for s in 0..ns {
        if !order.contains(&s) {
            t[(order.len(), s)] = 1.0;
            order.push(s);
            state_tracks.push(0);
            names.push(rom.states[s].clone());
        }
    }
    let tt = t.transpose().to_owned();
    let pick = |v: &[String]| order.iter().map(|&s| v[s].clone()).collect::<Vec<_>>();
    let out = RomExport {
        e: &t * &rom.e * &tt,
        a: &t * &rom.a * &tt,
        b: &t * &rom.b,
        c: &rom.c * &tt,
        states: names,
        state_units: pick(&rom.state_units),
        state_modes: order.iter().map(|&s| rom.state_modes[s]).collect(),
        state_freq_hz: order.iter().map(|&s| rom.state_freq_hz[s]).collect(),
        ..rom.clone()
    };
    ConsistentRom { rom: out, state_tracks }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::c64;

    /// A pair's states turned by the phase of its reference entry: `V Tᵀ` must be
    /// `[Re v', Im v']` with `v' = v e^{−jφ}`, whose reference entry is real positive.
    #[test]
    fn the_pair_rotation_makes_the_reference_entry_real_positive() {
        let v = [c64::new(0.3, -0.4), c64::new(-0.2, 0.9)];
        let mode = PointMode { lambda: c64::new(-0.1, 5.0), label: String::new(), members: vec![1, 2], shapes: vec![v.to_vec()], adjoint: Vec::new() };
        // A ROM of one pair whose C is V itself (outputs = the two components).
        let rom = RomExport {
            kind: "ordinary",
            e: Mat::identity(2, 2),
            a: Mat::from_fn(2, 2, |i, j| [[-0.1, 5.0], [-5.0, -0.1]][i][j]),
            b: Mat::from_fn(2, 1, |i, _| [1.0, 2.0][i]),
            c: Mat::from_fn(2, 2, |i, j| if j == 0 { v[i].re } else { v[i].im }),
            d: Mat::zeros(2, 1),
            eigenvalues: Vec::new(),
            full_eigenvalues: Vec::new(),
            inputs: vec!["u".into()],
            outputs: vec!["y1".into(), "y2".into()],
            states: vec!["mode 1 re".into(), "mode 1 im".into()],
            input_units: vec![String::new()],
            output_units: vec![String::new(); 2],
            state_units: vec![String::new(); 2],
            state_modes: vec![1, 1],
            state_freq_hz: vec![0.8; 2],
            reference_time: None,
            dcoef: 1e-3,
            full_static_gain: None,
            rom_static_gain: None,
            sample_time: None,
            discretization: "continuous".into(),
            hankel_singular_values: Vec::new(),
            error_bound: None,
        };
        let out = consistent_rom(&rom, &[mode], &[Some(Match { candidate: 0, mac: 1.0, crossing: false })], &[1]);
        let phase = v[1].arg();
        let rotated: Vec<c64> = v.iter().map(|x| x * c64::new(phase.cos(), -phase.sin())).collect();
        for (i, r) in rotated.iter().enumerate() {
            assert!((out.rom.c[(i, 0)] - r.re).abs() < 1e-15 && (out.rom.c[(i, 1)] - r.im).abs() < 1e-15);
        }
        // Reference entry real positive: Im 0, Re |v₁|.
        assert!(out.rom.c[(1, 1)].abs() < 1e-15 && (out.rom.c[(1, 0)] - v[1].norm()).abs() < 1e-15);
        // The transfer function is unchanged: C B and C A B.
        let (cb, cb2) = (&rom.c * &rom.b, &out.rom.c * &out.rom.b);
        let (cab, cab2) = (&rom.c * &rom.a * &rom.b, &out.rom.c * &out.rom.a * &out.rom.b);
        for i in 0..2 {
            assert!((cb[(i, 0)] - cb2[(i, 0)]).abs() < 1e-14 && (cab[(i, 0)] - cab2[(i, 0)]).abs() < 1e-13);
        }
        assert_eq!(out.state_tracks, vec![1, 1]);
    }
}
