//! The modal table: one row per eigenvalue, as text and as JSON.

use serde::Serialize;

use crate::eigen::{describe, EnergyShare};
use crate::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use crate::linear::hz;

/// One row of the modal table (units: rad/s, Hz).
#[derive(Serialize, Debug, Clone)]
pub struct ModeRow {
    pub index: usize,
    /// Real part of λ [rad/s]; `null` in JSON when not finite.
    pub re: Option<f64>,
    /// Imaginary part of λ [rad/s]; `null` in JSON when not finite.
    pub im: Option<f64>,
    pub kind: ModeKind,
    /// Frequency as MBDyn reports it, |Im λ|/2π [Hz] (the damped frequency).
    pub freq_hz: Option<f64>,
    /// Undamped natural frequency |λ|/2π [Hz].
    pub undamped_freq_hz: Option<f64>,
    /// Damping ratio −Re λ/|λ|.
    pub damping: Option<f64>,
    /// Estimated absolute error of λ [rad/s] (eqs. 32–35).
    pub error: Option<f64>,
    /// One-line label of a dynamic mode, e.g. "table pitch (ry) 93 %" (multibody models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Where the mode lives: shares of its energy over node components, element stores and signal states, e.g. "node 3 rz 92 %" (multibody models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// 1-based index of the other member of a complex or ± real pair.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub partner: Option<usize>,
    /// Kinetic-energy share of every node component (multibody models).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub energy: Vec<EnergyShare>,
}

/// The JSON document of `romdyn eig --json`.
#[derive(Serialize, Debug, Clone)]
pub struct ModalReport {
    pub equations: usize,
    pub dcoef: f64,
    pub route: EigenRoute,
    pub units: &'static str,
    pub counts: Counts,
    pub eigenvalues: Vec<ModeRow>,
    /// How the modes were found when not by the dense eigenanalysis of the whole pencil
    /// (the sparse route: which modes, certified or not, largest residual).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

#[derive(Serialize, Debug, Clone)]
pub struct Counts {
    pub dynamic: usize,
    pub zero: usize,
    pub infinite: usize,
}

fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

impl ModalReport {
    pub fn new(modal: &ModalAnalysis, equations: usize) -> Self {
        let eigenvalues = modal
            .modes
            .iter()
            .enumerate()
            .map(|(i, m)| {
                let infinite = m.kind == ModeKind::Infinite;
                let representable = m.lambda.re.is_finite() && m.lambda.im.is_finite();
                ModeRow {
                    index: i + 1,
                    re: representable.then_some(m.lambda.re),
                    im: representable.then_some(m.lambda.im),
                    kind: m.kind,
                    freq_hz: if infinite { None } else { finite(hz(m.lambda.im.abs())) },
                    undamped_freq_hz: if infinite { None } else { finite(m.freq_hz()) },
                    partner: None,
                    damping: if infinite { None } else { finite(m.damping()) },
                    error: finite(m.error),
                    label: None,
                    description: None,
                    energy: Vec::new(),
                }
            })
            .collect();
        let mut eigenvalues: Vec<ModeRow> = eigenvalues;
        for unit in crate::rom::mode_units(modal) {
            if let [a, b] = unit[..] {
                eigenvalues[a].partner = Some(b + 1);
                eigenvalues[b].partner = Some(a + 1);
            }
        }
        ModalReport {
            equations,
            dcoef: modal.dcoef,
            route: modal.route,
            units: "eigenvalues in rad/s, frequencies in Hz (freq_hz = |Im λ|/2π as MBDyn, undamped_freq_hz = |λ|/2π), dcoef in s",
            counts: Counts {
                dynamic: modal.count(ModeKind::Dynamic),
                zero: modal.count(ModeKind::Zero),
                infinite: modal.count(ModeKind::Infinite),
            },
            eigenvalues,
            note: None,
        }
    }

    /// The same report with a second header line (`None`: none).
    pub fn with_note(mut self, note: Option<String>) -> Self {
        self.note = note;
        self
    }

