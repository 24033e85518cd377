//! The math parser's `model` namespace (MBDyn's modelns.cc; input manual, "General",
//! §Model namespace): functions of the structural nodes' state, `model::node::structural`
//! private data, and `model::drive(LABEL, x)`.
//!
//! When they are evaluated is the caller's business: while the file is read (`set:`,
//! `remark:`) they see the nodes as written so far; in a `string` drive during the run they
//! see the state being assembled (the current Newton iterate, as MBDyn's
//! `StructNode::GetXCurr`; see [`crate::element::drive::TimeFunction`]).

use std::collections::HashMap;

use crate::element::{Element, ElementState, Label, NodeKinematics};
use crate::kinematics::{rotation_vector, Vec3};

/// The structural nodes a `model::` function reads, by label.
pub trait NodeStates {
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics>;
}

/// An element's view of the model during the run.
pub struct Live<'s>(pub &'s dyn ElementState);

impl NodeStates for Live<'_> {
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
        self.0.structural_node(label)
    }
}

/// The nodes read so far (while the file is read).
impl NodeStates for HashMap<Label, NodeKinematics> {
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
        self.get(&label)
    }
}

/// What a `model::` call reads besides its arguments.
#[derive(Clone, Copy)]
pub enum Reads<'a> {
    /// The nodes' state.
    Nodes(&'a dyn NodeStates),
    /// A check while the file is read, before any state exists: the labels of the
    /// structural nodes the file declares (each read gives 0).
    Labels(&'a std::collections::HashSet<Label>),
}

/// What a state function computes from one node (`a`) or from two (`b − a`).
#[derive(Clone, Copy, PartialEq, Debug)]
enum Quantity {
    Position,
    Distance,
    UnitVector,
    Angle,
    RelativeAngle,
    Velocity,
    RelativeVelocity,
    AngularVelocity,
    RelativeAngularVelocity,
}

/// Which scalar of the vector: its norm, its squared norm, or a component.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Part {
    Norm,
    Square,
    Component(usize),
}

/// The state functions of modelns.cc (`ModelNameSpace::ModelNameSpace`): the stem, its
/// quantity, and whether it has the norm and squared-norm forms (`unitvec` has only the
/// components, `angle` no square).
const STEMS: [(&str, Quantity, bool, bool); 9] = [
    ("position", Quantity::Position, true, true),
    ("distance", Quantity::Distance, true, true),
    ("unitvec", Quantity::UnitVector, false, false),
    ("angle", Quantity::Angle, true, false),
    ("anglerel", Quantity::RelativeAngle, true, false),
    ("velocity", Quantity::Velocity, true, true),
    ("vrel", Quantity::RelativeVelocity, true, true),
    ("angvel", Quantity::AngularVelocity, true, true),
    ("angvrel", Quantity::RelativeAngularVelocity, true, true),
];

impl Quantity {
    fn two_nodes(self) -> bool {
        matches!(self, Quantity::Distance | Quantity::UnitVector | Quantity::RelativeAngle | Quantity::RelativeVelocity | Quantity::RelativeAngularVelocity)
    }
}

/// `name` as a state function: `[x|y|z]STEM[2]`.
fn parse(name: &str) -> Option<(Quantity, Part)> {
    let (part, rest) = match name.as_bytes().first() {
        Some(b'x') if name != "x" => (Part::Component(0), &name[1..]),
        Some(b'y') => (Part::Component(1), &name[1..]),
        Some(b'z') => (Part::Component(2), &name[1..]),
        _ => (Part::Norm, name),
    };
    for (stem, q, norm, square) in STEMS {
        if rest == stem && (norm || matches!(part, Part::Component(_))) {
            return Some((q, part));
        }
        if part == Part::Norm && square && rest.strip_suffix('2') == Some(stem) {
            return Some((q, Part::Square));
        }
    }
    None
}

