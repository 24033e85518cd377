//! Frequency responses of linear models (issue 31 point 4): one type for every response
//! romdyn computes, plots, writes or hands to Python. The grid is held once, the transfer
//! matrix at each frequency is an array (outputs × inputs), and the ports are data (a name
//! and an SI unit), so nothing downstream regroups curves by their names or reads units
//! back out of them.

use faer::{c64, Mat};

/// Hertz to radians per second: `ω = 2π f`.
pub fn rad_per_s(freq_hz: f64) -> f64 {
    std::f64::consts::TAU * freq_hz
}

/// Radians per second to hertz: `f = ω / 2π`.
pub fn hz(omega: f64) -> f64 {
    omega / std::f64::consts::TAU
}

/// One input or output of a linear model: what it is and its SI unit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Port {
    /// "node 2 z", "cut genel 4 at node 7 (injected)".
    pub name: String,
    /// "m", "N", "rad/s", "Pa"; empty for a dimensionless port.
    pub unit: String,
}

impl Port {
    /// The port of a model's port label, `NAME [UNIT]` as `dae::ports` and the ROM files
    /// write it (a label without a bracketed unit is dimensionless). This is the one place
    /// a unit is read from a label: the linear model's labels enter here.
    pub fn from_label(label: &str) -> Port {
        match label.strip_suffix(']').and_then(|s| s.rsplit_once(" [")) {
            Some((name, unit)) if !unit.contains(['[', ']']) => Port { name: name.to_string(), unit: unit.to_string() },
            _ => Port { name: label.to_string(), unit: String::new() },
        }
    }

    /// The ports of a list of labels.
    pub fn from_labels(labels: &[String]) -> Vec<Port> {
        labels.iter().map(|l| Port::from_label(l)).collect()
    }

    /// `NAME [UNIT]`, the label the port came from.
    pub fn label(&self) -> String {
        if self.unit.is_empty() { self.name.clone() } else { format!("{} [{}]", self.name, self.unit) }
    }
}

/// A linear model's frequency response on a grid, `H(j 2π f) = C (j 2π f E − A)⁻¹ B` (eq. 96
/// for the full model), and the responses of reduced models on the same grid and ports.
#[derive(Clone, Debug)]
pub struct FrequencyResponse {
    /// The grid [Hz], increasing.
    pub freq_hz: Vec<f64>,
    /// The columns of each transfer matrix.
    pub inputs: Vec<Port>,
    /// The rows of each transfer matrix.
    pub outputs: Vec<Port>,
    /// The full model's transfer matrix at each frequency (outputs × inputs).
    pub full: Vec<Mat<c64>>,
    /// Reduced models' transfer matrices on the same grid, each with its label ("ROM").
    pub reduced: Vec<(String, Vec<Mat<c64>>)>,
}

impl FrequencyResponse {
    /// The full model's response `full` at `freq_hz` between `inputs` and `outputs`.
    pub fn new(freq_hz: Vec<f64>, inputs: Vec<Port>, outputs: Vec<Port>, full: Vec<Mat<c64>>) -> Self {
        FrequencyResponse { freq_hz, inputs, outputs, full, reduced: Vec::new() }
    }

    /// Adds a reduced model's response `h` on the same grid and ports, under `label`.
    pub fn with_reduced(mut self, label: &str, h: Vec<Mat<c64>>) -> Self {
        self.reduced.push((label.to_string(), h));
        self
    }

    /// The first reduced model's response ("the ROM" of a comparison); empty when none.
    pub fn rom(&self) -> &[Mat<c64>] {
        self.reduced.first().map_or(&[], |r| r.1.as_slice())
    }

    /// One channel's values over the grid: output `i` per input `j`.
    pub fn channel(h: &[Mat<c64>], i: usize, j: usize) -> Vec<c64> {
        h.iter().map(|m| m[(i, j)]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_port_label_round_trips_and_gives_its_unit() {
        for label in ["node 2 z [m]", "cut genel 4 at node 7 (injected) [N]", "abstract 3 [1]", "plain"] {
            assert_eq!(Port::from_label(label).label(), label);
        }
        let (u, z) = (Port::from_label("node 1 x [N]"), Port::from_label("node 2 z [m]"));
        assert_eq!((u.name.as_str(), u.unit.as_str(), z.unit.as_str()), ("node 1 x", "N", "m"));
        assert_eq!(Port::from_label("plain").unit, "");
        assert!((hz(rad_per_s(3.5)) - 3.5).abs() < 1e-15);
    }
}
