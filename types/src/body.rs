//! The robot as a replay draws it: named rigid bodies whose poses a trajectory records per step,
//! and the collision shapes fixed to them (the simulation's own: a capsule per arm link, boxes
//! for the palm, the finger struts and the pads), plus the table box and the base's mount.
//!
//! Poses are 7 numbers `[x, y, z, qx, qy, qz, qw]` (metres, unit quaternion).

use serde::{Deserialize, Serialize};

/// A pose `[x, y, z, qx, qy, qz, qw]`: position \[m\] and unit quaternion.
pub type Pose7 = [f64; 7];

/// The identity pose.
pub const IDENTITY_POSE: Pose7 = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];

/// One collision shape fixed to a recorded body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyShape {
    /// What the shape is (`upperarm_link`, `palm`, `finger_left_pad`, …).
    pub name: String,
    /// Index of the body it is fixed to (in [`crate::trajectory::TrajectoryScene::bodies`]).
    pub body: usize,
    /// The shape, in the body's frame.
    #[serde(flatten)]
    pub geometry: Geometry,
}

/// A primitive shape in its body's frame \[m\].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Geometry {
    /// The segment `a → b` swept by `radius`.
    Capsule {
        a: [f64; 3],
        b: [f64; 3],
        radius: f64,
    },
    /// A box with these half extents, centred at `centre`, axes along the body's.
    Box {
        centre: [f64; 3],
        half_extents: [f64; 3],
    },
}

/// An axis-aligned box in the world: centre and half extents \[m\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorldBox {
    pub centre: [f64; 3],
    pub half_extents: [f64; 3],
}

/// Rotates `v` by the unit quaternion `q = [x, y, z, w]`.
pub fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    let [x, y, z, w] = q;
    // v + 2w(q×v) + 2q×(q×v), q = (x, y, z)
    let u = [x, y, z];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let t = cross(u, v).map(|c| 2.0 * c);
    let s = cross(u, t);
    [0, 1, 2].map(|i| v[i] + w * t[i] + s[i])
}

/// `a ∘ b`: the pose `b` (given in the frame `a`) expressed where `a` is given.
pub fn compose(a: &Pose7, b: &Pose7) -> Pose7 {
    let qa = [a[3], a[4], a[5], a[6]];
    let p = rotate(qa, [b[0], b[1], b[2]]);
    let [x1, y1, z1, w1] = qa;
    let [x2, y2, z2, w2] = [b[3], b[4], b[5], b[6]];
    [
        a[0] + p[0],
        a[1] + p[1],
        a[2] + p[2],
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composing_two_quarter_turns_about_z_is_a_half_turn_and_moves_the_point() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let quarter = [1.0, 0.0, 0.0, 0.0, 0.0, s, s];
        let c = compose(&quarter, &quarter);
        // Half turn about z: quaternion (0, 0, 1, 0); the second offset (1, 0, 0) turned to y.
        let expect = [1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        for (a, b) in c.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12, "{c:?}");
        }
        assert_eq!(compose(&IDENTITY_POSE, &quarter), quarter);
    }

    #[test]
    fn a_shape_round_trips_through_json_with_its_kind_named() {
        let s = BodyShape {
            name: "palm".into(),
            body: 7,
            geometry: Geometry::Box {
                centre: [0.0, 0.0, 0.05],
                half_extents: [0.045, 0.03, 0.05],
            },
        };
        let text = serde_json::to_string(&s).unwrap();
        assert!(text.contains(r#""kind":"box""#), "{text}");
        assert_eq!(serde_json::from_str::<BodyShape>(&text).unwrap(), s);
    }
}
