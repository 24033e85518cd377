//! MBDyn input constructs, each read from text and checked against the MBDyn input manual:
//! the math parser, `set:`, `include:`, reference frames, orientation and matrix forms,
//! the initial value and control data blocks, and every element romdyn reads (their
//! residual compared with the same model built through the Rust API from the manual's
//! formulas, at pseudo-random states).

use crate::common;

use common::mbdyn::{assert_same_physics, file, read, variables};

use romdyn::dae::{Assembler, State};
use romdyn::element::drive::Drive;
use romdyn::element::{Anchor, Couple, DrivenJoint, DeformableDisplacement, DeformableHinge, Force, ForceFrame, Joint, LinearViscoelastic, RigidBody, Rod};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::model::ConstraintForm;
use romdyn::model::{AbortAfter, Method, ModelBuilder};

fn rz(a: f64) -> Mat3 {
    *nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), a).matrix()
}

fn node_anchor(label: u32, offset: Vec3, orientation: Mat3) -> Anchor {
    Anchor::Node { label, offset, orientation }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * (1.0 + b.abs())
}

// ---------------------------------------------------------------- the math parser

#[test]
fn integer_and_real_arithmetic_follow_mbdyn_typing() {
    // Manual, §Variables: "1/3 returns 0 because both values are implicit integers"; a
    // value assigned to a typed variable is cast to its type.
    // `-2^2` is 4: MBDyn 1.7.3 applies the unary minus to its operand first (see
    // `operators_bind_as_mbdyn_evaluates_them`).
    let v = variables("set: integer a = 1/3; set: real b = 1/3; set: real c = 1./3; set: integer d = 7/2.; set: real e2 = 2^3^2; set: real f = -2^2; set: integer g = 17 % 5; set: real h = 1 + 2.5;");
    let r = |n| v.real(n).unwrap();
    assert_eq!((r("a"), r("b"), r("d"), r("e2"), r("f"), r("g"), r("h")), (0.0, 0.0, 3.0, 512.0, 4.0, 2.0, 3.5));
    assert!(close(r("c"), 1.0 / 3.0));
}

#[test]
fn comparisons_and_logic_follow_the_operator_table() {
    let v = variables("set: bool a = 1 < 2 && !(3 == 4); set: bool b = 1 > 2 || 2 >= 2; set: bool c = 1 ~| 1; set: integer d = (2 != 2) + (3 <= 3); set: bool e3 = !1 > 2;");
    let r = |n| v.real(n).unwrap();
    // `!` binds to its operand, as MBDyn 1.7.3 evaluates it: !1 > 2 = (!1) > 2 = 0.
    assert_eq!((r("a"), r("b"), r("c"), r("d"), r("e3")), (1.0, 1.0, 0.0, 1.0, 0.0));
}

/// What MBDyn 1.7.3 prints for each `remark:` of a file of these expressions (built from the
/// mirror's 1727489e, `mbdyn -f`; its manual's operator table puts `^` above unary minus and
/// `!` below the comparisons, but libmbutil/mathp.cc evaluates otherwise, and romdyn gives
/// MBDyn's numbers): exact.
#[test]
fn operators_bind_as_mbdyn_evaluates_them() {
    let cases: [(&str, f64); 17] = [
        ("-2^2", 4.0),
        ("(-2)^2", 4.0),
        ("3-2^2", -1.0),
        ("2^-1", 0.0),
        ("3*-2^2", 12.0),
        ("2^3^2", 512.0),
        ("-2.^2.", 4.0),
        ("!1 > 2", 0.0),
        ("1 || 0 && 0", 0.0),
        ("1 ~| 1 || 1", 1.0),
        ("0 && 0 || 1", 1.0),
        ("1^-1", 0.0),
        ("2.^-1", 0.5),
        ("-sqrt(4.)^2", 4.0),
        ("7 % 2^2", 3.0),
        ("2^0", 1.0),
        ("0^0", 1.0),
    ];
    for (k, (expr, mbdyn)) in cases.iter().enumerate() {
        let v = variables(&format!("set: real x{k} = {expr};"));
        assert_eq!(v.real(&format!("x{k}")).unwrap(), *mbdyn, "{expr}");
    }
    // MBDyn refuses a negative base with an exponent <= 0 ("invalid operands in power()").
    for expr in ["(-2)^0", "(-2.)^-1"] {
        let text = format!("begin: data; problem: initial value; end: data;\nset: real x = {expr};\n");
        let e = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("p.mbd")).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(e.contains("p.mbd:2:") && e.contains("invalid operands in power()"), "{expr}: {e}");
    }
}

