//! The `drivers` block's file drivers (input manual, "Drivers", §File Drivers; MBDyn's
//! fixedstep.cc, `FixedStepDR::Read` and the `FixedStepFileDrive` constructor):
//!
//! `file: LABEL, fixed step, {STEPS | count}, CHANNELS, [initial time,] {T0 | from file},
//! [time step,] {DT | from file}, [interpolation, {linear | const},] [pad zeros, {yes | no}
//! | bailout, none,] "FILE";`
//!
//! FILE (relative to the folder of the input file that names it) holds one row per step,
//! CHANNELS numbers each, after optional leading `#` lines (which give `initial time: T0`
//! and `time step: DT` when the card says `from file`). `count` takes every row. The
//! `file, LABEL [, CHANNEL] [, amplitude, A]` drive caller reads a channel. `variable step`,
//! `socket`, `stream` and the other drivers, and a `bailout` that ends the run, are refused
//! by name.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::{MbdynError, Span};
use crate::mbdyn::syntax::parser::Statement;
use crate::mbdyn::syntax::diagnostic;
use crate::mbdyn::syntax::parser;

/// A fixed step file driver: its channels' samples, read from the data file.
#[derive(Clone, Debug)]
pub struct FixedStepDriver {
    pub t0: f64,
    pub dt: f64,
    /// `channels[i][k]`: channel `i + 1` at `t0 + k dt`.
    pub channels: Vec<Arc<Vec<f64>>>,
    pub linear: bool,
    pub pad_zeros: bool,
    /// The statement's position in the input (drive callers use drivers read before them).
    pub seq: usize,
    pub span: Span,
}

/// The file drivers of the `drivers` block, by label.
pub type FileDrivers = HashMap<u32, FixedStepDriver>;

/// Drivers MBDyn knows that romdyn does not read.
const REFUSED: [&str; 5] = ["variable step", "socket", "stream", "rtai input", "socket stream"];

/// Reads one `file: …;` statement of the `drivers` block.
pub fn file_driver(st: &Statement, c: &mut Cursor, drivers: &mut FileDrivers) -> Result<(), MbdynError> {
    let span = c.here();
    let label = c.label("file driver label")?;
    if let Some(prev) = drivers.get(&label) {
        return Err(c.error_at(span, format!("file driver {label} is defined twice (first at line {})", prev.span.line)));
    }
    if let Some(kind) = c.accept_any(&REFUSED) {
        return Err(c.error(format!("{} (supported: fixed step)", diagnostic::mbdyn_runs_it(&format!("a '{kind}' file driver")))));
    }
    c.keyword("the file driver type", &["fixed step"])?;
    let steps_span = c.here();
    let steps = if c.accept("count") {
        None
    } else {
        let n = c.count("number of steps (or count)")?;
        if n == 0 {
            return Err(c.error_at(steps_span, "fixed step: the number of steps must be positive"));
        }
        Some(n)
    };
    let channels_span = c.here();
    let channels = c.count("number of channels")?;
    if channels == 0 {
        return Err(c.error_at(channels_span, "fixed step: the number of channels must be positive"));
    }
    c.accept("initial time");
    let t0 = if c.accept("from file") { None } else { Some(c.real("initial time [s]")?) };
    c.accept("time step");
    let dt_span = c.here();
    let dt = if c.accept("from file") {
        None
    } else {
        let dt = c.real("time step [s]")?;
        if dt <= 0.0 {
            return Err(c.error_at(dt_span, format!("fixed step: the time step must be positive, found {dt}")));
        }
        Some(dt)
    };
    let linear = if c.accept("interpolation") { c.keyword("the interpolation", &["linear", "const"])? == "linear" } else { true };
    // fixedstep.cc: `pad zeros` or `bailout`, not both; padding with zeros is the default.
    let mut pad_zeros = true;
    if c.accept("pad zeros") || c.accept("pad zeroes") {
        pad_zeros = c.flag("pad zeros")?;
    } else if c.accept("bailout") {
        let at = c.here();
        if c.keyword("the bailout", &["none", "upper", "lower", "any"])? != "none" {
            return Err(c.error_at(at, "a file driver's bailout ends the run when the time leaves the file's range; romdyn does not support it (MBDyn 1.7.3 does) (write 'bailout, none' or set the final time)"));
        }
    }
    let file_span = c.here();
    let name = c.string("the data file name")?;
    c.finish()?;
    let path = data_path(c, file_span, &name);
    let text = crate::text_file::read_text_file(&path).map_err(|e| c.error_at(file_span, format!("file driver {label}: cannot read the data file \"{}\": {}", path.display(), e.message)))?;
    let data = Samples::parse(&text, steps, channels, t0, dt).map_err(|m| c.error_at(file_span, format!("file driver {label}: data file \"{}\": {m}", path.display())))?;
    drivers.insert(label, FixedStepDriver { t0: data.t0, dt: data.dt, channels: data.channels.into_iter().map(Arc::new).collect(), linear, pad_zeros, seq: st.seq, span });
    Ok(())
}

/// The data file's path: as written when absolute, else relative to the folder of the input
/// file that names it.
pub(in crate::mbdyn) fn data_path(c: &Cursor, at: Span, name: &str) -> std::path::PathBuf {
    let p = Path::new(name);
    if p.is_absolute() {
        return p.to_path_buf();
    }
    let input = c.source_path(at);
    input.and_then(|f| f.parent().map(|d| d.join(p))).unwrap_or_else(|| p.to_path_buf())
}

