//! The short text a ROM is reported with: kept modes, damping, static gains as a named
//! matrix, accuracy on the frequency grid, warnings.

use faer::Mat;

use crate::eigen::describe;

use super::{GridAccuracy, ReducedModel, RomCheck, StaticGains, Study};

/// A frequency [Hz] with 4 decimals in 1e-3..1e5, scientific outside.
fn fmt_hz(f: f64) -> String {
    if (1e-3..1e5).contains(&f) { format!("{f:.4}") } else { format!("{f:.4e}") }
}

fn hz(l: faer::c64) -> (f64, f64) {
    let tau = 2.0 * std::f64::consts::PI;
    (l.im.abs() / tau, l.norm() / tau)
}

/// `rows × columns` matrices side by side under named columns, one block per row name.
fn gain_table(g: &StaticGains) -> String {
    let mut s = String::from("static gain (rows: outputs, columns: inputs; SI units)\n");
    let width = g.input_names.iter().map(|n| n.chars().count()).max().unwrap_or(0).max(13);
    s += &format!("{:<24}", "");
    for n in &g.input_names {
        s += &format!("  {n:>width$}");
    }
    s += "\n";
    let big = g.full.as_ref().map_or(0.0, |m| (0..m.nrows()).flat_map(|i| (0..m.ncols()).map(move |j| (i, j))).filter(|&(i, j)| !g.is_zero(i, j)).map(|(i, j)| m[(i, j)].abs()).fold(0.0, f64::max));
    let cell = |m: &Mat<f64>, i: usize, j: usize| format!("  {:>width$}", format!("{:.6e}", m[(i, j)]));
    for (i, out) in g.output_names.iter().enumerate() {
        s += &format!("{out}\n");
        if let Ok(full) = &g.full {
            s += &format!("{:<24}", "  full model");
            (0..g.input_names.len()).for_each(|j| s += &cell(full, i, j));
            s += "\n";
        }
        if let Ok(rom) = &g.rom {
            s += &format!("{:<24}", "  ROM");
            (0..g.input_names.len()).for_each(|j| s += &cell(rom, i, j));
            s += "\n";
        }
        if let (Ok(full), Ok(rom)) = (&g.full, &g.rom) {
            s += &format!("{:<24}", "  relative difference");
            for j in 0..g.input_names.len() {
                let f = full[(i, j)];
                // Entries zero to rounding have no meaningful relative difference.
                let text = if g.is_zero(i, j) {
                    "(rounding)".into()
                } else if f.abs() > StaticGains::ZERO * big {
                    format!("{:.1e}", (rom[(i, j)] - f) / f.abs())
                } else {
                    "(zero)".into()
                };
                s += &format!("  {text:>width$}");
            }
            s += "\n";
        }
    }
    if let Err(e) = &g.full {
        s += &format!("full model: not available ({e})\n");
    }
    if let Err(e) = &g.rom {
        s += &format!("ROM: not available ({e})\n");
    }
    s
}

/// A response's accuracy on the grid: the normwise line, and with more than one port pair the
/// worst pair on its own scale.
fn accuracy_lines(what: &str, a: &GridAccuracy, pairs: usize, outputs: &[String], inputs: &[String]) -> String {
    let ok = a.within_1_percent_up_to_hz.map_or("nowhere on the grid".to_string(), |f| format!("up to {} Hz", fmt_hz(f)));
    let mut s = format!(
        "{what} on {}–{} Hz ({} points): largest relative error {:.2e} at {} Hz; within 1 % {ok}\n",
        fmt_hz(a.fmin_hz),
        fmt_hz(a.fmax_hz),
        a.points,
        a.largest_relative_error,
        fmt_hz(a.at_hz)
    );
    // With one input and one output the pair is the whole response: the line above.
    if let Some(c) = a.worst_channel.as_ref().filter(|_| pairs > 1) {
        let name = |names: &[String], k: usize| names.get(k).cloned().unwrap_or_else(|| (k + 1).to_string());
        let channel = format!("{} / {}", name(outputs, c.output), name(inputs, c.input));
        s += &format!("worst port pair on its own scale: {channel}, relative error {:.2e} at {} Hz\n", c.relative, fmt_hz(c.at_hz));
    }
    s
}

