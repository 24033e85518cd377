//! Bode plot and CSV of an analytic single-degree-of-freedom response.

use romdyn::c64;
use romdyn::linear::{FrequencyResponse, Port};
use romdyn::output::bode::{response_curves, write_bode, BodePlot};
use romdyn::output::response_csv::write_response_csv;
use romdyn::rom::log_frequencies;

/// 1/(k − m ω² + j r ω), m = 10 kg, k = 1000 N/m, r = 10 N s/m.
fn sdof(f_hz: f64, k: f64) -> c64 {
    let w = 2.0 * std::f64::consts::PI * f_hz;
    c64::new(1.0, 0.0) / c64::new(k - 10.0 * w * w, 10.0 * w)
}

#[test]
fn sdof_plot_and_table() {
    let dir = std::env::temp_dir().join(format!("romdyn-bode-{}", std::process::id()));
    // The grid includes the resonance 10 rad/s exactly.
    let mut freq = log_frequencies(0.1, 10.0, 200);
    freq.push(10.0 / (2.0 * std::f64::consts::PI));
    freq.sort_by(f64::total_cmp);
    let h = |k| freq.iter().map(|f| faer::Mat::from_fn(1, 1, |_, _| sdof(*f, k))).collect::<Vec<_>>();
    let (input, output) = (Port::from_label("f [N]"), Port::from_label("x [m]"));
    assert_eq!((input.unit.as_str(), output.unit.as_str()), ("N", "m"));
    let response = FrequencyResponse::new(freq.clone(), vec![input], vec![output], h(1000.0)).with_reduced("ROM", h(1010.0));
    let plot = BodePlot { title: "SDOF".into(), magnitude_unit: "m/N".into(), response: &response, curves: response_curves(&response, &[(0, 0)]) };
    let (svg, png, csv) = (dir.join("b.svg"), dir.join("b.png"), dir.join("b.csv"));
    write_bode(&plot, &svg, &png).unwrap();
    let png_bytes = std::fs::read(&png).unwrap();
    assert_eq!(&png_bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png_bytes.len() > 20_000);
    let svg_text = std::fs::read_to_string(&svg).unwrap();
    for text in ["frequency [Hz]", "phase [deg]", "dB re 1 m/N", "full model", "ROM", "x [m] / f [N]"] {
        assert!(svg_text.contains(text), "{text}");
    }
    write_response_csv(&response, &plot.curves, &csv).unwrap();
    let table = std::fs::read_to_string(&csv).unwrap();
    let mut rows = table.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    assert_eq!(header.len(), 9);
    assert_eq!(header[3], "full model: x [m] / f [N] mag");
    let at_resonance = rows
        .map(|r| r.split(',').map(|x| x.parse::<f64>().unwrap()).collect::<Vec<_>>())
        .find(|r| (r[0] * 2.0 * std::f64::consts::PI - 10.0).abs() < 1e-9)
        .unwrap();
    // |H(10 rad/s)| = 1/(r ω) = 0.01 m/N (closed form), 1e-9 relative; phase −90°.
    assert!((at_resonance[3] - 0.01).abs() < 1e-11, "{}", at_resonance[3]);
    assert!((at_resonance[4] + 90.0).abs() < 1e-6);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn undamped_sign_flips_unwrap_down_at_poles_and_up_at_zeros() {
    // Issue 9 point 4: an undamped response changes sign at each resonance (phase −180°,
    // |H| peaks) and antiresonance (+180°, |H| dips). H = (1 − (f/2)²) / ((1 − f²)(1 − (f/3)²)):
    // poles at 1 and 3, a zero at 2 (closed form): phase 0, −180, 0, −180.
    use romdyn::output::bode::unwrapped_phase_deg;
    let f = log_frequencies(0.1, 10.0, 301);
    let h: Vec<c64> = f.iter().map(|f| c64::new((1.0 - f * f / 4.0) / ((1.0 - f * f) * (1.0 - f * f / 9.0)), 0.0)).collect();
    let p = unwrapped_phase_deg(&h);
    for (f, p) in f.iter().zip(&p) {
        let expect = if *f < 1.0 || (2.0..3.0).contains(f) { 0.0 } else if *f < 2.0 || *f > 3.0 { -180.0 } else { unreachable!() };
        assert_eq!(*p, expect, "at {f} Hz");
    }
    // A real negative start is −180°, whatever the sign of a rounding imaginary part.
    assert_eq!(unwrapped_phase_deg(&[c64::new(-1.0, 0.0)]), vec![-180.0]);
    assert_eq!(unwrapped_phase_deg(&[c64::new(-1.0, -0.0)]), vec![-180.0]);
}

#[test]
fn line_plot_writes_svg_png_and_csv_and_refuses_an_empty_plot() {
    use romdyn::output::line_plot::{write_line_plot, write_series_csv, LinePlot, Series, SeriesStyle};
    let dir = std::env::temp_dir().join(format!("romdyn-line-{}", std::process::id()));
    let series = vec![Series { label: "y = x²".into(), points: (0..=10).map(|i| (i as f64, (i * i) as f64)).collect(), style: SeriesStyle::Markers }];
    let plot = LinePlot { title: "parabola".into(), x_label: "x [-]".into(), y_label: "y [-]".into(), series };
    let (svg, png, csv) = (dir.join("p.svg"), dir.join("p.png"), dir.join("p.csv"));
    write_line_plot(&plot, &svg, &png).unwrap();
    write_series_csv(&plot, &csv).unwrap();
    assert!(std::fs::read_to_string(&svg).unwrap().contains("parabola"));
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    let rows: Vec<String> = std::fs::read_to_string(&csv).unwrap().lines().map(String::from).collect();
    assert_eq!(rows.len(), 12);
    assert_eq!(rows[0], "series,x [-],y [-]");
    assert!(rows[11].ends_with(",1.000000000000e1,1.000000000000e2"), "{}", rows[11]);
    let empty = LinePlot { series: vec![], ..plot };
    assert!(write_line_plot(&empty, &dir.join("e.svg"), &dir.join("e.png")).is_err());
    std::fs::remove_dir_all(&dir).ok();
}