/// Whether `name` is one of modelns.cc's functions of the previous step's state.
pub fn is_previous_step(name: &str) -> bool {
    name.strip_suffix("_prev").is_some_and(|n| parse(n).is_some())
}

/// Number of node labels `name` takes, if it is a state function.
pub fn arity(name: &str) -> Option<usize> {
    parse(name).map(|(q, _)| if q.two_nodes() { 2 } else { 1 })
}

/// A node label from a number of the expression.
fn label(x: f64, what: &str) -> Result<Label, String> {
    if x >= 0.0 && x.fract() == 0.0 && x <= Label::MAX as f64 {
        Ok(x as Label)
    } else {
        Err(format!("{what}: expected a node label (a non-negative integer), found {x}"))
    }
}

fn node<'r>(reads: &'r dyn NodeStates, l: Label, call: &str) -> Result<&'r NodeKinematics, String> {
    reads.structural_node(l).ok_or_else(|| format!("{call}: there is no structural node {l} (dummy nodes are not read; while the file is read, only the nodes above this statement are)"))
}

/// Evaluates the state function `name` on node labels `args`.
pub fn state_function(name: &str, args: &[f64], reads: Reads) -> Result<f64, String> {
    let Some((q, part)) = parse(name) else { return Err(format!("model::{name} is not a function of MBDyn's model namespace")) };
    let call = format!("model::{name}({})", args.iter().map(|a| a.to_string()).collect::<Vec<_>>().join(", "));
    let labels = args.iter().map(|&a| label(a, &call)).collect::<Result<Vec<_>, _>>()?;
    let reads = match reads {
        Reads::Labels(known) => {
            if let Some(l) = labels.iter().find(|l| !known.contains(l)) {
                return Err(format!("{call}: the file declares no structural node {l} (dummy nodes are not read)"));
            }
            return Ok(0.0);
        }
        Reads::Nodes(n) => n,
    };
    let a = node(reads, labels[0], &call)?;
    let b = if q.two_nodes() { Some(node(reads, labels[1], &call)?) } else { None };
    let v: Vec3 = match (q, b) {
        (Quantity::Position, _) => a.x,
        (Quantity::Velocity, _) => a.xdot,
        (Quantity::AngularVelocity, _) => a.omega,
        (Quantity::Angle, _) => rotation_vector(&a.r),
        (Quantity::Distance | Quantity::UnitVector, Some(b)) => b.x - a.x,
        (Quantity::RelativeAngle, Some(b)) => rotation_vector(&(a.r.transpose() * b.r)),
        (Quantity::RelativeVelocity, Some(b)) => b.xdot - a.xdot,
        (Quantity::RelativeAngularVelocity, Some(b)) => b.omega - a.omega,
        _ => unreachable!("two-node quantities have two nodes"),
    };
    if q == Quantity::UnitVector {
        let d = v.norm();
        if d <= f64::EPSILON {
            return Err(format!("{call}: null distance"));
        }
        let Part::Component(k) = part else { unreachable!("unitvec has components only") };
        return Ok(v[k] / d);
    }
    Ok(match part {
        Part::Norm => v.norm(),
        Part::Square => v.norm_squared(),
        Part::Component(k) => v[k],
    })
}

