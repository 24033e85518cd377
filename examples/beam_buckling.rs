//! Paper Fig. 5: the first bending frequency of the simply supported beam (CASES C4, Table 3)
//! against the axial compression N/N_crit, with 2 and 4 finite-volume beam elements, next
//! to eq. 37. Writes `out/beam_buckling.{csv,svg,png}`.
//!
//!     cargo run --release --example beam_buckling

#[allow(dead_code)]
#[path = "../tests/common/beams.rs"]
mod beams;

use std::path::Path;

use romdyn::dae::{linearize, Assembler, State};
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::output::line_plot::{write_line_plot, write_series_csv, LinePlot, Series, SeriesStyle};
use romdyn::solve::{static_solution, NewtonSettings};

/// Lowest natural frequency [rad/s] of the beam at its static equilibrium under `n` [N].
fn first_bending(elements: usize, n: f64) -> anyhow::Result<f64> {
    let model = beams::simply_supported(&beams::TABLE3, elements, n, 0.0);
    let asm = Assembler::new(&model);
    let mut st = State::initial(&model, &asm.dofs);
    static_solution(&asm, &mut st, 1, &NewtonSettings { tolerance: 1e-10, ..NewtonSettings::default() })?;
    let dae = linearize(&model, &st, &[], &[], None)?;
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda)?;
    Ok(modal.of_kind(ModeKind::Dynamic).map(|i| modal.modes[i].lambda.norm()).fold(f64::INFINITY, f64::min))
}

fn main() -> anyhow::Result<()> {
    let d = beams::TABLE3;
    let k = std::f64::consts::PI / d.length;
    let n_crit = k * k * d.ej;
    let eq37 = |r: f64| k * k * (d.ej / d.rho_a).sqrt() * (1.0 - r).sqrt();
    let ratios = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];
    let mut series = vec![Series { label: "eq. 37".into(), points: (0..=100).map(|i| i as f64 / 100.0).map(|r| (r, eq37(r))).collect(), style: SeriesStyle::Line }];
    println!("N/Ncrit   eq. 37 [rad/s]   2 elements        4 elements");
    let mut rows = vec![Vec::new(); ratios.len()];
    for elements in [2, 4] {
        let mut points = Vec::new();
        for (row, &r) in rows.iter_mut().zip(&ratios) {
            let w = first_bending(elements, r * n_crit)?;
            row.push(format!("{w:9.3} ({:+.2} %)", 100.0 * (w / eq37(r) - 1.0)));
            points.push((r, w));
        }
        series.push(Series { label: format!("{elements} beam elements"), points, style: SeriesStyle::Markers });
    }
    for (row, &r) in rows.iter().zip(&ratios) {
        println!("{r:7.1}   {:14.3}   {}", eq37(r), row.join("   "));
    }
    let plot = LinePlot {
        title: "Simply supported beam: first bending frequency under axial compression".into(),
        x_label: "N / N_crit [-]".into(),
        y_label: "angular frequency [rad/s]".into(),
        series,
    };
    let prefix = Path::new("out/beam_buckling");
    write_series_csv(&plot, &prefix.with_extension("csv"))?;
    write_line_plot(&plot, &prefix.with_extension("svg"), &prefix.with_extension("png"))?;
    println!("wrote out/beam_buckling.csv, .svg, .png");
    Ok(())
}
