//! The book's worked example of a cut control loop (docs/src/guide/control.md): the flexible
//! drive of `examples/pid_two_mass.mbd` under its PID position loop. From the one file: the
//! plant (the loop cut at genel 5, `--cut genel:5`), the loop transfer function at the cut
//! `L = −returned/injected`, and the closed loop, full models and ROMs. Prints their poles
//! and static gains and writes `out/pid_two_mass_bode.{svg,png}`.
//!
//!     cargo run --example pid_two_mass_bode

use romdyn::dae::{Cut, NodeInput, NodeOutput};
use romdyn::eigen::ModeKind;
use romdyn::linear::{FrequencyResponse, Port};
use romdyn::output::bode::{write_bode, BodePlot, CurveStyle, ResponseCurve};
use romdyn::rom::{full_frequency_response, log_frequencies, ModeSelection};
use romdyn::study::{Ports, RomRequest, Study, StudySource};

fn study(cuts: &[Cut]) -> anyhow::Result<Study> {
    let inputs: Vec<NodeInput> = vec!["1:abstract".parse()?];
    let outputs: Vec<NodeOutput> = vec!["2:abstract".parse()?];
    let ports = Ports::from_parts(None, &inputs, &outputs, &[], &[], None, cuts)?;
    Ok(Study::builder(StudySource::model_file("examples/pid_two_mass.mbd")).ports(ports).build()?)
}

fn poles(s: &Study) -> String {
    let mut p: Vec<_> = s.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic && m.lambda.im >= 0.0).map(|m| m.lambda).collect();
    p.sort_by(|a, b| a.norm().total_cmp(&b.norm()));
    p.iter().map(|l| if l.im == 0.0 { format!("{:.6}", l.re) } else { format!("{:.6} ± {:.6}j", l.re, l.im) }).collect::<Vec<_>>().join(", ")
}

fn main() -> anyhow::Result<()> {
    let plant = study(&["genel:5".parse().map_err(anyhow::Error::msg)?])?;
    let closed = study(&[])?;
    println!("plant (cut at genel 5) poles [rad/s]: {}", poles(&plant));
    println!("closed-loop poles [rad/s]: {}", poles(&closed));
    let band = RomRequest::new(ModeSelection::band(0.0, 10.0).map_err(anyhow::Error::msg)?);
    let plant_rom = plant.reduce(&band)?;
    let closed_rom = closed.reduce(&band)?;
    let gain = |g: &Result<faer::Mat<f64>, String>| g.as_ref().map_or_else(|e| e.clone(), |g| format!("{:.6e}", g[(0, 0)]));
    println!("plant x2/d static gain [m/N]: full {}, ROM {}", gain(&plant_rom.static_gains.full), gain(&plant_rom.static_gains.rom));
    println!("closed loop x2/d static gain [m/N]: full {}, ROM {}", gain(&closed_rom.static_gains.full), gain(&closed_rom.static_gains.rom));
    println!("plant ROM: {} states; closed-loop ROM: {} states", plant_rom.ordinary.a.nrows(), closed_rom.ordinary.a.nrows());
    let freq = log_frequencies(0.05, 20.0, 600);
    let full_plant = full_frequency_response(plant.dae(), &freq);
    let full_closed = full_frequency_response(closed.dae(), &freq);
    // One grid and two channels (x2/d and the loop L at the cut), each with its models' curves.
    let entry = |h: &[faer::Mat<faer::c64>], i: usize, j: usize, sign: f64| h.iter().map(|m| m[(i, j)] * sign).collect::<Vec<_>>();
    let ports = |names: [&str; 2]| names.map(|n| Port { name: n.into(), unit: String::new() }).to_vec();
    let full = full_plant.iter().map(|m| faer::Mat::from_fn(2, 2, |i, j| if i == j { m[(i, j)] * if i == 0 { 1.0 } else { -1.0 } } else { faer::c64::new(0.0, 0.0) })).collect();
    let response = FrequencyResponse::new(freq.clone(), ports(["d (motor force)", "w (injected at the cut)"]), ports(["x2", "L"]), full);
    let curve = |label, (output, input), values, style| ResponseCurve { label, output, input, values, style };
    let plot = BodePlot {
        title: "Flexible drive under PID: one file, cut and closed".into(),
        magnitude_unit: "m/N (L: -)".into(),
        response: &response,
        curves: vec![
            curve("plant P = x2/d (cut)", (0, 0), entry(&full_plant, 0, 0, 1.0), CurveStyle::Full),
            curve("plant ROM", (0, 0), entry(&plant_rom.ordinary.frequency_response(&freq), 0, 0, 1.0), CurveStyle::Rom),
            curve("loop L = -returned/injected", (1, 1), entry(&full_plant, 1, 1, -1.0), CurveStyle::Full),
            curve("closed loop x2/d", (0, 0), entry(&full_closed, 0, 0, 1.0), CurveStyle::Full),
            curve("closed-loop ROM", (0, 0), entry(&closed_rom.ordinary.frequency_response(&freq), 0, 0, 1.0), CurveStyle::Rom),
        ],
    };
    std::fs::create_dir_all("out")?;
    write_bode(&plot, "out/pid_two_mass_bode.svg".as_ref(), "out/pid_two_mass_bode.png".as_ref())?;
    println!("wrote out/pid_two_mass_bode.svg, out/pid_two_mass_bode.png");
    Ok(())
}