    /// The rows `kept` (0-based, in table order) renumbered from 1, partners and counts
    /// following: the table of a selection of modes.
    pub fn only(&self, kept: &[usize]) -> Self {
        let mut kept = kept.to_vec();
        kept.sort_unstable();
        kept.dedup();
        let new_index = |old: usize| kept.iter().position(|&k| k + 1 == old).map(|p| p + 1);
        let eigenvalues: Vec<ModeRow> = kept
            .iter()
            .filter_map(|&k| self.eigenvalues.get(k))
            .map(|r| ModeRow { index: new_index(r.index).unwrap_or(r.index), partner: r.partner.and_then(new_index), ..r.clone() })
            .collect();
        let count = |kind| eigenvalues.iter().filter(|r| r.kind == kind).count();
        let counts = Counts { dynamic: count(ModeKind::Dynamic), zero: count(ModeKind::Zero), infinite: count(ModeKind::Infinite) };
        ModalReport { equations: self.equations, dcoef: self.dcoef, route: self.route, units: self.units, counts, eigenvalues, note: self.note.clone() }
    }

    /// Attaches kinetic-energy shares (one list per mode, in table order).
    pub fn with_energy(self, shares: Vec<Vec<EnergyShare>>) -> Self {
        let mut report = self.with_descriptions(&shares);
        for (row, s) in report.eigenvalues.iter_mut().zip(shares) {
            row.energy = s;
        }
        report
    }

    /// Attaches the one-line descriptions of the kinetic-energy shares (one list per mode,
    /// in table order), not the shares themselves (a writer that streams them, e.g.
    /// `eigen_json`, borrows them instead of copying a list per mode).
    pub fn with_descriptions(mut self, shares: &[Vec<EnergyShare>]) -> Self {
        for (row, s) in self.eigenvalues.iter_mut().zip(shares) {
            row.description = (!s.is_empty()).then(|| describe(s));
        }
        self
    }

    /// Attaches mode labels (one per mode, in table order; dynamic modes only are shown).
    pub fn with_labels(mut self, labels: Vec<Option<String>>) -> Self {
        for (row, l) in self.eigenvalues.iter_mut().zip(labels) {
            row.label = if row.kind == ModeKind::Dynamic { l } else { None };
        }
        self
    }

    /// The table as aligned text: one row per dynamic mode (a complex or ± real pair is
    /// one row), the zero and infinite eigenvalues counted on one line each.
    pub fn to_text(&self) -> String {
        let rows = self.paired_rows(usize::MAX);
        let (z, i) = (self.of_kind(ModeKind::Zero), self.of_kind(ModeKind::Infinite));
        let mut tail = String::new();
        for (rows, what) in [(z, "zero eigenvalues (constrained or static unknowns)"), (i, "infinite eigenvalues (multipliers, algebraic unknowns)")] {
            if let (Some(a), Some(b)) = (rows.first(), rows.last()) {
                tail += &format!("  modes {}–{}: {} {what}; --all lists every eigenvalue\n", a.index, b.index, rows.len());
            }
        }
        self.text(rows, &tail)
    }

    /// Every eigenvalue on its own row.
    pub fn to_text_all(&self) -> String {
        self.text(self.eigenvalues.iter().map(|r| (r, None)).collect(), "")
    }

    /// The header and the first `limit` dynamic modes (one row per pair), as aligned text.
    pub fn to_text_dynamic(&self, limit: usize) -> String {
        let rows = self.paired_rows(limit);
        let total = self.paired_rows(usize::MAX).len();
        let more = total.saturating_sub(limit);
        let tail = if more > 0 { format!("  … {more} more dynamic modes (romdyn eig lists every mode)\n") } else { String::new() };
        self.text(rows, &tail)
    }

    fn of_kind(&self, kind: ModeKind) -> Vec<&ModeRow> {
        self.eigenvalues.iter().filter(|r| r.kind == kind).collect()
    }