#[test]
fn builtin_functions_match_their_definitions() {
    let text = "set: real x01 = sin(0.3) + cos(0.3) + tan(0.3); set: real x02 = asin(0.3) + acos(0.3) + atan(0.3); set: real x03 = atan2(1., 2.);
        set: real x04 = sqrt(2.) * exp(0.5) * log(3.) * log10(7.); set: real x05 = abs(-2.5) + sinh(0.3) + cosh(0.3) + tanh(0.3);
        set: real x06 = asinh(0.3) + acosh(1.5) + atanh(0.3); set: integer x07 = ceil(2.1) + floor(-2.1) + round(2.5) + sign(-3.);
        set: real x08 = min(2., 3.) + max(2., 3.) + copysign(2., -1.); set: real x09 = actan(2.) + actan2(2., 3.) + ctan(0.4) + ctanh(0.4) + actanh(2.);
        set: real x10 = step(-1.) + step(0.) + step(2.) + ramp(-1.) + ramp(2.) + sramp(3., 2.) + sramp(1., 2.) + par(3.) + par(-3.);
        set: bool x11 = in_ee(1., 1., 2.) && in_el(1., 1., 2.) && !in_le(1., 1., 2.) && in_ll(1., 1.5, 2.);
        set: real x12 = default::sqrt(4.) + real(3) + integer(2.7);";
    let v = variables(text);
    let r = |n| v.real(n).unwrap();
    let want = [
        ("x01", 0.3f64.sin() + 0.3f64.cos() + 0.3f64.tan()),
        ("x02", 0.3f64.asin() + 0.3f64.acos() + 0.3f64.atan()),
        ("x03", 1f64.atan2(2.0)),
        ("x04", 2f64.sqrt() * 0.5f64.exp() * 3f64.ln() * 7f64.log10()),
        ("x05", 2.5 + 0.3f64.sinh() + 0.3f64.cosh() + 0.3f64.tanh()),
        ("x06", 0.3f64.asinh() + 1.5f64.acosh() + 0.3f64.atanh()),
        ("x07", 3.0 - 3.0 + 3.0 - 1.0),
        ("x08", 2.0 + 3.0 - 2.0),
        // actan(x) = atan2(1, x), actan2(a, b) = atan2(b, a), ctan = 1/tan, ctanh = 1/tanh,
        // actanh(x) = atanh(1/x) (MBDyn's math parser).
        ("x09", 1f64.atan2(2.0) + 3f64.atan2(2.0) + 1.0 / 0.4f64.tan() + 1.0 / 0.4f64.tanh() + 0.5f64.atanh()),
        // step: 0, 1/2, 1; ramp: 0, x; sramp(x, a): x clipped to [0, a]; par: x² for x > 0.
        ("x10", 0.0 + 0.5 + 1.0 + 0.0 + 2.0 + 2.0 + 1.0 + 9.0 + 0.0),
        ("x11", 1.0),
        ("x12", 2.0 + 3.0 + 2.0),
    ];
    for (name, value) in want {
        assert!(close(r(name), value), "{name} = {}, want {value}", r(name));
    }
}

#[test]
fn predefined_constants_have_the_manual_values() {
    let v = variables("set: real a = pi + e; set: real b = deg2rad * 180.; set: real c = in2m * m2in + ft2m * m2ft + lb2kg * kg2lb + slug2kg * kg2slug + in2mm * mm2in; set: real d = rad2deg; set: integer f = INT_MAX; set: bool g = TRUE && !FALSE;");
    let r = |n| v.real(n).unwrap();
    assert!(close(r("a"), std::f64::consts::PI + std::f64::consts::E));
    assert!(close(r("b"), std::f64::consts::PI));
    assert!(close(r("c"), 5.0) && close(r("d"), 180.0 / std::f64::consts::PI));
    assert_eq!((r("f"), r("g")), (2147483647.0, 1.0));
}

#[test]
fn set_declares_assigns_and_evaluates_statement_lists() {
    let text = "set: real a; set: ifndef real a = 3.; set: a = 2.; set: ifndef integer n = 4;
        set: (real EA = 1e6; real GA = EA/2.; 0);
        set: integer k = (integer i = 3; i * 2) + 1;
        set: string s = \"ab\" + \"cd\";
        begin: data; problem: initial value; end: data;";
    let v = variables(text);
    assert_eq!((v.real("a"), v.real("n"), v.real("EA"), v.real("GA"), v.real("k"), v.real("i")), (Some(2.0), Some(4.0), Some(1e6), Some(5e5), Some(7.0), Some(3.0)));
    assert_eq!(v.get("s").map(|x| x.value.clone()), Some(romdyn::input::mbdyn::TypedValue::Str("abcd".into())));
}

#[test]
fn values_are_taken_when_read_not_at_the_end() {
    // The second node sees L after the re-assignment, the first before it.
    let m = read(&file(
        "structural nodes: 2;",
        "set: real L = 1.; structural: 1, static, L, 0., 0., eye, null, null; set: L = 2.; structural: 2, static, L, 0., 0., eye, null, null;",
        "",
    ));
    assert_eq!((m.model.nodes[0].position.x, m.model.nodes[1].position.x), (1.0, 2.0));
}

#[test]
fn comments_keywords_and_empty_fields() {
    let text = "# a comment\nbegin: Data; /* a comment\n over two lines */ problem: initial value; end: data;
        begin: CONTROLDATA; structural nodes: 1; end: control data;
        begin: nodes; structural: 1, static, , 2., , eye, default, null; end: nodes;";
    let m = read(text);
    // Keywords ignore case and spaces (manual, §Keywords); an empty field is zero (§Variables).
    assert_eq!(m.model.nodes[0].position, Vec3::new(0.0, 2.0, 0.0));
}

