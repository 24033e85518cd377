//! A ROM between design points: the stacked ROMs in the consistent modal basis
//! ([`super::basis`]) interpolated entry by entry, linearly in each parameter between the
//! grid values around the point (multilinear over several), and its check against the ROM
//! computed there.

use faer::{c64, Mat};

use crate::output::rom_file::RomExport;
use crate::rom::OrdinaryRom;

use super::basis::{consistent_rom, ConsistentRom};
use super::output::StackError;
use super::track::track;
use super::{PointResult, SweepResults};

/// How far an interpolated ROM is from the ROM computed at the same design point.
#[derive(Clone, Debug)]
pub struct InterpolationCheck {
    /// `‖X_interpolated − X_exact‖_F / ‖X_exact‖_F` of A, B, C, D (both in the consistent
    /// basis; D's is absolute when D is zero).
    pub matrices: Vec<(&'static str, f64)>,
    /// Largest `|λ_interpolated − λ_exact| / |λ_exact|` over the ROM's eigenvalues, each
    /// paired with the nearest exact one.
    pub eigenvalues: f64,
    /// `‖G_interpolated − G_exact‖_F / ‖G_exact‖_F` of the static gains `D − C A⁻¹ B`
    /// (NaN when a ROM has none).
    pub static_gain: f64,
}

impl InterpolationCheck {
    /// "A 2.1e-4, B 3.0e-5, …; eigenvalues 1.2e-4; static gain 4.0e-5" (relative).
    pub fn describe(&self) -> String {
        let m: Vec<String> = self.matrices.iter().map(|(n, e)| format!("{n} {e:.2e}")).collect();
        format!("relative differences {}; eigenvalues {:.2e}; static gain {:.2e}", m.join(", "), self.eigenvalues, self.static_gain)
    }
}

fn frobenius(m: &Mat<f64>) -> f64 {
    m.norm_l2()
}

/// Largest relative distance from each of `a` to the nearest of `b`.
fn eigenvalue_error(a: &[c64], b: &[c64]) -> f64 {
    a.iter().map(|x| b.iter().map(|y| (x - y).norm() / y.norm().max(f64::MIN_POSITIVE)).fold(f64::INFINITY, f64::min)).fold(0.0, f64::max)
}

fn ordinary(r: &RomExport) -> OrdinaryRom {
    OrdinaryRom { a: r.a.clone(), b: r.b.clone(), c: r.c.clone(), d: r.d.clone(), eigenvalues: Vec::new(), input_names: r.inputs.clone(), output_names: r.outputs.clone() }
}

impl SweepResults {
    /// Every point's ROM in the consistent basis (`None` where it failed).
    pub fn consistent_roms(&self) -> Vec<Option<ConsistentRom>> {
        let tracking = self.tracking();
        self.results
            .iter()
            .enumerate()
            .map(|(k, r)| {
                let r = r.as_ref().ok()?;
                Some(consistent_rom(&r.rom, &r.modes, tracking.matches[k].as_deref().unwrap_or(&[]), &tracking.reference))
            })
            .collect()
    }

    /// The design points around `values` (one per parameter) and their weights: for each
    /// parameter the two grid values around its value, every combination of them.
    fn corners(&self, values: &[f64]) -> Result<Vec<(usize, f64)>, StackError> {
        let bad = |m: String| StackError::Interpolation(m);
        if values.len() != self.names.len() {
            return Err(bad(format!("give one value for each swept parameter ({})", self.names.join(", "))));
        }
        let mut axes: Vec<Vec<(f64, f64)>> = Vec::new();
        for (j, &v) in values.iter().enumerate() {
            let mut grid: Vec<f64> = self.points.iter().map(|p| p[j]).collect();
            grid.sort_by(f64::total_cmp);
            grid.dedup();
            let (lo, hi) = (grid[0], grid[grid.len() - 1]);
            if !(v >= lo && v <= hi) {
                return Err(bad(format!("{} = {v} is outside the sweep's values {lo} to {hi}: a ROM is only interpolated between design points", self.names[j])));
            }
            axes.push(if let Some(&g) = grid.iter().find(|&&g| g == v) {
                vec![(g, 1.0)]
            } else {
                // lo < v < hi: grid[i − 1] < v < grid[i].
                let i = grid.partition_point(|&g| g < v);
                let (a, b) = (grid[i - 1], grid[i]);
                let w = (v - a) / (b - a);
                vec![(a, 1.0 - w), (b, w)]
            });
        }
        let mut corners = vec![(Vec::new(), 1.0)];
        for axis in &axes {
            corners = corners.into_iter().flat_map(|(p, w): (Vec<f64>, f64)| axis.iter().map(move |&(x, wx)| ([p.clone(), vec![x]].concat(), w * wx))).collect();
        }
        corners
            .into_iter()
            .filter(|(_, w)| *w != 0.0)
            .map(|(p, w)| {
                let k = self.points.iter().position(|q| q.iter().zip(&p).all(|(a, b)| a.to_bits() == b.to_bits()));
                match k {
                    Some(k) if self.results[k].is_ok() => Ok((k, w)),
                    Some(k) => Err(bad(format!("design point {} ({}) failed: no ROM to interpolate from", k + 1, self.describe_point(k)))),
                    None => Err(bad(format!("the sweep has no design point at {}: interpolation needs the full grid around the point", self.names.iter().zip(&p).map(|(n, v)| format!("{n} = {v}")).collect::<Vec<_>>().join(", ")))),
                }
            })
            .collect()
    }