    /// Dynamic rows, a pair as its first member with its partner.
    fn paired_rows(&self, limit: usize) -> Vec<(&ModeRow, Option<&ModeRow>)> {
        self.eigenvalues
            .iter()
            .filter(|r| r.kind == ModeKind::Dynamic && r.partner.is_none_or(|p| p > r.index))
            .take(limit)
            .map(|r| (r, r.partner.and_then(|p| self.eigenvalues.get(p - 1))))
            .collect()
    }

    fn text(&self, rows: Vec<(&ModeRow, Option<&ModeRow>)>, tail: &str) -> String {
        let mut s = format!(
            "# {} equations, route {:?}, dCoef {:e} s; {} dynamic, {} zero, {} infinite; freq = |Im λ|/2π (MBDyn's), undamped = |λ|/2π\n",
            self.equations, self.route, self.dcoef, self.counts.dynamic, self.counts.zero, self.counts.infinite
        );
        if let Some(note) = &self.note {
            s += &format!("# {note}\n");
        }
        let labels = self.eigenvalues.iter().any(|r| r.label.is_some());
        let energy_column = match (labels, self.eigenvalues.iter().any(|r| r.description.is_some())) {
            (true, _) => format!("  {:<36}  energy share", "label"),
            (false, true) => "  energy share".to_string(),
            (false, false) => String::new(),
        };
        s += &format!(
            "{:>7}  {:>14}  {:>15}  {:>12}  {:>14}  {:>9}  {:>8}  {:>9}{energy_column}\n",
            "mode", "Re λ [rad/s]", "Im λ [rad/s]", "freq [Hz]", "undamped [Hz]", "damping", "kind", "error"
        );
        // `+ 0.0` prints a real eigenvalue's Im λ = −0 as 0.000000e0, not -0.000000e0.
        let num = |x: Option<f64>, w: usize| x.map_or(format!("{:>w$}", "-"), |v| format!("{:>w$.6e}", v + 0.0));
        let hz = |x: Option<f64>, w: usize| x.map_or(format!("{:>w$}", "-"), |v| format!("{v:>w$.6}"));
        for (r, partner) in rows {
            let dynamic = r.kind == ModeKind::Dynamic;
            let index = match partner {
                Some(p) => format!("{},{}", r.index, p.index),
                None => r.index.to_string(),
            };
            // A complex pair shows ±Im λ; a ± real pair ±Re λ.
            let complex_pair = partner.is_some() && r.im.is_some_and(|v| v != 0.0);
            let real_pair = partner.is_some() && !complex_pair;
            let re = if real_pair { r.re.map_or(format!("{:>14}", "-"), |v| format!("{:>14}", format!("±{:.6e}", v.abs()))) } else { num(r.re, 14) };
            let im = if complex_pair { r.im.map_or(format!("{:>15}", "-"), |v| format!("{:>15}", format!("±{:.6e}", v.abs()))) } else { num(r.im, 15) };
            let label = if labels { format!("{:<36}  ", if dynamic { r.label.as_deref().unwrap_or("") } else { "" }) } else { String::new() };
            let row = format!(
                "{index:>7}  {re}  {im}  {}  {}  {}  {:>8}  {}  {label}{}",
                hz(r.freq_hz, 12),
                hz(r.undamped_freq_hz, 14),
                // Rounding leaves |ζ| ~ 1e-12 on undamped modes: show 0.0000, not -0.0000;
                // a ± real pair has no single damping ratio; zero and infinite rows none.
                match (dynamic && !real_pair, r.damping) {
                    (true, Some(v)) => format!("{:>9.4}", if v.abs() < 5e-5 { 0.0 } else { v }),
                    _ => format!("{:>9}", ""),
                },
                r.kind.name(),
                r.error.map_or(format!("{:>9}", "inf"), |v| format!("{v:>9.1e}")),
                if dynamic { r.description.as_deref().unwrap_or("") } else { "" },
            );
            s += row.trim_end();
            s += "\n";
        }
        s + tail
    }
}
