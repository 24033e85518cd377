//! The ports file (JSON): named inputs and outputs at points of nodes, names of nodes, dummy
//! springs to remove and an imposed motion (paper §8). Syntax and type errors carry the
//! file's line and column (serde_json); a port that does not fit its type names its list,
//! index and name.
//!
//! ```json
//! {
//!   "names": { "1": "base", "2": "spring box", "3": "table" },
//!   "inputs": [
//!     "3:Fz",
//!     { "name": "H1", "type": "actuator", "from": 1, "to": 2, "at": [0.55, 0, 0.5], "direction": [0, 1, 0] },
//!     { "name": "F", "type": "force", "node": 3, "offset": [0.5, 0, 0], "direction": [0, 0, 1], "frame": "node" },
//!     { "name": "M", "type": "moment", "node": 3, "direction": [0, 1, 0] }
//!   ],
//!   "outputs": [
//!     { "name": "L1", "type": "relative", "from": 1, "to": 2, "at": [0.55, 0, 0.5], "direction": [0, 1, 0] },
//!     { "name": "G1", "type": "velocity", "node": 3, "at": [0.9, 0, 1], "direction": [1, 0, 0] },
//!     { "type": "displacement", "node": 3, "direction": [0, 0, 1] }, { "type": "rotation", "node": 3, "direction": [0, 1, 0] },
//!     { "type": "angular velocity", "node": 3, "direction": [0, 0, 1] }
//!   ],
//!   "remove_springs": [901, 902],
//!   "imposed": "1:x,y,z",
//!   "cut": ["genel:4"]
//! }
//! ```
//!
//! Modal coordinates (issue 35): `{ "type": "modal coordinate", "joint": 200, "mode": 1 }` is
//! modal joint 200's `q` of mode 1 (its number in the FEM file), `"modal coordinate rate"`
//! its `q̇`; the shorthand `"200:q1"`, `"200:q1_rate"`. A FEM node of modal joint 200 (a
//! sensor on the flexible body): `{ "type": "fem displacement", "joint": 200, "fem_node":
//! "17", "direction": [0, 1, 0] }` (`"fem velocity"` its velocity; `"frame": "node"` the
//! floating frame's axes).
//! Cuts (issue 34): `"cut"` lists control loops to cut open, `"genel:LABEL"` or
//! `"force:LABEL"` (an abstract force), as `--cut` ([`crate::dae::Cut`]).
//! Scalar nodes (issue 34): `{ "name": "disturbance", "type": "abstract", "node": 1 }` as an
//! input adds it to the node's equation, as an output is its value (`"abstract rate"`: its
//! derivative); likewise `"electric"`, `"hydraulic"`; the shorthand `"1:abstract"`.
//! A point is `"offset"` (node frame) or `"at"` (global position at the reference); pairs take
//! `"at"` (one point, as a collocated actuator or sensor) or `"from_offset"`/`"to_offset"`.
//! `"frame"` is `"global"` (default) or `"node"` (the `from` node's for pairs).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::Deserialize;

use crate::dae::ports::{Direction, Excitation, Frame, InputPort, Location, Measurement, OutputPort, Point};
use crate::dae::{Cut, NodeInput, NodeOutput};
use crate::kinematics::Vec3;
use crate::model::{Label, ScalarNodeId, ScalarNodeKind};

/// What a ports file describes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PortsFile {
    pub inputs: Vec<InputPort>,
    pub outputs: Vec<OutputPort>,
    /// Names of nodes (bodies), for mode labels and reports.
    pub names: BTreeMap<Label, String>,
    pub remove_springs: Vec<Label>,
    /// `NODE[:COMPONENTS]`.
    pub imposed: Option<String>,
    /// Control loops cut open (`"cut": ["genel:4"]`).
    pub cuts: Vec<Cut>,
}