    /// The ROM at `values` (one per parameter, inside the sweep's range) interpolated from
    /// the consistent ROMs of the points around it. The ROMs there must be ordinary and keep
    /// the same tracked modes (a ROM through a crossing must keep both modes).
    pub fn interpolate(&self, values: &[f64]) -> Result<RomExport, StackError> {
        self.interpolate_tracked(values).map(|(rom, _)| rom)
    }

    /// [`SweepResults::interpolate`] and the tracked mode of each state.
    fn interpolate_tracked(&self, values: &[f64]) -> Result<(RomExport, Vec<usize>), StackError> {
        let corners = self.corners(values)?;
        let roms = self.consistent_roms();
        let (k0, _) = corners[0];
        let Some(first) = &roms[k0] else { return Err(StackError::NoPoint) };
        if first.rom.kind != "ordinary" {
            return Err(StackError::Interpolation("only ordinary ROMs are interpolated (a descriptor ROM's static states have no modal basis): build them with the ordinary form".into()));
        }
        for &(k, _) in &corners {
            let r = roms[k].as_ref().ok_or(StackError::NoPoint)?;
            if r.state_tracks != first.state_tracks || r.state_tracks.contains(&0) {
                return Err(StackError::Interpolation(format!(
                    "the ROMs at {} and at {} do not keep the same tracked modes (states of modes {:?} and {:?}; 0: a mode not tracked): keep every mode that crosses the kept ones (a larger --count or --lowest)",
                    self.describe_point(k0),
                    self.describe_point(k),
                    first.state_tracks,
                    r.state_tracks
                )));
            }
        }
        let blend = |get: &dyn Fn(&RomExport) -> &Mat<f64>| {
            let m0 = get(&first.rom);
            let mut out = Mat::<f64>::zeros(m0.nrows(), m0.ncols());
            for &(k, w) in &corners {
                if let Some(r) = &roms[k] {
                    out += get(&r.rom) * faer::Scale(w);
                }
            }
            out
        };
        let mut out = RomExport { e: blend(&|r| &r.e), a: blend(&|r| &r.a), b: blend(&|r| &r.b), c: blend(&|r| &r.c), d: blend(&|r| &r.d), full_static_gain: None, ..first.rom.clone() };
        let n = out.a.nrows();
        let mut eig = if n == 0 { Vec::new() } else { out.a.as_ref().eigenvalues().unwrap_or_default() };
        eig.sort_by(|a, b| a.norm().total_cmp(&b.norm()).then(b.im.total_cmp(&a.im)));
        out.eigenvalues = eig;
        out.full_eigenvalues = Vec::new();
        out.reference_time = None;
        out.state_freq_hz = vec![f64::NAN; n];
        out.state_modes = vec![0; n];
        out.rom_static_gain = ordinary(&out).static_gain().ok();
        Ok((out, first.state_tracks.clone()))
    }

    /// Interpolates at `values` and compares with `exact`, the point computed there (its
    /// modes tracked from the nearest design point, its ROM in the same basis).
    pub fn check_interpolation(&self, values: &[f64], exact: &PointResult) -> Result<(RomExport, RomExport, InterpolationCheck), StackError> {
        let (interpolated, tracks) = self.interpolate_tracked(values)?;
        let mut points = self.points.clone();
        points.push(values.to_vec());
        let mut modes: Vec<Option<&[crate::sweep::PointMode]>> = self.results.iter().map(|r| r.as_ref().ok().map(|r| r.modes.as_slice())).collect();
        modes.push(Some(&exact.modes));
        let tracking = track(&points, &modes, self.modes);
        let last = tracking.matches.last().and_then(|m| m.clone()).unwrap_or_default();
        let exact = consistent_rom(&exact.rom, &exact.modes, &last, &tracking.reference);
        if exact.state_tracks != tracks {
            return Err(StackError::Interpolation(format!("the ROM computed at the point keeps other modes than the sweep's around it (states of tracked modes {:?}, interpolated {:?})", exact.state_tracks, tracks)));
        }
        let rel = |a: &Mat<f64>, b: &Mat<f64>| {
            let d = frobenius(&(a - b));
            let s = frobenius(b);
            if s > 0.0 { d / s } else { d }
        };
        let (x, e) = (&interpolated, &exact.rom);
        let matrices = vec![("A", rel(&x.a, &e.a)), ("B", rel(&x.b, &e.b)), ("C", rel(&x.c, &e.c)), ("D", rel(&x.d, &e.d))];
        let exact_eig = if e.a.nrows() == 0 { Vec::new() } else { e.a.as_ref().eigenvalues().unwrap_or_default() };
        let static_gain = match (ordinary(x).static_gain(), ordinary(e).static_gain()) {
            (Ok(g), Ok(h)) => rel(&g, &h),
            _ => f64::NAN,
        };
        let check = InterpolationCheck { matrices, eigenvalues: eigenvalue_error(&x.eigenvalues, &exact_eig), static_gain };
        Ok((interpolated, exact.rom, check))
    }
}