impl ReducedModel {
    /// The summary: states, kept modes with frequency, damping and dominant node
    /// components, modal damping applied, static gains, accuracy of every response on the
    /// check's grid (when checked; its warnings are the check's, printed with the others).
    pub fn summary(&self, study: &Study, check: Option<&RomCheck>) -> String {
        let energy = study.modal_energy();
        let states = self.ordinary.a.nrows();
        let mut s = if self.static_correction {
            format!("ROM: {states} states from {} kept mode(s), the modes not kept statically corrected in D (full model's static gain by sparse LU)\n", self.kept_modes.len())
        } else {
            format!("ROM: {states} states from {} kept mode(s), {} statically residualized state(s) folded into D\n", self.kept_modes.len(), self.descriptor.static_states)
        };
        s += &format!("  {:>7}  {:>12}  {:>14}  {:>8}  {:>9}  description\n", "mode", "freq [Hz]", "undamped [Hz]", "damping", "dominance");
        for k in &self.kept_modes {
            let m = &study.modal().modes[k.indices[0] - 1];
            let (f, fu) = hz(k.lambda);
            let idx = k.indices.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(",");
            let label = energy.as_ref().map(|e| describe(&e.shares(m))).unwrap_or_default();
            let zeta = m.damping();
            s += &format!("  {idx:>7}  {f:>12.6}  {fu:>14.6}  {:>8.4}  {:>9.2e}  {label}\n", if zeta.abs() < 5e-5 { 0.0 } else { zeta }, k.dominance).trim_end().to_string();
            s += "\n";
        }
        for d in &self.damping {
            s += &format!(
                "modal damping (ROM only): mode {}: ζ {:.4} -> {:.4}, λ {:.6}{:+.6}j -> {:.6}{:+.6}j rad/s\n",
                d.mode + 1,
                // As the table above: a ratio that rounds to zero prints without a sign.
                { let z = -d.before.re / d.before.norm(); if z.abs() < 5e-5 { 0.0 } else { z } },
                -d.after.re / d.after.norm(),
                d.before.re,
                d.before.im,
                d.after.re,
                d.after.im
            );
        }
        if let Some(order) = &self.order {
            s += &order.describe();
        }
        if let Some(d) = &self.discrete {
            s += &super::control::describe_discrete(d);
        }
        s += &gain_table(&self.static_gains);
        if let (Some(share), Some((rel, channel))) = (self.static_gains.kept_share(), self.static_gains.largest_relative_difference()) {
            s += &format!("the ROM keeps {:.4} % of the full model's static gain (Frobenius norms); largest relative difference {rel:.1e} ({channel})\n", 100.0 * share);
        }
        if let Some(check) = check {
            let pairs = self.static_gains.output_names.len() * self.static_gains.input_names.len();
            let what = match &self.undamped {
                Some(t) if t.before_order_reduction => "frequency response (of the modal ROM without its added modal damping, which the full model lacks, and so before the balanced reduction, whose error the Hankel bound states)",
                Some(_) => "frequency response (of the ROM without its added modal damping, which the full model lacks)",
                None => "frequency response",
            };
            s += &accuracy_lines(what, &check.accuracy, pairs, &self.static_gains.output_names, &self.static_gains.input_names);
            if let Some((t, a)) = &check.transmissibility {
                let labels = |ports: &[crate::linear::Port]| ports.iter().map(|p| p.label()).collect::<Vec<_>>();
                s += &accuracy_lines("transmissibility z/z_e (eq. 100)", a, t.outputs.len() * t.inputs.len(), &labels(&t.outputs), &labels(&t.inputs));
            }
        }
        s
    }
}