/// `model::node::structural(LABEL, "NAME[i]")`: a structural node's private data
/// (strnode.cc, `StructNode::iGetPrivDataIdx`, `dGetPrivData`): `X` position, `x` its
/// components in the node frame, `Phi` rotation vector, `XP` velocity, `xP` in the node
/// frame, `Omega` angular velocity, `omega` in the node frame; i = 1, 2, 3.
pub fn node_private_data(label_arg: f64, data: &str, reads: Reads) -> Result<f64, String> {
    let call = format!("model::node::structural({label_arg}, \"{data}\")");
    let l = label(label_arg, &call)?;
    let parsed = data.strip_suffix(']').and_then(|d| d.split_once('[')).and_then(|(name, i)| Some((name, i.parse::<usize>().ok().filter(|i| (1..=3).contains(i))?)));
    const NAMES: [&str; 7] = ["X", "x", "Phi", "XP", "xP", "Omega", "omega"];
    let Some((name, i)) = parsed.filter(|(n, _)| NAMES.contains(n)) else {
        return Err(format!("{call}: romdyn reads the private data {} with an index 1 to 3 (Euler angles, Euler parameters and accelerations are not supported)", NAMES.map(|n| format!("\"{n}[i]\"")).join(", ")));
    };
    let reads = match reads {
        Reads::Labels(known) if known.contains(&l) => return Ok(0.0),
        Reads::Labels(_) => return Err(format!("{call}: the file declares no structural node {l} (dummy nodes are not read)")),
        Reads::Nodes(n) => n,
    };
    let n = node(reads, l, &call)?;
    let v = match name {
        "X" => n.x,
        "x" => n.r.transpose() * n.x,
        "Phi" => rotation_vector(&n.r),
        "XP" => n.xdot,
        "xP" => n.r.transpose() * n.xdot,
        "Omega" => n.omega,
        _ => n.r.transpose() * n.omega,
    };
    Ok(v[i - 1])
}

/// The elements read so far, by label space (`elements::label_space`) and label: the
/// element, or why romdyn could not read it while reading the file.
pub type ElementsRead = HashMap<(&'static str, Label), Result<Box<dyn Element>, String>>;

/// The model's state while the file is read: the nodes as written, time 0 and no gravity
/// (MBDyn links the gravity element to the bodies once it has read every element).
struct AsWritten<'r> {
    nodes: &'r dyn NodeStates,
    none: NodeKinematics,
}

impl ElementState for AsWritten<'_> {
    fn node(&self, _slot: usize) -> &NodeKinematics {
        &self.none
    }
    fn multiplier(&self, _k: usize) -> f64 {
        0.0
    }
    fn time(&self) -> f64 {
        0.0
    }
    fn gravity(&self) -> Vec3 {
        Vec3::zeros()
    }
    fn load_factor(&self) -> f64 {
        1.0
    }
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
        self.nodes.structural_node(label)
    }
}

/// `model::element::TYPE(LABEL, "NAME")` while the file is read (modelns.cc, `model_elem`:
/// `Elem::dGetPrivData` of the element `LABEL` read above): the private data romdyn
/// computes ([`crate::element::private_data`], a body's "E", "V", "m") at the nodes as
/// written.
pub fn element_private_data(kind: &str, label_arg: f64, data: &str, elements: &ElementsRead, reads: Reads) -> Result<f64, String> {
    let call = format!("model::element::{kind}({label_arg}, \"{data}\")");
    let (space, l) = element_key(kind, label_arg, &call)?;
    let element = match elements.get(&(space, l)) {
        None => return Err(format!("{call}: there is no {space} {l} above this statement (MBDyn: \"unable to find\")")),
        Some(Err(why)) => return Err(format!("{call}: romdyn could not read {space} {l} while reading the file: {why}")),
        Some(Ok(e)) => e,
    };
    let Some(datum) = element.outputs().and_then(|o| o.private_data(data)) else {
        return Err(format!("{call}: romdyn does not compute the private data \"{data}\" of {} {l} (it computes a body's \"E\", \"V\", \"m\", a revolute hinge's \"rz\", \"wz\", a total joint's \"px\" … \"wz\")", element.type_name()));
    };
    let nodes = match reads {
        Reads::Nodes(n) => n,
        Reads::Labels(_) => return Ok(0.0),
    };
    let none = NodeKinematics { x: Vec3::zeros(), r: crate::kinematics::Mat3::identity(), xdot: Vec3::zeros(), omega: Vec3::zeros() };
    datum.value(&AsWritten { nodes, none }).ok_or_else(|| format!("{call}: a node of {space} {l} is not among the nodes read"))
}

