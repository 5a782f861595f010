//! Conversions between the kinematics' f64 nalgebra types and rapier's f32 glam types.

use nalgebra::Isometry3;
use rapier3d::prelude::*;

/// f64 isometry → rapier pose.
pub fn to_rapier(iso: &Isometry3<f64>) -> rapier3d::math::Pose {
    let t = iso.translation.vector;
    let q = iso.rotation.coords;
    rapier3d::math::Pose::from_parts(
        Vector::new(t.x as f32, t.y as f32, t.z as f32),
        rapier3d::math::Rotation::from_xyzw(q.x as f32, q.y as f32, q.z as f32, q.w as f32)
            .normalize(),
    )
}

/// rapier pose → f64 isometry.
pub fn from_rapier(pose: &rapier3d::math::Pose) -> Isometry3<f64> {
    let t = pose.translation;
    let q = pose.rotation;
    Isometry3::from_parts(
        nalgebra::Translation3::new(t.x as f64, t.y as f64, t.z as f64),
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            q.w as f64, q.x as f64, q.y as f64, q.z as f64,
        )),
    )
}

pub fn vec3(v: [f64; 3]) -> Vector {
    Vector::new(v[0] as f32, v[1] as f32, v[2] as f32)
}
