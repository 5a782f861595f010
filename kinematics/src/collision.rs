//! Geometric self-collision and clearance checks with the arm's capsules and a capsule model of
//! the gripper, without any physics engine: fast enough to screen thousands of grasp poses.
//!
//! All positions are in `base_link` \[m\].

use nalgebra::{Point3, Vector3};

use crate::model::ArmModel;
use crate::pose::Pose;

/// A capsule placed in `base_link`: the segment `a → b` swept by `radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlacedCapsule {
    /// Link or gripper part name.
    pub name: &'static str,
    pub a: [f64; 3],
    pub b: [f64; 3],
    pub radius: f64,
}

/// Shortest distance between segments `p1–q1` and `p2–q2` \[m\] (Ericson, Real-Time Collision
/// Detection, §5.1.9).
pub fn segment_distance(p1: [f64; 3], q1: [f64; 3], p2: [f64; 3], q2: [f64; 3]) -> f64 {
    let (p1, q1, p2, q2) = (
        Vector3::from(p1),
        Vector3::from(q1),
        Vector3::from(p2),
        Vector3::from(q2),
    );
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let eps = 1e-12;
    let (s, t) = if a <= eps && e <= eps {
        (0.0, 0.0)
    } else if a <= eps {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(&r);
        if e <= eps {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let mut s = if denom > eps {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    ((p1 + d1 * s) - (p2 + d2 * t)).norm()
}

/// The gripper as capsules in the `tool0` frame with the pads' inner faces `opening` \[m\] apart:
/// the palm, and each finger from the palm's bottom face to the pad's tip.
fn gripper_capsules(
    model: &ArmModel,
    opening: f64,
) -> [(&'static str, [f64; 3], [f64; 3], f64); 3] {
    let g = &model.gripper;
    let palm_radius = 0.5 * g.palm_size[0].hypot(g.palm_size[1]) * 0.75;
    let x = 0.5 * opening + 0.5 * g.pad_size[0];
    let tip = g.tcp_offset + 0.5 * g.pad_size[2];
    let finger_radius = 0.5 * g.pad_size[1];
    [
        (
            "palm",
            [0.0, 0.0, palm_radius.min(0.5 * g.palm_size[2])],
            [
                0.0,
                0.0,
                g.palm_size[2] - palm_radius.min(0.5 * g.palm_size[2]),
            ],
            palm_radius,
        ),
        (
            "finger_left",
            [-x, 0.0, g.palm_size[2]],
            [-x, 0.0, tip - finger_radius],
            finger_radius,
        ),
        (
            "finger_right",
            [x, 0.0, g.palm_size[2]],
            [x, 0.0, tip - finger_radius],
            finger_radius,
        ),
    ]
}

impl ArmModel {
    /// Every link capsule and the gripper's capsules (fingers fully open), placed at joints `q`.
    pub fn placed_capsules(&self, q: &[f64; 6]) -> Vec<PlacedCapsule> {
        self.placed_capsules_with_opening(q, self.gripper.opening(0.0))
    }

    /// Like [`ArmModel::placed_capsules`], with the pads' inner faces `opening` \[m\] apart.
    pub fn placed_capsules_with_opening(&self, q: &[f64; 6], opening: f64) -> Vec<PlacedCapsule> {
        let poses = self.link_poses(q);
        let mut out = Vec::with_capacity(self.capsules.len() + 3);
        for c in &self.capsules {
            let Some(i) = self.links.iter().position(|l| *l == c.link) else {
                continue;
            };
            let place = |p: [f64; 3]| {
                let w = poses[i] * Point3::from(p);
                [w.x, w.y, w.z]
            };
            out.push(PlacedCapsule {
                name: c.link,
                a: place(c.from),
                b: place(c.to),
                radius: c.radius,
            });
        }
        let tool0 = self.fk_flange(q);
        for (name, a, b, radius) in gripper_capsules(self, opening) {
            out.push(PlacedCapsule {
                name,
                a: tool0.transform_point(a),
                b: tool0.transform_point(b),
                radius,
            });
        }
        out
    }

    /// Is the pair never checked (adjacent links, the model's ignored pairs, the gripper's own
    /// parts — palm, fingers, pads — and its mount)? The one rule: the env's contact filter
    /// asks it too (`env/src/sim/collision_filter.rs`).
    pub fn collision_ignored(&self, a: &str, b: &str) -> bool {
        let index = |n: &str| self.links.iter().position(|l| *l == n);
        if let (Some(i), Some(j)) = (index(a), index(b))
            && i.abs_diff(j) <= 1
        {
            return true;
        }
        let gripper = |n: &str| {
            matches!(
                n,
                "palm"
                    | "finger_left"
                    | "finger_right"
                    | "finger_left_pad"
                    | "finger_right_pad"
                    | "wrist3_link"
            )
        };
        if gripper(a) && gripper(b) {
            return true;
        }
        self.ignored_collision_pairs
            .iter()
            .any(|(x, y)| (*x == a && *y == b) || (*x == b && *y == a))
    }

    /// The checked pairs closer than `margin` \[m\] at `q`, with their clearance (negative =
    /// overlapping). Empty means collision-free.
    pub fn self_collisions(
        &self,
        q: &[f64; 6],
        margin: f64,
    ) -> Vec<(&'static str, &'static str, f64)> {
        let capsules = self.placed_capsules(q);
        let mut hits = Vec::new();
        for (i, c1) in capsules.iter().enumerate() {
            for c2 in &capsules[i + 1..] {
                if self.collision_ignored(c1.name, c2.name) {
                    continue;
                }
                let clearance = segment_distance(c1.a, c1.b, c2.a, c2.b) - c1.radius - c2.radius;
                if clearance < margin {
                    hits.push((c1.name, c2.name, clearance));
                }
            }
        }
        hits
    }

    /// The lowest point of any capsule except the base's, as a height in `base_link` \[m\].
    pub fn lowest_point(&self, q: &[f64; 6]) -> f64 {
        self.lowest_point_in(q, &Pose::identity())
    }

    /// The lowest point of any capsule except the base's, as a height along the z axis of
    /// `frame` (a frame given in `base_link`, e.g. the table frame: z up, origin on the table
    /// top) \[m\]. A capsule's lowest point along a direction is its lower end minus its radius.
    pub fn lowest_point_in(&self, q: &[f64; 6], frame: &Pose) -> f64 {
        let to_frame = frame.inverse();
        let height = |p: [f64; 3]| to_frame.transform_point(p)[2];
        self.placed_capsules(q)
            .iter()
            .filter(|c| c.name != "base_link")
            .map(|c| height(c.a).min(height(c.b)) - c.radius)
            .fold(f64::INFINITY, f64::min)
    }
}
