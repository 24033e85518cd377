//! A measured frequency response (`--measured FILE.csv`, the paper's Fig. 11: a
//! transmissibility measured with geophones). Format, comma separated, `#` starts a comment
//! line:
//!
//! ```text
//! frequency [Hz],1/1 re [m/N],1/1 im [m/N],2/1 mag [m/N],2/1 phase [deg]
//! 1.0,2.1e-5,-1.0e-8,3.0e-6,-179.5
//! ```
//!
//! The first column is the frequency [Hz], increasing and positive; then per channel two
//! columns, `O/I re` and `O/I im`, or `O/I mag` and `O/I phase` (phase in `[deg]` or
//! `[rad]`), `O` and `I` the 1-based output and input of the ROM, the unit in brackets
//! (the response's, e.g. `m/N`; it must be the ROM channel's output unit over its input unit).

use std::path::{Path, PathBuf};

use faer::c64;

/// A malformed measurement file: `FILE:LINE:COLUMN: message`.
#[derive(Debug, thiserror::Error)]
pub enum MeasuredError {
    #[error("{}: {cause}", path.display())]
    Read { path: PathBuf, cause: std::io::Error },
    #[error("{}:{line}:{column}: {message}", path.display())]
    At { path: PathBuf, line: usize, column: usize, message: String },
}

/// One channel: output `output` over input `input` (0-based).
#[derive(Clone, Debug)]
pub struct MeasuredChannel {
    pub name: String,
    pub output: usize,
    pub input: usize,
    /// The unit in the header, e.g. "m/N".
    pub unit: String,
    pub values: Vec<c64>,
}

#[derive(Clone, Debug)]
pub struct MeasuredResponse {
    pub path: PathBuf,
    pub freq_hz: Vec<f64>,
    pub channels: Vec<MeasuredChannel>,
}

/// A column header `NAME KIND [UNIT]`.
fn header(cell: &str) -> Option<(String, String, String)> {
    let (head, unit) = cell.trim().split_once('[')?;
    let unit = unit.strip_suffix(']')?.trim().to_string();
    let mut words = head.split_whitespace();
    let name = words.next()?.to_string();
    let kind = words.next()?.to_ascii_lowercase();
    words.next().is_none().then_some((name, kind, unit))
}

/// Reads a measured response, refusing a malformed file with its line and column.
pub fn read_measured(path: &Path) -> Result<MeasuredResponse, MeasuredError> {
    let text = std::fs::read_to_string(path).map_err(|e| MeasuredError::Read { path: path.to_path_buf(), cause: e })?;
    let at = |line: usize, column: usize, message: String| MeasuredError::At { path: path.to_path_buf(), line, column, message };
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((hl, head)) = lines.next() else { return Err(at(1, 1, "no header line: expected 'frequency [Hz],O/I re [UNIT],O/I im [UNIT],...'".into())) };
    // Byte column (1-based) of each cell.
    let cells = |l: &str| -> Vec<(usize, String)> {
        let mut col = 1;
        l.split(',').map(|c| {
            let start = col;
            col += c.len() + 1;
            (start, c.to_string())
        }).collect()
    };
    let head = cells(head);
    if head.first().and_then(|(_, c)| header(&format!("{} x [{}", c.split('[').next().unwrap_or("").trim(), c.split_once('[').map_or("", |x| x.1)))).is_none_or(|(n, _, u)| !n.eq_ignore_ascii_case("frequency") || u != "Hz") {
        return Err(at(hl + 1, 1, format!("the first column must be 'frequency [Hz]', got '{}'", head[0].1.trim())));
    }
    if head.len() < 3 || (head.len() - 1) % 2 != 0 {
        return Err(at(hl + 1, head.last().map_or(1, |c| c.0), format!("{} columns: expected the frequency, then two columns per channel (re, im or mag, phase)", head.len())));
    }
    let mut channels = Vec::new();
    let mut polar = Vec::new();
    for pair in head[1..].chunks(2) {
        let bad = |(col, cell): &(usize, String), expected: &str| at(hl + 1, *col, format!("'{}': expected {expected}", cell.trim()));
        let (name, kind, unit) = header(&pair[0].1).ok_or_else(|| bad(&pair[0], "'O/I re [UNIT]' or 'O/I mag [UNIT]'"))?;
        let (name2, kind2, unit2) = header(&pair[1].1).ok_or_else(|| bad(&pair[1], "'O/I im [UNIT]' or 'O/I phase [deg|rad]'"))?;
        let (o, i) = name.split_once('/').and_then(|(o, i)| Some((o.parse::<usize>().ok()?, i.parse::<usize>().ok()?))).filter(|(o, i)| *o > 0 && *i > 0).ok_or_else(|| bad(&pair[0], "a channel 'O/I' with 1-based output and input numbers, e.g. 1/1"))?;
        let phase_scale = match (kind.as_str(), kind2.as_str(), unit2.as_str()) {
            ("re", "im", _) if unit2 == unit => None,
            ("mag", "phase", "deg") => Some(std::f64::consts::PI / 180.0),
            ("mag", "phase", "rad") => Some(1.0),
            _ => return Err(bad(&pair[1], &format!("'{name} im [{unit}]' after '{name} re', or '{name} phase [deg|rad]' after '{name} mag'"))),
        };
        if name2 != name {
            return Err(bad(&pair[1], &format!("the second column of channel {name}")));
        }
        polar.push(phase_scale);
        channels.push(MeasuredChannel { name, output: o - 1, input: i - 1, unit, values: Vec::new() });
    }
    let mut freq_hz: Vec<f64> = Vec::new();
    for (l, line) in lines {
        let row = cells(line);
        if row.len() != head.len() {
            return Err(at(l + 1, row.last().map_or(1, |c| c.0), format!("{} columns, the header has {}", row.len(), head.len())));
        }
        let nums = row.iter().map(|(col, c)| c.trim().parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| at(l + 1, *col, format!("'{}' is not a finite number", c.trim())))).collect::<Result<Vec<_>, _>>()?;
        if !(nums[0] > 0.0) || freq_hz.last().is_some_and(|f| nums[0] <= *f) {
            return Err(at(l + 1, 1, format!("frequency {} Hz: frequencies must be positive and increasing", nums[0])));
        }
        freq_hz.push(nums[0]);
        for (k, ch) in channels.iter_mut().enumerate() {
            let (a, b) = (nums[1 + 2 * k], nums[2 + 2 * k]);
            ch.values.push(match polar[k] {
                None => c64::new(a, b),
                Some(s) => c64::from_polar(a, b * s),
            });
        }
    }
    if freq_hz.is_empty() {
        return Err(at(hl + 1, 1, "no data line after the header".into()));
    }
    Ok(MeasuredResponse { path: path.to_path_buf(), freq_hz, channels })
}
