//! `rigid body kinematics: {const | drive}, …;` in control data (input manual, "Rigid Body
//! Kinematics"; dataman3.cc): the moving frame the model is written in
//! ([`crate::element::frame_motion`]).
//!
//! `const, [position, X,] [orientation, R,] [velocity, V,] [angular velocity, W,]
//! [acceleration, A,] [angular acceleration, Ẇ]` and `drive, …` with template drive callers
//! for the same six (the orientation as a rotation vector). Only `W`, `A` and `Ẇ` enter the
//! equations (body.cc, autostr.cc); the others are read (a `drive` form's orientation turns
//! the vectors, as rbk_impl.cc does). MBDyn stops on a form with none of the six ("null
//! rigid body kinematics"), and so does romdyn.

use crate::mbdyn::syntax::cursor::Cursor;
use crate::mbdyn::syntax::diagnostic::MbdynError;
use crate::mbdyn::drives::callers::{template_vec3, Drives};
use crate::mbdyn::syntax::references::{Context, Frames};
use crate::element::drive::Drive;
use crate::element::{FrameMotion, VectorDrive};
use crate::kinematics::{Mat3, Vec3};

const ITEMS: [&str; 6] = ["position", "orientation", "velocity", "angular velocity", "acceleration", "angular acceleration"];

fn constant(v: Vec3) -> VectorDrive {
    VectorDrive(vec![(v, Drive::Const(1.0))])
}

/// Reads the statement's arguments (after the colon).
pub fn rigid_body_kinematics(c: &mut Cursor, drives: &Drives, frames: &Frames, seq: usize) -> Result<FrameMotion, MbdynError> {
    let form_span = c.here();
    let form = c.keyword("the rigid body kinematics type", &["const", "drive"])?;
    let mut motion = FrameMotion { orientation: None, angular_velocity: constant(Vec3::zeros()), acceleration: constant(Vec3::zeros()), angular_acceleration: constant(Vec3::zeros()) };
    let ctx = Context::global(frames, seq);
    let mut got = false;
    for item in ITEMS {
        if !c.accept(item) {
            continue;
        }
        got = true;
        let value = if form == "const" {
            if item == "orientation" {
                ctx.orientation(c, "rigid body kinematics orientation")?;
                continue;
            }
            constant(c.vec3_values(&format!("rigid body kinematics {item}"))?)
        } else {
            VectorDrive(template_vec3(c, drives, seq, &Mat3::identity(), &|c: &mut Cursor| c.vec3_values(&format!("rigid body kinematics {item} direction")))?)
        };
        match item {
            "orientation" => motion.orientation = Some(value),
            "angular velocity" => motion.angular_velocity = value,
            "acceleration" => motion.acceleration = value,
            "angular acceleration" => motion.angular_acceleration = value,
            _ => {}
        }
    }
    if !got {
        return Err(c.error_at(form_span, format!("'rigid body kinematics: {form}' needs at least one of {} (MBDyn 1.7.3: \"null rigid body kinematics\")", ITEMS.join(", "))));
    }
    Ok(motion)
}