struct Samples {
    t0: f64,
    dt: f64,
    channels: Vec<Vec<f64>>,
}

impl Samples {
    /// The rows after the leading `#` lines; `steps` rows (every row for `None`), each of
    /// `channels` numbers. Blank lines are skipped.
    fn parse(text: &str, steps: Option<usize>, channels: usize, t0: Option<f64>, dt: Option<f64>) -> Result<Samples, String> {
        let mut lines = text.lines().enumerate().peekable();
        let (mut t0, mut dt) = (t0, dt);
        while let Some((k, line)) = lines.next_if(|(_, l)| l.starts_with('#')) {
            let body = line.trim_start_matches('#').trim();
            let header = |key: &str| body.get(..key.len()).filter(|h| h.eq_ignore_ascii_case(key)).map(|_| body[key.len()..].trim());
            if t0.is_none()
                && let Some(v) = header("initial time:")
            {
                t0 = Some(v.parse().map_err(|_| format!("line {}: cannot read the initial time \"{v}\"", k + 1))?);
            }
            if dt.is_none()
                && let Some(v) = header("time step:")
            {
                let d: f64 = v.parse().map_err(|_| format!("line {}: cannot read the time step \"{v}\"", k + 1))?;
                if !(d > 0.0) {
                    return Err(format!("line {}: the time step must be positive, found {d}", k + 1));
                }
                dt = Some(d);
            }
        }
        let t0 = t0.ok_or("expected an \"# initial time: T0\" line before the data (the card says 'from file')")?;
        let dt = dt.ok_or("expected a \"# time step: DT\" line before the data (the card says 'from file')")?;
        // Allocated once the first row has shown the channels the card declares.
        let mut out: Vec<Vec<f64>> = Vec::new();
        let mut rows = 0;
        for (k, line) in lines {
            if steps == Some(rows) {
                break;
            }
            if line.trim().is_empty() {
                continue;
            }
            let values: Vec<&str> = line.split_whitespace().collect();
            if values.len() != channels {
                return Err(format!("line {}: expected {channels} number(s) (one per channel), found {}", k + 1, values.len()));
            }
            if out.is_empty() {
                out = vec![Vec::new(); channels];
            }
            for (ch, v) in out.iter_mut().zip(values) {
                ch.push(v.parse().map_err(|_| format!("line {}: \"{v}\" is not a number", k + 1))?);
            }
            rows += 1;
        }
        if rows == 0 || steps.is_some_and(|n| rows < n) {
            return Err(format!("expected {} row(s) of data, found {rows}", steps.map_or("at least one".to_string(), |n| n.to_string())));
        }
        Ok(Samples { t0, dt, channels: out })
    }
}

/// `file, LABEL [, CHANNEL] [, amplitude, A]` (drive_.cc, `FileDCR::Read`): a channel of a
/// file driver read before the drive caller.
pub fn file_drive(c: &mut Cursor, drivers: &FileDrivers, seq: usize) -> Result<crate::element::drive::Drive, MbdynError> {
    let span = c.here();
    let label = c.label("file driver label")?;
    let Some(d) = drivers.get(&label).filter(|d| d.seq < seq) else {
        return Err(c.error_at(span, format!("file driver {label} is not defined in a drivers block before this drive caller")));
    };
    let mut channel = 1;
    if c.next_is_number() {
        let at = c.here();
        channel = c.count("channel")?;
        if channel < 1 || channel > d.channels.len() {
            return Err(c.error_at(at, format!("file driver {label} has channels 1 to {}, found {channel}", d.channels.len())));
        }
    } else if c.peek_keyword().is_some_and(|k| parser::same_keyword(k, "amplitude")) {
        // drive_.cc reads a channel number whenever an argument follows the label.
        return Err(c.error("expected the channel number before 'amplitude' (MBDyn reads a channel whenever an argument follows the driver's label)"));
    }
    let amplitude = if c.accept("amplitude") { c.real("amplitude")? } else { 1.0 };
    Ok(crate::element::drive::Drive::Sampled(crate::element::drive::SampledChannel { t0: d.t0, dt: d.dt, values: d.channels[channel - 1].clone(), linear: d.linear, pad_zeros: d.pad_zeros, amplitude }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_rows_follow_fixedstep_cc() -> Result<(), String> {
        let s = Samples::parse("# initial time: 0.5\n# time step: 0.1\n1 2\n3 4\n\n5 6\n", None, 2, None, None)?;
        assert_eq!((s.t0, s.dt, s.channels.clone()), (0.5, 0.1, vec![vec![1.0, 3.0, 5.0], vec![2.0, 4.0, 6.0]]));
        let s = Samples::parse("1\n2\n3\n", Some(2), 1, Some(0.0), Some(1.0))?;
        assert_eq!(s.channels, vec![vec![1.0, 2.0]]);
        assert!(matches!(Samples::parse("1 2\n3\n", None, 2, Some(0.0), Some(1.0)), Err(e) if e.contains("line 2: expected 2 number(s)")));
        assert!(matches!(Samples::parse("1\n", Some(3), 1, Some(0.0), Some(1.0)), Err(e) if e.contains("expected 3 row(s)")));
        assert!(matches!(Samples::parse("1\n", None, 1, None, Some(1.0)), Err(e) if e.contains("initial time")));
        Ok(())
    }
}