/// Why a ports file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum PortsFileError {
    #[error(transparent)]
    Read(#[from] super::text_file::TextFileError),
    #[error("{}:{line}:{column}: error: {message}", path.display())]
    Syntax { path: PathBuf, line: usize, column: usize, message: String },
    #[error("{}: {list}[{index}] ({name}): {message}", path.display())]
    Port { path: PathBuf, list: &'static str, index: usize, name: String, message: String },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Document {
    #[serde(default)]
    names: BTreeMap<String, String>,
    #[serde(default)]
    inputs: Vec<Entry>,
    #[serde(default)]
    outputs: Vec<Entry>,
    #[serde(default)]
    remove_springs: Vec<Label>,
    #[serde(default)]
    imposed: Option<String>,
    #[serde(default)]
    cut: Vec<String>,
}

/// `"NODE:COMP"` or a full port.
enum Entry {
    Short(String),
    Full(Spec),
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct Spec {
    name: Option<String>,
    #[serde(rename = "type")]
    kind: String,
    node: Option<Label>,
    from: Option<Label>,
    to: Option<Label>,
    offset: Option<[f64; 3]>,
    at: Option<[f64; 3]>,
    from_offset: Option<[f64; 3]>,
    to_offset: Option<[f64; 3]>,
    direction: Option<[f64; 3]>,
    frame: Option<FrameName>,
    fem_node: Option<String>,
    /// A modal joint's label and a mode's number in its FEM file (modal coordinates).
    joint: Option<Label>,
    mode: Option<usize>,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(rename_all = "lowercase")]
enum FrameName {
    Global,
    Node,
}

impl<'de> Deserialize<'de> for Entry {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Entry;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("\"NODE:COMPONENT\" or a port object {\"type\": …}")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Entry, E> {
                Ok(Entry::Short(s.to_string()))
            }
            fn visit_map<M: MapAccess<'de>>(self, m: M) -> Result<Entry, M::Error> {
                Spec::deserialize(de::value::MapAccessDeserializer::new(m)).map(Entry::Full)
            }
        }
        d.deserialize_any(V)
    }
}

