//! The modal table: one row per eigenvalue, as text and as JSON.

use serde::Serialize;

use crate::dae::{describe, EnergyShare};
use crate::linear::{EigenRoute, ModalAnalysis, ModeKind};

/// One row of the modal table (units: rad/s, Hz).
#[derive(Serialize, Debug, Clone)]
pub struct ModeRow {
    pub index: usize,
    /// Real part of λ [rad/s]; `null` in JSON when not finite.
    pub re: Option<f64>,
    /// Imaginary part of λ [rad/s]; `null` in JSON when not finite.
    pub im: Option<f64>,
    pub kind: ModeKind,
    /// Natural frequency |λ|/2π [Hz].
    pub freq_hz: Option<f64>,
    /// Damping ratio −Re λ/|λ|.
    pub damping: Option<f64>,
    /// Estimated absolute error of λ [rad/s] (eqs. 32–35).
    pub error: Option<f64>,
    /// One-line label of a dynamic mode, e.g. "table pitch (ry) 93 %" (multibody models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Dominant node components by kinetic energy, e.g. "node 3 rz 92 %" (multibody models).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
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
                    freq_hz: if infinite { None } else { finite(m.freq_hz()) },
                    damping: if infinite { None } else { finite(m.damping()) },
                    error: finite(m.error),
                    label: None,
                    description: None,
                    energy: Vec::new(),
                }
            })
            .collect();
        ModalReport {
            equations,
            dcoef: modal.dcoef,
            route: modal.route,
            units: "eigenvalues in rad/s, frequencies in Hz, dcoef in s",
            counts: Counts {
                dynamic: modal.count(ModeKind::Dynamic),
                zero: modal.count(ModeKind::Zero),
                infinite: modal.count(ModeKind::Infinite),
            },
            eigenvalues,
        }
    }

    /// Attaches kinetic-energy shares (one list per mode, in table order).
    pub fn with_energy(mut self, shares: Vec<Vec<EnergyShare>>) -> Self {
        for (row, s) in self.eigenvalues.iter_mut().zip(shares) {
            row.description = (!s.is_empty()).then(|| describe(&s));
            row.energy = s;
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

    /// The table as aligned text.
    pub fn to_text(&self) -> String {
        self.text(self.eigenvalues.iter(), "")
    }

    /// The header and the first `limit` dynamic modes (pairs count twice), as aligned text.
    pub fn to_text_dynamic(&self, limit: usize) -> String {
        let dynamic: Vec<&ModeRow> = self.eigenvalues.iter().filter(|r| r.kind == ModeKind::Dynamic).collect();
        let more = dynamic.len().saturating_sub(limit);
        let tail = if more > 0 { format!("  … {more} more dynamic modes (romdyn eig lists every mode)\n") } else { String::new() };
        self.text(dynamic.into_iter().take(limit), &tail)
    }

    fn text<'a>(&self, rows: impl Iterator<Item = &'a ModeRow>, tail: &str) -> String {
        let mut s = format!(
            "# {} equations, route {:?}, dCoef {:e} s; {} dynamic, {} zero, {} infinite\n",
            self.equations, self.route, self.dcoef, self.counts.dynamic, self.counts.zero, self.counts.infinite
        );
        let labels = self.eigenvalues.iter().any(|r| r.label.is_some());
        let energy_column = match (labels, self.eigenvalues.iter().any(|r| r.description.is_some())) {
            (true, _) => format!("  {:<36}  kinetic energy", "label"),
            (false, true) => "  kinetic energy".to_string(),
            (false, false) => String::new(),
        };
        s += &format!(
            "{:>5}  {:>14}  {:>14}  {:>12}  {:>9}  {:>8}  {:>9}{energy_column}\n",
            "mode", "Re λ [rad/s]", "Im λ [rad/s]", "freq [Hz]", "damping", "kind", "error"
        );
        let num = |x: Option<f64>, w: usize| x.map_or(format!("{:>w$}", "-"), |v| format!("{v:>w$.6e}"));
        for r in rows {
            let label = if labels { format!("{:<36}  ", r.label.as_deref().unwrap_or("")) } else { String::new() };
            let row = format!(
                "{:>5}  {}  {}  {}  {}  {:>8}  {}  {label}{}",
                r.index,
                num(r.re, 14),
                num(r.im, 14),
                r.freq_hz.map_or(format!("{:>12}", "-"), |v| format!("{v:>12.6}")),
                // Rounding leaves |ζ| ~ 1e-12 on undamped modes: show 0.0000, not -0.0000.
                r.damping.map_or(format!("{:>9}", "-"), |v| format!("{:>9.4}", if v.abs() < 5e-5 { 0.0 } else { v })),
                r.kind.name(),
                r.error.map_or(format!("{:>9}", "inf"), |v| format!("{v:>9.1e}")),
                r.description.as_deref().unwrap_or(""),
            );
            s += row.trim_end();
            s += "\n";
        }
        s + tail
    }
}