/// The label space (`elements::label_space`) and label `model::element::KIND(LABEL, …)`
/// names; `call` is the call as written, for messages.
pub fn element_key(kind: &str, label_arg: f64, call: &str) -> Result<(&'static str, Label), String> {
    let l = label(label_arg, call).map_err(|m| m.replace("node label", "element label"))?;
    let space = match kind {
        "body" => "body",
        "joint" => "joint",
        "force" | "couple" => "force",
        "beam" => "beam",
        _ => return Err(format!("{call}: romdyn reads the private data of bodies and joints (element types body, joint, force, couple, beam)")),
    };
    Ok((space, l))
}

/// `model::drive(LABEL, x)`: the `drive caller:` card `LABEL` at `x` (modelns.cc,
/// `DriveCaller::dGet(x)`), reading the same state.
pub fn drive(table: &super::card_tables::DrivesBefore, label_arg: f64, x: f64, reads: Reads, state: Option<&dyn ElementState>) -> Result<f64, String> {
    let call = format!("model::drive({label_arg}, {x})");
    let l = label(label_arg, &call)?;
    let Some(d) = table.get(l) else { return Err(format!("{call}: drive caller {l} is not defined before this expression")) };
    Ok(match reads {
        Reads::Labels(_) => 0.0,
        Reads::Nodes(_) => d.value_at(x, state),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Mat3;

    fn kin(x: [f64; 3], v: [f64; 3], w: [f64; 3]) -> NodeKinematics {
        NodeKinematics { x: Vec3::from(x), r: Mat3::identity(), xdot: Vec3::from(v), omega: Vec3::from(w) }
    }

    #[test]
    fn names_follow_modelns() {
        assert_eq!(parse("xposition"), Some((Quantity::Position, Part::Component(0))));
        assert_eq!(parse("distance2"), Some((Quantity::Distance, Part::Square)));
        assert_eq!(parse("zunitvec"), Some((Quantity::UnitVector, Part::Component(2))));
        assert_eq!(parse("unitvec"), None);
        assert_eq!(parse("angle2"), None);
        assert_eq!(parse("angvrel2"), Some((Quantity::RelativeAngularVelocity, Part::Square)));
        assert!(is_previous_step("xvelocity_prev") && !is_previous_step("velocity"));
        assert_eq!((arity("vrel"), arity("angvel"), arity("current")), (Some(2), Some(1), None));
    }

    /// The values of MBDyn's own test `tests/namespaces/model` (node 1 at the origin, node 2
    /// at (1, 2, 3)): its remarks expect position 3.74166, position2 14, distance 3.74166.
    #[test]
    fn state_functions_give_the_values_of_mbdyns_test() -> Result<(), String> {
        let nodes: HashMap<Label, NodeKinematics> = [(1, kin([0.0; 3], [0.0; 3], [0.0; 3])), (2, kin([1.0, 2.0, 3.0], [0.5, 0.0, 0.0], [0.0, 0.0, 2.0]))].into();
        let r = Reads::Nodes(&nodes);
        assert!((state_function("position", &[2.0], r)? - 14f64.sqrt()).abs() < 1e-15);
        assert_eq!(state_function("position2", &[2.0], r)?, 14.0);
        assert_eq!(state_function("ydistance", &[1.0, 2.0], r)?, 2.0);
        assert!((state_function("zunitvec", &[1.0, 2.0], r)? - 3.0 / 14f64.sqrt()).abs() < 1e-15);
        assert_eq!(state_function("xvelocity", &[2.0], r)?, 0.5);
        assert_eq!(state_function("angvrel", &[1.0, 2.0], r)?, 2.0);
        assert_eq!(node_private_data(2.0, "X[3]", r)?, 3.0);
        assert!(matches!(state_function("position", &[7.0], r), Err(e) if e.contains("no structural node 7")));
        assert!(matches!(state_function("zunitvec", &[1.0, 1.0], r), Err(e) if e.contains("null distance")));
        assert!(node_private_data(2.0, "E[1]", r).is_err());
        Ok(())
    }
}