fn vec3(v: [f64; 3]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

impl Spec {
    fn direction(&self) -> Result<Direction, String> {
        let v = self.direction.ok_or("needs \"direction\": [x, y, z]")?;
        Ok(Direction { vector: vec3(v), frame: if matches!(self.frame, Some(FrameName::Node)) { Frame::Node } else { Frame::Global } })
    }
    fn node(&self) -> Result<Label, String> {
        if self.from.is_some() || self.to.is_some() {
            return Err(format!("a '{}' port acts on one node: give \"node\", not \"from\"/\"to\"", self.kind));
        }
        self.node.ok_or_else(|| format!("a '{}' port needs \"node\"", self.kind))
    }
    fn point(&self) -> Result<Point, String> {
        let node = self.node()?;
        let location = match (self.offset, self.at) {
            (Some(_), Some(_)) => return Err("give \"offset\" or \"at\", not both".into()),
            (Some(o), None) => Location::Offset(vec3(o)),
            (None, Some(a)) => Location::At(vec3(a)),
            (None, None) => Location::Offset(Vec3::zeros()),
        };
        Ok(Point { node, location })
    }
    fn pair(&self) -> Result<(Point, Point), String> {
        let (Some(from), Some(to)) = (self.from, self.to) else {
            return Err(format!("a '{}' port needs \"from\" and \"to\" nodes", self.kind));
        };
        if self.node.is_some() || self.offset.is_some() {
            return Err("pairs take \"from\"/\"to\" with \"at\" or \"from_offset\"/\"to_offset\"".into());
        }
        if from == to {
            let instead = if self.kind == "actuator" { "a 'force' or a 'moment' input on the node" } else { "a 'displacement' output of the node" };
            return Err(format!("a '{}' port acts between two nodes, \"from\" and \"to\" are both node {from} (for one node use {instead})", self.kind));
        }
        let side = |node, off: Option<[f64; 3]>| match (self.at, off) {
            (Some(_), Some(_)) => Err("give \"at\" or the offsets, not both".to_string()),
            (Some(a), None) => Ok(Point { node, location: Location::At(vec3(a)) }),
            (None, o) => Ok(Point { node, location: Location::Offset(o.map(vec3).unwrap_or_else(Vec3::zeros)) }),
        };
        Ok((side(from, self.from_offset)?, side(to, self.to_offset)?))
    }
    fn no_point(&self) -> Result<(), String> {
        if self.offset.is_some() || self.at.is_some() {
            return Err(format!("a '{}' port has no point (\"offset\", \"at\")", self.kind));
        }
        Ok(())
    }
    /// The scalar node of a port whose type is a scalar node kind ("abstract", "electric",
    /// "hydraulic", with " rate" for an output's derivative).
    fn scalar(&self) -> Result<ScalarNodeId, String> {
        self.no_point()?;
        if self.direction.is_some() {
            return Err(format!("a '{}' port has no direction", self.kind));
        }
        let kind = match self.kind.trim_end_matches(" rate") {
            "electric" => ScalarNodeKind::Electric,
            "hydraulic" => ScalarNodeKind::Hydraulic,
            _ => ScalarNodeKind::Abstract,
        };
        Ok(ScalarNodeId { kind, label: self.node()? })
    }
    /// The joint and mode of a modal coordinate output (`"joint"`, `"mode"`, nothing else).
    fn modal(&self) -> Result<(Label, usize), String> {
        if self.node.is_some() || self.from.is_some() || self.to.is_some() || self.direction.is_some() {
            return Err(format!("a '{}' port takes \"joint\" (a modal joint's label) and \"mode\" (a mode's number in its FEM file), no node or direction", self.kind));
        }
        self.no_point()?;
        let joint = self.joint.ok_or_else(|| format!("a '{}' port needs \"joint\": the modal joint's label", self.kind))?;
        let mode = self.mode.filter(|m| *m >= 1).ok_or_else(|| format!("a '{}' port needs \"mode\": a mode's number in the FEM file (from 1)", self.kind))?;
        Ok((joint, mode))
    }
    /// The joint and FEM node of a FEM node output (`"joint"`, `"fem_node"`, `"direction"`,
    /// `"frame"`).
    fn fem_node(&self) -> Result<(Label, String), String> {
        if self.node.is_some() || self.from.is_some() || self.to.is_some() || self.mode.is_some() {
            return Err(format!("a '{}' port takes \"joint\" (a modal joint's label), \"fem_node\" (a node label of its FEM file) and \"direction\", no node or mode", self.kind));
        }
        self.no_point()?;
        let joint = self.joint.ok_or_else(|| format!("a '{}' port needs \"joint\": the modal joint's label", self.kind))?;
        let fem_node = self.fem_node.clone().ok_or_else(|| format!("a '{}' port needs \"fem_node\": a node label of the joint's FEM file", self.kind))?;
        Ok((joint, fem_node))
    }
    fn input(&self, index: usize) -> Result<InputPort, String> {
        if self.fem_node.is_some() {
            return Err("\"fem_node\" belongs to 'fem displacement', 'fem velocity' and 'fem rotation' outputs".into());
        }
        if self.joint.is_some() || self.mode.is_some() {
            return Err("\"joint\" and \"mode\" belong to 'modal coordinate' outputs".into());
        }
        let excitation = match self.kind.as_str() {
            "abstract" | "electric" | "hydraulic" => Excitation::Scalar { node: self.scalar()? },
            "force" => Excitation::Force { point: self.point()?, direction: self.direction()? },
            "moment" => {
                self.no_point()?;
                Excitation::Moment { node: self.node()?, direction: self.direction()? }
            }
            "actuator" => {
                let (from, to) = self.pair()?;
                Excitation::Actuator { from, to, direction: self.direction()? }
            }
            k => return Err(format!("input type '{k}' is not one of force, moment, actuator, abstract, electric, hydraulic")),
        };
        Ok(InputPort { name: self.name.clone().unwrap_or_else(|| format!("input {}", index + 1)), excitation })
    }
    fn output(&self, index: usize) -> Result<OutputPort, String> {
        let measurement = match self.kind.as_str() {
            "abstract" | "electric" | "hydraulic" => Measurement::ScalarValue { node: self.scalar()? },
            "abstract rate" | "electric rate" | "hydraulic rate" => Measurement::ScalarRate { node: self.scalar()? },
            "displacement" => Measurement::Displacement { point: self.point()?, direction: self.direction()? },
            "velocity" => Measurement::Velocity { point: self.point()?, direction: self.direction()? },
            "rotation" => {
                self.no_point()?;
                Measurement::Rotation { node: self.node()?, direction: self.direction()? }
            }
            "angular velocity" => {
                self.no_point()?;
                Measurement::AngularVelocity { node: self.node()?, direction: self.direction()? }
            }
            "relative" => {
                let (from, to) = self.pair()?;
                Measurement::Relative { from, to, direction: self.direction()? }
            }
            "modal coordinate" => {
                let (joint, mode) = self.modal()?;
                Measurement::ModalCoordinate { joint, mode }
            }
            "modal coordinate rate" => {
                let (joint, mode) = self.modal()?;
                Measurement::ModalRate { joint, mode }
            }
            "fem displacement" => {
                let (joint, fem_node) = self.fem_node()?;
                Measurement::FemDisplacement { joint, fem_node, direction: self.direction()? }
            }
            "fem velocity" => {
                let (joint, fem_node) = self.fem_node()?;
                Measurement::FemVelocity { joint, fem_node, direction: self.direction()? }
            }
            "fem rotation" => {
                let (joint, fem_node) = self.fem_node()?;
                Measurement::FemRotation { joint, fem_node, direction: self.direction()? }
            }
            k => return Err(format!("output type '{k}' is not one of displacement, rotation, relative, velocity, angular velocity, abstract, electric, hydraulic (and their 'rate'), modal coordinate, modal coordinate rate, fem displacement, fem velocity, fem rotation")),
        };
        if self.fem_node.is_some() && !self.kind.starts_with("fem ") {
            return Err("\"fem_node\" belongs to 'fem displacement', 'fem velocity' and 'fem rotation' outputs".into());
        }
        if (self.joint.is_some() || self.mode.is_some()) && !self.kind.starts_with("modal coordinate") && !self.kind.starts_with("fem ") {
            return Err("\"joint\" and \"mode\" belong to 'modal coordinate' outputs".into());
        }
        Ok(OutputPort { name: self.name.clone().unwrap_or_else(|| format!("output {}", index + 1)), measurement })
    }
}

/// Parses a ports file's text (`path` names it in errors).
pub fn parse_ports(text: &str, path: &Path) -> Result<PortsFile, PortsFileError> {
    let doc: Document = serde_json::from_str(text).map_err(|e| PortsFileError::Syntax { path: path.to_path_buf(), line: e.line(), column: e.column(), message: e.to_string() })?;
    let port_err = |list, index, name: &str, message: String| PortsFileError::Port { path: path.to_path_buf(), list, index, name: name.to_string(), message };
    let mut out = PortsFile { remove_springs: doc.remove_springs, imposed: doc.imposed, ..Default::default() };
    for (k, v) in doc.names {
        let label: Label = k.trim().parse().map_err(|_| port_err("names", 0, &k, "keys are node labels (non-negative integers)".into()))?;
        out.names.insert(label, v);
    }
    for (i, c) in doc.cut.iter().enumerate() {
        out.cuts.push(c.parse().map_err(|m| port_err("cut", i, c, m))?);
    }
    for (i, e) in doc.inputs.iter().enumerate() {
        out.inputs.push(match e {
            Entry::Short(s) => s.parse::<NodeInput>().map(|p| p.port()).map_err(|err| port_err("inputs", i, s, err.to_string()))?,
            Entry::Full(spec) => spec.input(i).map_err(|m| port_err("inputs", i, spec.name.as_deref().unwrap_or("unnamed"), m))?,
        });
    }
    for (i, e) in doc.outputs.iter().enumerate() {
        out.outputs.push(match e {
            Entry::Short(s) => s.parse::<NodeOutput>().map(|p| p.port()).map_err(|err| port_err("outputs", i, s, err.to_string()))?,
            Entry::Full(spec) => spec.output(i).map_err(|m| port_err("outputs", i, spec.name.as_deref().unwrap_or("unnamed"), m))?,
        });
    }
    Ok(out)
}

/// Reads a ports file (a regular UTF-8 file, see [`super::text_file`]; at most 16 MiB).
pub fn read_ports_file(path: &Path) -> Result<PortsFile, PortsFileError> {
    if let Some(len) = std::fs::metadata(path).ok().map(|m| m.len()).filter(|len| *len > 16 << 20) {
        return Err(PortsFileError::Syntax { path: path.to_path_buf(), line: 0, column: 0, message: format!("{len} bytes: a ports file is at most 16 MiB") });
    }
    let text = super::text_file::read_text_file(path)?;
    parse_ports(&text, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shorthand_and_full_ports_parse() -> Result<(), PortsFileError> {
        let text = r#"{"names": {"3": "table"}, "inputs": ["3:Fz", {"name": "A", "type": "actuator", "from": 1, "to": 2, "at": [1, 0, 0], "direction": [0, 1, 0]}],
            "outputs": [{"name": "G", "type": "velocity", "node": 3, "offset": [0.5, 0, 0], "direction": [1, 0, 0], "frame": "node"}], "remove_springs": [9], "imposed": "1:x", "cut": ["genel:4", "force:2"]}"#;
        let p = parse_ports(text, Path::new("p.json"))?;
        assert_eq!(p.inputs.len(), 2);
        assert_eq!(p.inputs[0].label(), "node 3 Fz [N]");
        assert_eq!(p.outputs[0].label(), "G [m/s]");
        assert_eq!(p.names[&3], "table");
        assert_eq!(p.remove_springs, vec![9]);
        assert_eq!(p.cuts.iter().map(|c| c.to_string()).collect::<Vec<_>>(), ["genel:4", "force:2"]);
        Ok(())
    }

    #[test]
    fn errors_name_line_column_or_the_port() {
        let e = parse_ports("{\"inputs\": [\n  {\"type\": \"force\", \"nod\": 3}]}", Path::new("p.json")).unwrap_err().to_string();
        assert!(e.starts_with("p.json:2:"), "{e}");
        assert!(e.contains("unknown field `nod`"), "{e}");
        let e = parse_ports(r#"{"outputs": [{"name": "L", "type": "relative", "node": 2, "direction": [1, 0, 0]}]}"#, Path::new("p.json")).unwrap_err().to_string();
        assert_eq!(e, "p.json: outputs[0] (L): a 'relative' port needs \"from\" and \"to\" nodes");
        let e = parse_ports(r#"{"inputs": ["3:Fw"]}"#, Path::new("p.json")).unwrap_err().to_string();
        assert!(e.contains("inputs[0] (3:Fw)"), "{e}");
        let e = parse_ports(r#"{"cut": ["genel:4", "joint:3"]}"#, Path::new("p.json")).unwrap_err().to_string();
        assert_eq!(e, "p.json: cut[1] (joint:3): 'joint:3': expected genel:LABEL or force:LABEL (a genel or an abstract force of the model)");
    }
}