#[test]
fn include_reads_the_file_where_it_stands() {
    let dir = std::env::temp_dir().join(format!("romdyn_include_{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(dir.join("sub/params.mbd"), "set: const real L = 2.5; # from the included file\n").unwrap();
    std::fs::write(dir.join("main.mbd"), file("structural nodes: 1;", "include: \"sub/params.mbd\"; structural: 1, static, L, 0., 0., eye, null, null;", "")).unwrap();
    let m = romdyn::input::mbdyn::read_model(&dir.join("main.mbd")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(m.model.nodes[0].position.x, 2.5);
    std::fs::remove_dir_all(&dir).ok();
}

// ---------------------------------------------------------------- frames and orientations

#[test]
fn reference_frames_compose_positions_velocities_and_orientations() {
    // Manual, §Use of Reference Frames: w = R_R w_in + Ω_R, v = R_R v_in + V_R + Ω_R × (R_R x_in).
    let m = read(&file(
        "structural nodes: 2;",
        "reference: 1, reference, global, 1., 2., 3., reference, global, euler123, 0., 0., pi/2, reference, global, 0.1, 0., 0., reference, global, 0., 0., 2.;
         reference: 2, reference, 1, 0., 1., 0., reference, 1, eye, reference, 1, null, reference, 1, null;
         structural: 1, dynamic, reference, 1, 1., 0., 0., reference, 1, eye, reference, 1, 0., 1., 0., reference, 1, 0., 0., 1.;
         structural: 2, dynamic, at reference, 2;",
        "",
    ));
    let (a, b) = (&m.model.nodes[0], &m.model.nodes[1]);
    let near = |x: Vec3, y: Vec3| (x - y).norm() < 1e-14;
    assert!(near(a.position, Vec3::new(1.0, 3.0, 3.0)), "{}", a.position);
    assert!(near(a.velocity, Vec3::new(-2.9, 0.0, 0.0)), "{}", a.velocity);
    assert!(near(a.angular_velocity, Vec3::new(0.0, 0.0, 3.0)));
    assert!((a.orientation - rz(std::f64::consts::FRAC_PI_2)).norm() < 1e-14);
    assert!(near(b.position, Vec3::new(0.0, 2.0, 3.0)) && near(b.velocity, Vec3::new(0.1, -2.0, 0.0)) && near(b.angular_velocity, Vec3::new(0.0, 0.0, 2.0)));
}

#[test]
fn denavit_hartenberg_reference() {
    // Manual, §Reference: x = x_old + R_old (d e3 + exp(θ e3×) a e1), R = R_old exp(θ e3×) exp(α e1×).
    let m = read(&file("structural nodes: 1;", "reference: 1, Denavit Hartenberg, 0.5, pi/2, 2., pi/2; structural: 1, static, at reference, 1;", ""));
    let n = &m.model.nodes[0];
    assert!((n.position - Vec3::new(0.0, 2.0, 0.5)).norm() < 1e-14, "{}", n.position);
    // Axis 3 of the new frame: e3 turned by α about the new x (= global y), i.e. −x... : R e3.
    let e3 = n.orientation * Vec3::z();
    assert!((e3 - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-14, "{e3}");
}

fn orientation_of(text: &str) -> Mat3 {
    read(&file("structural nodes: 1;", &format!("structural: 1, static, null, {text}, null, null;"), "")).model.nodes[0].orientation
}

#[test]
fn euler_angles_follow_mbdyn_sequences_in_radians_or_degrees() {
    let (a, b, c) = (0.3f64, -0.4f64, 1.1f64);
    let (ca, sa, cb, sb, cc, sc) = (a.cos(), a.sin(), b.cos(), b.sin(), c.cos(), c.sin());
    // MBDyn's EulerAngles123_2MatR, EulerAngles313_2MatR, EulerAngles321_2MatR (rows).
    let r123 = Mat3::new(cb * cc, -cb * sc, sb, ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb, sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb);
    let r313 = Mat3::new(ca * cc - sa * cb * sc, -ca * sc - sa * cb * cc, sa * sb, sa * cc + ca * cb * sc, -sa * sc + ca * cb * cc, -ca * sb, sb * sc, sb * cc, cb);
    let r321 = Mat3::new(ca * cb, -sa * cc + ca * sb * sc, sa * sc + ca * sb * cc, sa * cb, ca * cc + sa * sb * sc, -ca * sc + sa * sb * cc, -sb, cb * sc, cb * cc);
    for (kw, want) in [("euler123", r123), ("euler", r123), ("euler313", r313), ("euler321", r321), ("euler 321", r321)] {
        let got = orientation_of(&format!("{kw}, {a}, {b}, {c}"));
        assert!((got - want).norm() < 1e-14, "{kw}: {got} want {want}");
        let d = 180.0 / std::f64::consts::PI;
        let got = orientation_of(&format!("{kw}, degrees, {}, {}, {}", a * d, b * d, c * d));
        assert!((got - want).norm() < 1e-13, "{kw} in degrees");
    }
}

#[test]
fn orientation_vector_matr_and_eye() {
    assert!((orientation_of("vector, 0., 0., pi/2") - rz(std::f64::consts::FRAC_PI_2)).norm() < 1e-15);
    assert!((orientation_of("matr, 0., -1., 0., 1., 0., 0., 0., 0., 1.") - rz(std::f64::consts::FRAC_PI_2)).norm() < 1e-15);
    assert_eq!(orientation_of("eye"), Mat3::identity());
    // The nearest rotation to a matrix written with 5 digits.
    let m = orientation_of("matr, 0.70711, -0.70711, 0., 0.70711, 0.70711, 0., 0., 0., 1.");
    assert!((m - rz(std::f64::consts::FRAC_PI_4)).norm() < 1e-12, "{m}");
}

#[test]
fn two_vector_orientations_for_every_axis_pair() {
    // Manual, §Orientation Matrix: axis i along v_i; the third axis normal to v_i and v_j;
    // axis j completes a right-handed frame, on v_j's side of axis i.
    let (vi, vj) = (Vec3::new(1.0, 2.0, -0.5), Vec3::new(-0.3, 0.4, 2.0));
    for (i, j) in [(1, 2), (2, 1), (1, 3), (3, 1), (2, 3), (3, 2)] {
        let r = orientation_of(&format!("{i}, {}, {}, {}, {j}, {}, {}, {}", vi.x, vi.y, vi.z, vj.x, vj.y, vj.z));
        assert!((r.transpose() * r - Mat3::identity()).norm() < 1e-14 && (r.determinant() - 1.0).abs() < 1e-14, "({i}, {j}) not a rotation");
        let (ei, ej) = (r.column(i - 1).into_owned(), r.column(j - 1).into_owned());
        assert!((ei - vi.normalize()).norm() < 1e-14, "({i}, {j}): axis {i}");
        let k = 6 - i - j;
        assert!(r.column(k - 1).dot(&vj).abs() < 1e-14 && ej.dot(&vj) > 0.0, "({i}, {j}): axis {j}");
    }
    // guess: any axis orthogonal to v_1.
    let r = orientation_of("1, 0., 0., 2., 2, guess");
    assert!((r.column(0) - Vec3::z()).norm() < 1e-15 && (r.transpose() * r - Mat3::identity()).norm() < 1e-15);
}

#[test]
fn vectors_scale_and_matrices_in_all_forms() {
    let m = read(&file(
        "structural nodes: 1; rigid bodies: 5;",
        "structural: 1, dynamic, 1., 2., 3., scale, 2., eye, null, null;",
        "body: 1, 1, 1., null, sym, 1., 0.1, 0.2, 2., 0.3, 3.;
         body: 2, 1, 1., null, diag, 1., 2., 3., scale, 2.;
         body: 3, 1, 1., null, matr, 1., 0., 0., 0., 2., 0., 0., 0., 3.;
         body: 4, 1, 1., null, 1., 0., 0., 0., 2., 0., 0., 0., 3.;
         body: 5, 1, 1., null, eye;",
    ));
    assert_eq!(m.model.nodes[0].position, Vec3::new(2.0, 4.0, 6.0));
    let j = |d: [f64; 3]| Mat3::from_diagonal(&Vec3::from(d));
    let mut b = ModelBuilder::new();
    b.dynamic_node(1, Vec3::new(2.0, 4.0, 6.0), Mat3::identity(), Vec3::zeros(), Vec3::zeros());
    b.element(RigidBody::new(1, 1, 1.0, Vec3::zeros(), Mat3::new(1.0, 0.1, 0.2, 0.1, 2.0, 0.3, 0.2, 0.3, 3.0)));
    b.element(RigidBody::new(2, 1, 1.0, Vec3::zeros(), j([2.0, 4.0, 6.0])));
    b.element(RigidBody::new(3, 1, 1.0, Vec3::zeros(), j([1.0, 2.0, 3.0])));
    b.element(RigidBody::new(4, 1, 1.0, Vec3::zeros(), j([1.0, 2.0, 3.0])));
    b.element(RigidBody::new(5, 1, 1.0, Vec3::zeros(), Mat3::identity()));
    assert_same_physics(&file("structural nodes: 1; rigid bodies: 5;", "structural: 1, dynamic, 1., 2., 3., scale, 2., eye, null, null;", "body: 1, 1, 1., null, sym, 1., 0.1, 0.2, 2., 0.3, 3.; body: 2, 1, 1., null, diag, 1., 2., 3., scale, 2.; body: 3, 1, 1., null, matr, 1., 0., 0., 0., 2., 0., 0., 0., 3.; body: 4, 1, 1., null, 1., 0., 0., 0., 2., 0., 0., 0., 3.; body: 5, 1, 1., null, eye;"), b.build().unwrap());
}

// ---------------------------------------------------------------- elements

/// Node 1 static at the origin, node 2 dynamic at (1, 0.5, 0) turned 90° about z, node 3
/// dynamic at (0, 2, 0.5).
const NODES: &str = "structural: 1, static, null, eye, null, null;
    structural: 2, dynamic, 1., 0.5, 0., euler123, 0., 0., pi/2, null, null;
    structural: 3, dynamic, 0., 2., 0.5, eye, null, null;";

fn nodes(b: &mut ModelBuilder) {
    b.static_node(1, Vec3::zeros(), Mat3::identity());
    b.dynamic_node(2, Vec3::new(1.0, 0.5, 0.0), rz(std::f64::consts::FRAC_PI_2), Vec3::zeros(), Vec3::zeros());
    b.dynamic_node(3, Vec3::new(0.0, 2.0, 0.5), Mat3::identity(), Vec3::zeros(), Vec3::zeros());
}

#[test]
fn bodies_with_offsets_orientation_and_condense() {
    let text = file(
        "structural nodes: 3; rigid bodies: 3;",
        NODES,
        "body: 1, 2, 2., reference, node, 0.1, 0., 0., diag, 1., 2., 3., orientation, euler123, 0., 0., pi/2;
         body: 2, 2, 3., reference, global, 1., 1.5, 0., diag, 1., 1., 1.;
         body: 3, 3, condense, 2, 1., 0., 0., 0.5, diag, 0.1, 0.1, 0.1, 3., 0., 0., -0.5, diag, 0.2, 0.2, 0.2;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    // Inertia rotated by the orientation: R J Rᵀ with R = Rz(90°) swaps J_xx and J_yy.
    b.element(RigidBody::new(1, 2, 2.0, Vec3::new(0.1, 0.0, 0.0), Mat3::from_diagonal(&Vec3::new(2.0, 1.0, 3.0))));
    // A global point seen from node 2: R₂ᵀ ((1, 1.5, 0) − (1, 0.5, 0)) = (1, 0, 0).
    b.element(RigidBody::new(2, 2, 3.0, Vec3::new(1.0, 0.0, 0.0), Mat3::identity()));
    // Lumped: m = 4, centre of mass at z = (0.5 − 1.5)/4 = −0.25; J = Σ J_i + m_i d_i² (x, y).
    let (d1, d2) = (0.75f64, 0.25f64);
    let jxy = 0.1 + 0.2 + 1.0 * d1 * d1 + 3.0 * d2 * d2;
    b.element(RigidBody::new(3, 3, 4.0, Vec3::new(0.0, 0.0, -0.25), Mat3::from_diagonal(&Vec3::new(jxy, jxy, 0.3))));
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn clamp_revolute_spherical_joints_and_pins() {
    let text = file(
        "structural nodes: 3; joints: 6;",
        NODES,
        "joint: 1, clamp, 1, node, node;
         joint: 2, revolute hinge, 1, position, 1., 0.5, 0., orientation, eye, 2, position, reference, other position, null, orientation, reference, other orientation, eye;
         joint: 3, spherical hinge, 2, position, reference, global, 0., 2., 0.5, 3, null;
         joint: 4, revolute pin, 3, position, null, orientation, eye, position, 0., 2., 0.5, orientation, eye, initial theta, 0.;
         joint: 5, spherical pin, 3, position, null, position, reference, global, 0., 2., 0.5;
         joint: 6, plane hinge, 1, null, 3, reference, other node, null;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    let r2t = rz(std::f64::consts::FRAC_PI_2).transpose();
    b.element(Joint::clamp(1, 1, Vec3::zeros(), Mat3::identity()));
    b.element(Joint::revolute_hinge(2, node_anchor(1, Vec3::new(1.0, 0.5, 0.0), Mat3::identity()), node_anchor(2, Vec3::zeros(), r2t)));
    b.element(Joint::spherical_hinge(3, node_anchor(2, r2t * Vec3::new(-1.0, 1.5, 0.5), Mat3::identity()), node_anchor(3, Vec3::zeros(), Mat3::identity())));
    b.element(Joint::revolute_hinge(4, Anchor::Ground { position: Vec3::new(0.0, 2.0, 0.5), orientation: Mat3::identity() }, node_anchor(3, Vec3::zeros(), Mat3::identity())));
    b.element(Joint::spherical_hinge(5, Anchor::Ground { position: Vec3::new(0.0, 2.0, 0.5), orientation: Mat3::identity() }, node_anchor(3, Vec3::zeros(), Mat3::identity())));
    b.element(Joint::revolute_hinge(6, node_anchor(1, Vec3::zeros(), Mat3::identity()), node_anchor(3, Vec3::new(0.0, -2.0, -0.5), Mat3::identity())));
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn total_joint_and_total_pin_joint() {
    let text = file(
        "structural nodes: 3; joints: 2;",
        NODES,
        "joint: 1, total joint,
            2, position, reference, global, 0., 2., 0.5, position orientation, reference, global, eye, rotation orientation, reference, global, eye,
            3, position, null, rotation orientation, eye,
            position constraint, active, inactive, 1, null,
            orientation constraint, rotation, active, inactive, null;
         joint: 2, total pin joint,
            3, position, 0., 0., 0.1,
            position, reference, global, 0., 2., 0.5,
            position constraint, active, active, active, single, 0., 0., 0.1, const, 1.;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    let r2t = rz(std::f64::consts::FRAC_PI_2).transpose();
    // Two rotations locked, not three: MBDyn's rows with the remnant of the free one (zero
    // before the first convergence).
    let mut j1 = DrivenJoint::new(Joint::total(1, node_anchor(2, r2t * Vec3::new(-1.0, 1.5, 0.5), r2t), node_anchor(3, Vec3::zeros(), Mat3::identity()), [true, false, true], [true, true, false]), "total joint");
    j1.rotation_remnant = true;
    b.element(j1);
    // The node's point is imposed 0.1 above the fixed point (0, 2, 0.5): the fixed point
    // moves to (0, 2, 0.6), where the node's point (0, 2, 0.5) + 0.1 z is.
    b.element(Joint::total(2, Anchor::Ground { position: Vec3::new(0.0, 2.0, 0.6), orientation: Mat3::identity() }, node_anchor(3, Vec3::new(0.0, 0.0, 0.1), Mat3::identity()), [true; 3], [false; 3]));
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn deformable_joints_with_their_laws() {
    let text = file(
        "structural nodes: 3; joints: 6;",
        NODES,
        "constitutive law: 7, name, \"law\", 3, linear viscoelastic isotropic, 10., proportional, 0.1;
         joint: 1, deformable displacement joint, 1, position, 1., 0.5, 0., 2, position, null, linear elastic, 100.;
         joint: 2, deformable displacement joint, 1, null, 3, null, linear elastic generic, sym, 1., 0.1, 0.2, 2., 0.3, 3., prestrain, single, 0., 0., 0.1, const, 1.;
         joint: 3, deformable displacement hinge, 2, null, orientation, eye, 3, null, linear viscous generic, diag, 1., 2., 3.;
         joint: 4, deformable hinge, 1, 2, linear viscoelastic generic, diag, 10., 20., 30., diag, 1., 2., 3.;
         joint: 5, deformable hinge, 2, position, null, orientation, reference, global, eye, 3, reference, 7;
         joint: 6, deformable displacement joint, 1, null, 3, null, linear elastic isotropic, 5., prestress, 0., 0., 1.;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    let r2t = rz(std::f64::consts::FRAC_PI_2).transpose();
    let (o, i) = (Vec3::zeros(), Mat3::identity());
    b.element(DeformableDisplacement { label: 1, a: node_anchor(1, Vec3::new(1.0, 0.5, 0.0), i), b: node_anchor(2, o, i), law: LinearViscoelastic::isotropic(100.0, 0.0), rest: o });
    b.element(DeformableDisplacement { label: 2, a: node_anchor(1, o, i), b: node_anchor(3, o, i), law: LinearViscoelastic::elastic(Mat3::new(1.0, 0.1, 0.2, 0.1, 2.0, 0.3, 0.2, 0.3, 3.0)), rest: Vec3::new(0.0, 0.0, 0.1) });
    b.element(DeformableDisplacement { label: 3, a: node_anchor(2, o, i), b: node_anchor(3, o, i), law: LinearViscoelastic { stiffness: Mat3::zeros(), viscosity: Mat3::from_diagonal(&Vec3::new(1.0, 2.0, 3.0)) }, rest: o });
    b.element(DeformableHinge { label: 4, a: node_anchor(1, o, i), b: node_anchor(2, o, i), law: LinearViscoelastic { stiffness: Mat3::from_diagonal(&Vec3::new(10.0, 20.0, 30.0)), viscosity: Mat3::from_diagonal(&Vec3::new(1.0, 2.0, 3.0)) } });
    b.element(DeformableHinge { label: 5, a: node_anchor(2, o, r2t), b: node_anchor(3, o, i), law: LinearViscoelastic::isotropic(10.0, 1.0) });
    // Prestress f_p = K (−ε_rest): rest strain −f_p/k = (0, 0, −0.2).
    b.element(DeformableDisplacement { label: 6, a: node_anchor(1, o, i), b: node_anchor(3, o, i), law: LinearViscoelastic::isotropic(5.0, 0.0), rest: Vec3::new(0.0, 0.0, -0.2) });
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn rods_from_nodes_with_offsets_and_prestrain() {
    let text = file(
        "structural nodes: 3; joints: 3;",
        NODES,
        "joint: 1, rod, 1, 3, from nodes, linear elastic, 1000.;
         joint: 2, rod, 1, position, 0., 0., 0.5, 3, position, reference, global, 0., 1., 0.5, 1.5, linear elastic generic, 200.;
         joint: 3, rod with offset, 2, null, 3, null, 2., linear elastic, 100., prestrain, single, const, 0.1;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    let (o, i) = (Vec3::zeros(), Mat3::identity());
    b.element(Rod { label: 1, a: node_anchor(1, o, i), b: node_anchor(3, o, i), axial_stiffness: 1000.0, length: (4.0f64 + 0.25).sqrt(), viscous: None, elastic: None });
    b.element(Rod { label: 2, a: node_anchor(1, Vec3::new(0.0, 0.0, 0.5), i), b: node_anchor(3, Vec3::new(0.0, -1.0, 0.0), i), axial_stiffness: 200.0, length: 1.5, viscous: None, elastic: None });
    // Prestrain 0.1: rest length 2.2 and EA/l0 kept, so EA' = 100 · 2.2/2.
    b.element(Rod { label: 3, a: node_anchor(2, o, i), b: node_anchor(3, o, i), axial_stiffness: 110.0, length: 2.2, viscous: None, elastic: None });
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn forces_and_couples_read_directions_in_the_node_frame() {
    // Node 2 is turned 90° about z: an absolute force along x acts along global x as MBDyn
    // 1.7.3 applies it (tests/mbdyn_files/absolute_force_direction.mbd; the manual's "Known
    // issues" says the node frame), a follower's components are in the node frame.
    let text = file(
        "structural nodes: 3; forces: 6;",
        NODES,
        "force: 1, absolute, 2, position, 0.1, 0., 0., 1., 0., 0., const, 3.;
         force: 2, absolute, 2, position, null, single, reference, global, 1., 0., 0., const, 3.;
         force: 3, follower, 2, position, null, component, const, 1., inactive, const, 2.;
         force: 4, absolute, 2, 0., 0., 2., 0.1, 0., 0., const, 5.;
         couple: 5, follower, 3, 0., 0., 1., sine, 0., 2., 1., forever, 0.;
         couple: 6, absolute, 2, position, null, array, 2, 1., 0., 0., const, 1., 0., 1., 0., const, 2.;",
    );
    let mut b = ModelBuilder::new();
    nodes(&mut b);
    let c = |v| Drive::Const(v);
    b.element(Force::new(1, 2, ForceFrame::Absolute, Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.1, 0.0, 0.0), c(3.0)));
    b.element(Force::new(2, 2, ForceFrame::Absolute, Vec3::new(1.0, 0.0, 0.0), Vec3::zeros(), c(3.0)));
    b.element(Force::new(3, 2, ForceFrame::Follower, Vec3::new(1.0, 0.0, 2.0), Vec3::zeros(), c(1.0)));
    // MBDyn's older syntax: unit direction, arm, drive.
    b.element(Force::new(4, 2, ForceFrame::Absolute, Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.1, 0.0, 0.0), c(5.0)));
    b.element(Couple::new(5, 3, ForceFrame::Follower, Vec3::new(0.0, 0.0, 1.0), Drive::Sine { t0: 0.0, omega: 2.0, amplitude: 1.0, cycles: None, v0: 0.0 }));
    b.element(Couple::new(6, 2, ForceFrame::Absolute, Vec3::new(1.0, 2.0, 0.0), c(1.0)));
    assert_same_physics(&text, b.build().unwrap());
}

/// The x force of drive `drive` on a free static node at time `t` (its residual is −f).
fn drive_value(drive: &str, t: f64) -> f64 {
    let text = format!("drive caller: 9, const, 4.;\n{}", file("structural nodes: 1; forces: 1;", "structural: 1, static, null, eye, null, null;", &format!("force: 1, absolute, 1, position, null, 1., 0., 0., {drive};")));
    let m = read(&text);
    let asm = Assembler::new(&m.model);
    let mut st = State::initial(&m.model, &asm.dofs);
    st.t = t;
    -asm.residual(&st, ConstraintForm::Plain, 1.0)[0]
}

#[test]
fn drive_callers_follow_the_manual_formulas() {
    use std::f64::consts::PI;
    let cases: &[(&str, f64, f64)] = &[
        ("2.5", 9.0, 2.5),
        ("const, 2.5", 9.0, 2.5),
        ("null", 1.0, 0.0),
        ("unit", 1.0, 1.0),
        ("time", 1.7, 1.7),
        ("reference, 9", 1.0, 4.0),
        // ramp: v0 + slope (t − t0) between t0 and t1.
        ("ramp, 2., 1., 3., 0.5", 0.5, 0.5),
        ("ramp, 2., 1., 3., 0.5", 2.0, 2.5),
        ("ramp, 2., 1., 3., 0.5", 9.0, 4.5),
        ("ramp, 2., 1., forever, 0.5", 9.0, 16.5),
        // step: v0 + value after t0, (v0 + value)/2 at t0 itself (MBDyn 1.7.3, drive_.h).
        ("step, 1., 3., -1.", 0.9, -1.0),
        ("step, 1., 3., -1.", 1.0, 1.0),
        ("step, 1., 3., -1.", 1.1, 2.0),
        // double step: v0 + value on (t0, t1), (v0 + value)/2 at t0 and t1, v0 outside.
        ("double step, 1., 2., 3., -1.", 0.9, -1.0),
        ("double step, 1., 2., 3., -1.", 1.0, 1.0),
        ("double step, 1., 2., 3., -1.", 1.5, 2.0),
        ("double step, 1., 2., 3., -1.", 2.0, 1.0),
        ("double step, 1., 2., 3., -1.", 2.1, -1.0),
        // sine: one = half a period, then held (ends at 0); half = a quarter (held at A).
        ("sine, 0., pi, 2., one, 0.", 0.5, 2.0),
        ("sine, 0., pi, 2., one, 0.", 10.0, 0.0),
        ("sine, 0., pi, 2., half, 0.", 10.0, 2.0),
        ("sine, 0., pi, 2., 2, 0.", 1.25, 2.0 * (PI * 1.25).sin()),
        ("sine, 0., pi, 2., 2, 0.", 9.0, 0.0),
        ("sine, 0., pi, 2., -2, 1.", 9.0, 3.0),
        ("sine, 0., pi, 2., forever, 0.", 9.5, 2.0 * (9.5 * PI).sin()),
        // cosine: A (1 − cos ω(t − t0)); half stops at the top, 2A.
        ("cosine, 1., pi, 1., half, 0.", 1.5, 1.0),
        ("cosine, 1., pi, 1., half, 0.", 9.0, 2.0),
        ("cosine, 1., pi, 1., one, 0.", 9.0, 0.0),
        ("cosine, 1., pi, 1., -2, 0.5", 9.0, 2.5),
        ("cosine, 1., pi, 1., forever, 0.", 1.25, 1.0 - (0.25 * PI).cos()),
        // piecewise linear: interpolated, extended flat beyond the ends.
        ("piecewise linear, 3, 0., 0., 1., 10., 2., 0.", -1.0, 0.0),
        ("piecewise linear, 3, 0., 0., 1., 10., 2., 0.", 0.25, 2.5),
        ("piecewise linear, 3, 0., 0., 1., 10., 2., 0.", 1.5, 5.0),
        ("piecewise linear, 3, 0., 0., 1., 10., 2., 0.", 5.0, 0.0),
    ];
    for (drive, t, want) in cases {
        let got = drive_value(drive, *t);
        assert!((got - want).abs() < 1e-12, "{drive} at t = {t}: {got}, want {want}");
    }
}

#[test]
fn gravity_in_any_frame() {
    let text = "reference: 5, null, euler123, 0., 0., pi/2, null, null;\n".to_string() + &file("structural nodes: 1; rigid bodies: 1; gravity;", "structural: 1, dynamic, null, eye, null, null;", "body: 1, 1, 2., null, eye; gravity: uniform, single, reference, 5, 1., 0., 0., const, 9.81;");
    let mut b = ModelBuilder::new();
    b.dynamic_node(1, Vec3::zeros(), Mat3::identity(), Vec3::zeros(), Vec3::zeros());
    b.element(RigidBody::new(1, 1, 2.0, Vec3::zeros(), Mat3::identity()));
    b.gravity(Vec3::new(0.0, 9.81, 0.0));
    assert_same_physics(&text, b.build().unwrap());
}

#[test]
fn dummy_nodes_count_but_carry_no_unknowns() {
    let m = read(&file("structural nodes: 2;", "structural: 1, static, null, eye, null, null; structural: 2, dummy, 1, offset, 1., 0., 0., eye;", ""));
    assert_eq!(m.model.nodes.len(), 1);
}

// ---------------------------------------------------------------- problem and control data

#[test]
fn initial_value_block_fills_the_problem() {
    let m = read("begin: data; problem: initial value; end: data;
        begin: initial value;
            initial time: 0.5; final time: forever; time step: 1.e-2;
            method: ms, cosine, 0., pi, 0.2, half, 0.2, 0.;
            tolerance: 1.e-7, test, minmax, 1.e-9, test, norm;
            max iterations: 15, at most;
            derivatives tolerance: 1.e-5; derivatives max iterations: 7; derivatives coefficient: auto;
            nonlinear solver: newton raphson, modified, 5; linear solver: umfpack, cc; threads: disable;
            output: iterations, residual; strategy: factor, .5, 1, 1.25, 3, 5; dummy steps number: 0;
            eigenanalysis: list, 2, 0.5, 1., parameter, 1.e-2, output sparse matrices, output eigenvectors, output geometry,
                lower frequency limit, 0.1, upper frequency limit, 20., use arpack, 10, 20, 0., suffix width, compute,
                suffix format, \"%02d\", matrix output precision, 12, results output precision, 8;
            abort after: derivatives;
        end: initial value;");
    let p = &m.problem;
    assert_eq!((p.initial_time, p.final_time, p.time_step, p.tolerance, p.max_iterations), (0.5, f64::INFINITY, 1e-2, 1e-7, 15));
    // The radius drive at the initial time 0.5 s: 0.2 + 0.2 (1 − cos(π/2)) = 0.4.
    assert!(matches!(p.method, Method::Ms { rho } if (rho - 0.4).abs() < 1e-15), "{:?}", p.method);
    assert_eq!((p.derivatives_tolerance, p.derivatives_max_iterations, p.abort_after), (1e-5, 7, Some(AbortAfter::Derivatives)));
    let e = p.eigenanalysis.as_ref().unwrap();
    assert_eq!((e.times.clone(), e.dcoef, e.lower_frequency_hz, e.upper_frequency_hz), (vec![0.5, 1.0], Some(0.5e-2), Some(0.1), Some(20.0)));
    // dCoef = parameter / 2: MBDyn assembles Aplus, Aminus as J(±h/2) (solver.cc).
    assert!(e.output.sparse_matrices && e.output.eigenvectors && e.output.geometry && !e.output.full_matrices);
}

#[test]
fn integration_methods() {
    let method = |m: &str| read(&format!("begin: data; problem: initial value; end: data; begin: initial value; method: {m}; end: initial value;")).problem.method;
    assert_eq!(method("crank nicolson"), Method::CrankNicolson);
    assert_eq!(method("implicit euler"), Method::ImplicitEuler);
    assert_eq!(method("bdf"), Method::Ms { rho: 0.0 });
    assert_eq!(method("bdf, order, 1"), Method::ImplicitEuler);
    assert_eq!(method("ms, .6, .0"), Method::Ms { rho: 0.6 });
    assert_eq!(method("ms, const, .3"), Method::Ms { rho: 0.3 });
    // Of later MBDyn versions (their input manual, §Method; solver.cc): `Bathe, ρ [, ρ_alg]`,
    // and `hybrid, DEFAULT [, ρ [, ρ_alg]]`, every unknown with DEFAULT after a
    // Crank–Nicolson first step (ρ 0 when not given).
    assert_eq!(method("Bathe, 0.6"), Method::Bathe { rho: 0.6 });
    assert_eq!(method("bathe, const, .3, .0"), Method::Bathe { rho: 0.3 });
    assert_eq!(method("hybrid, ms, .6"), Method::Ms { rho: 0.6 });
    assert_eq!(method("hybrid, ms2"), Method::Ms { rho: 0.0 });
    assert_eq!(method("hybrid, crank nicolson"), Method::CrankNicolson);
    assert_eq!(method("hybrid, implicit euler, .6, .6"), Method::HybridImplicitEuler);
}

#[test]
fn control_data_settings_are_accepted_and_beams_are_counted() {
    let m = read(&file(
        "structural nodes: 1; beams: 0; genels: 0; skip initial joint assembly; use: rigid bodies, gravity, in assembly; initial stiffness: 1., 1.;
         tolerance: 1e-6; max iterations: 10; title: \"t\"; print: dof stats; default output: none, structural nodes; output precision: 12;
         output frequency: 10; default orientation: euler123; output results: netcdf; make restart file;",
        "structural: 1, static, null, eye, null, null, assembly, 1., 1., yes, scale, default, output, no;",
        "",
    ));
    assert_eq!(m.model.nodes.len(), 1);
}

// ---------------------------------------------------------------- model: static

/// `model: static` (dataman3.cc, strnode.cc `ReadStructNode`, body.cc `ReadBody`): MBDyn
/// 1.7.3 turns every dynamic node (and dynamic displacement node) into a static one, so its
/// bodies become static bodies that only weigh, and runs the file: each step is a static
/// equilibrium. Issue 38: romdyn refused such files, quoting a refusal MBDyn does not make.
#[test]
fn static_model_turns_dynamic_nodes_static() {
    let m = romdyn::input::mbdyn::read_model(&common::mbdyn::test_file("static_model_dynamic_nodes.mbd")).unwrap_or_else(|e| panic!("{e}"));
    assert!(m.model.nodes.iter().all(|n| n.kind == romdyn::model::NodeKind::Static), "every node is static");
    let mut h = romdyn::analysis::NodeHistories::default();
    romdyn::analysis::run(&m.model, &m.problem, &mut h).unwrap_or_else(|e| panic!("{e}"));
    let (mass, k, g) = (2.0, 400.0, 9.81);
    let last = h.time.len() - 1;
    assert!(h.time[last] >= 1.0, "the run reaches the end of the ramp");
    let position = |node: usize| &h.position[(last * h.labels.len() + node) * 3..][..3];
    // Node 2 (index 1): the spring's closed form z = -M g / K, 1e-9 relative (Newton
    // tolerance 1e-10 N on a 400 N/m spring).
    let z2 = position(1)[2];
    assert!((z2 - (-mass * g / k)).abs() < 1e-9 * (mass * g / k), "node 2 z = {z2}");
    // Node 3 (index 2): the three rods' force balance `M g e_z + Σ EA (l − 1) (p − a)/l = 0`
    // solved here by Newton with a finite-difference Jacobian (independent of romdyn's rod):
    // (2.870588e-4, 2.870588e-4, −1.0245246) m, also scipy's fsolve; 1e-9 m.
    let anchors = [([0.0, 0.0, 0.0], 2.0 * k), ([1.0, 0.0, -1.0], k), ([0.0, 1.0, -1.0], k)];
    let force = |p: [f64; 3]| {
        let mut f = [0.0, 0.0, -mass * g];
        for (a, ea) in anchors {
            let d = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            for i in 0..3 {
                f[i] -= ea * (l - 1.0) * d[i] / l;
            }
        }
        f
    };
    let mut p = [0.0, 0.0, -1.0];
    for _ in 0..50 {
        let f = force(p);
        let mut jac = nalgebra::Matrix3::zeros();
        for j in 0..3 {
            let mut q = p;
            q[j] += 1e-7;
            let fq = force(q);
            for i in 0..3 {
                jac[(i, j)] = (fq[i] - f[i]) / 1e-7;
            }
        }
        let step = jac.lu().solve(&nalgebra::Vector3::from(f)).expect("the rods hold the mass");
        for i in 0..3 {
            p[i] -= step[i];
        }
    }
    let p3 = position(2);
    for i in 0..3 {
        assert!((p3[i] - p[i]).abs() < 1e-9, "node 3 component {i}: {} against {}", p3[i], p[i]);
    }
    // MBDyn 1.7.3 (built from the mirror's 1727489e, `mbdyn -f` on this file with
    // `output precision: 16;` added to its control data) runs it to the end ("MBDyn
    // terminated normally") and writes at t = 1 s node 2 z = −4.9050000000000003e-02 m and
    // node 3 (2.8705883997376250e-04, 2.8705883997376256e-04, −1.0245245842600508e+00) m:
    // 1e-9 relative (issue 38 acceptance asks 1e-6).
    assert!((z2 - (-4.9050000000000003e-02)).abs() < 1e-9 * 4.905e-2, "node 2 z = {z2} against MBDyn's");
    for (i, mbdyn) in [2.8705883997376250e-04, 2.8705883997376256e-04, -1.0245245842600508e+00].into_iter().enumerate() {
        assert!((p3[i] - mbdyn).abs() < 1e-9 * mbdyn.abs(), "node 3 component {i}: {} against MBDyn's {mbdyn}", p3[i]);
    }
    // What MBDyn does refuse in a static model is refused with its reason: a body on a dummy
    // node (body.cc: "illegal structural node type"; romdyn: a dummy node has no unknowns).
    let nodes = "structural: 1, dynamic, 0., 0., 1., eye, null, null;\nstructural: 2, dummy, 1, offset, null, eye;";
    let text = file("model: static; structural nodes: 2; rigid bodies: 1;", nodes, "body: 1, 2, 1., null, eye;");
    let e = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("m.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d)).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("m.mbd:") && e.contains("structural node 2 is a dummy node"), "{e}");
    // A variable-mass body in a static model: MBDyn runs a static variable body, romdyn says
    // it does not (and does not blame MBDyn).
    let text = file("model: static; structural nodes: 1; rigid bodies: 1;", "structural: 1, dynamic, 0., 0., 1., eye, null, null;", "body: 1, 1, variable mass, const, 1., null, null, null;");
    let e = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("m.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d)).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("m.mbd:7:") && e.contains("not supported by romdyn") && e.contains("MBDyn 1.7.3 runs it"), "{e}");
    let text = file("model: dynamic; structural nodes: 1;", "structural: 1, static, 0., 0., 1., eye, null, null;", "");
    let e = romdyn::input::mbdyn::parse_text(&text, std::path::Path::new("m.mbd")).and_then(|d| romdyn::input::mbdyn::build(&d)).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(e.contains("m.mbd:2:") && e.contains("expected the model type (static)"), "{e}");
}
