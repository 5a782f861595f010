//! The robot's colliders as exact f64 shapes in the world, placed by forward kinematics without
//! rapier: for free-space steps, where the arm and gripper are checked against the table and
//! themselves analytically, and for the pairs rapier never computes in any step (the servo
//! arm's links and palm against each other and the table).
//!
//! Every shape is the one [`crate::sim::scene::build`] gives rapier (same sizes and offsets, from the
//! same functions of [`crate::sim::scene`]): a capsule per link, boxes for the palm, the two finger
//! struts and the two pads, and the table box. All positions are in `world` \[m\].

use fairgrasp_kinematics::collision::segment_distance;
use fairgrasp_kinematics::geometry::{
    Cuboid, box_box_separation, segment_box_distance, segment_box_signed_distance,
};
use fairgrasp_kinematics::{ArmModel, Pose};
use nalgebra::{Isometry3, Point3, Translation3};

use crate::config::EnvConfig;
use crate::sim::contacts::CollisionFilter;
use crate::sim::scene::{self, Part};

/// Number of robot shapes: seven links, the palm, two struts, two pads.
const ROBOT_SHAPES: usize = 12;

/// One robot collider placed in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    /// The segment `a → b` (world \[m\]) swept by `radius` \[m\].
    Capsule {
        a: [f64; 3],
        b: [f64; 3],
        radius: f64,
    },
    Box(Cuboid),
}

impl Shape {
    /// A sphere (centre, radius; world \[m\]) that contains the shape.
    fn bounding_sphere(&self) -> ([f64; 3], f64) {
        match self {
            Shape::Capsule { a, b, radius } => {
                let centre = std::array::from_fn(|k| 0.5 * (a[k] + b[k]));
                let half = 0.5 * (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt();
                (centre, half + radius)
            }
            Shape::Box(c) => {
                let t = c.pose.translation.vector;
                let h = c.half_extents;
                (
                    [t.x, t.y, t.z],
                    (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt(),
                )
            }
        }
    }
}

/// Signed distance \[m\] between two shapes when it is negative (minus the exact penetration
/// depth); when they are apart, a positive number no larger than their distance.
fn signed_distance(x: &Shape, y: &Shape) -> f64 {
    match (x, y) {
        (
            Shape::Capsule { a, b, radius },
            Shape::Capsule {
                a: c,
                b: d,
                radius: r,
            },
        ) => segment_distance(*a, *b, *c, *d) - radius - r,
        (Shape::Capsule { a, b, radius }, Shape::Box(c))
        | (Shape::Box(c), Shape::Capsule { a, b, radius }) => {
            segment_box_signed_distance(*a, *b, c) - radius
        }
        (Shape::Box(c), Shape::Box(d)) => box_box_separation(c, d),
    }
}

/// Could the two shapes touch? (Their bounding spheres overlap.)
fn may_touch(x: &([f64; 3], f64), y: &([f64; 3], f64)) -> bool {
    let d2: f64 = (0..3).map(|k| (x.0[k] - y.0[k]).powi(2)).sum();
    d2 <= (x.1 + y.1).powi(2)
}

/// A box of half sizes `half` whose centre is `centre` in the frame `frame` (world).
fn placed_box(frame: &Isometry3<f64>, (half, centre): ([f64; 3], [f64; 3])) -> Cuboid {
    Cuboid::new(
        frame * Translation3::new(centre[0], centre[1], centre[2]),
        half,
    )
}

/// The robot's colliders in the world at one configuration, and the table box.
///
/// Built once ([`RobotShapes::new`]); [`RobotShapes::place`], [`RobotShapes::collision`] and
/// [`RobotShapes::clearance_to`] then allocate nothing.
#[derive(Clone, Debug)]
pub struct RobotShapes {
    /// Link capsules in their link frames: `(from, to, radius)` \[m\].
    capsules: [([f64; 3], [f64; 3], f64); 7],
    /// The shapes in the order of [`RobotShapes::PARTS`], placed in the world.
    placed: [Shape; ROBOT_SHAPES],
    /// A bounding sphere of each placed shape (centre world \[m\], radius \[m\]).
    spheres: [([f64; 3], f64); ROBOT_SHAPES],
    /// The table box in the world.
    table: Cuboid,
    table_sphere: ([f64; 3], f64),
    /// The bits of the base pose, joints \[rad\] and finger travels \[m\] the shapes were last
    /// placed at ([`placement_key`]): placing them there again computes nothing.
    placed_at: Option<PlacementKey>,
}

/// The exact bits of one placement's inputs: the base's translation and rotation
/// quaternion, the joints and the finger travels.
type PlacementKey = [u64; 15];

/// The [`PlacementKey`] of placing the robot at `q` on `base` with `finger_travel`.
fn placement_key(base: &Pose, q: &[f64; 6], finger_travel: [f64; 2]) -> PlacementKey {
    let t = base.iso.translation.vector;
    let r = base.iso.rotation.coords;
    let values = [t.x, t.y, t.z, r.x, r.y, r.z, r.w];
    std::array::from_fn(|i| match i {
        0..7 => values[i].to_bits(),
        7..13 => q[i - 7].to_bits(),
        _ => finger_travel[i - 13].to_bits(),
    })
}

impl RobotShapes {
    /// The robot part of each shape, in order.
    pub const PARTS: [Part; ROBOT_SHAPES] = crate::sim::scene::ROBOT_PARTS;

    /// The shapes of `model`'s arm and gripper (placed at zero joints, on a base at the world
    /// origin, fingers open until [`RobotShapes::place`]) and the table of `config` under the
    /// base `config.arm.base_xyz`. A link without a capsule in the model gets none (a point).
    pub fn new(config: &EnvConfig, model: &ArmModel) -> Self {
        let capsules = std::array::from_fn(|i| {
            model
                .capsules
                .get(i)
                .map_or(([0.0; 3], [0.0; 3], 0.0), |c| (c.from, c.to, c.radius))
        });
        let base = config.arm.base_xyz;
        let (half, centre) = scene::table_box(config, [base[0], base[1]]);
        let table = Cuboid::new(
            Isometry3::translation(centre[0], centre[1], centre[2]),
            half,
        );
        let point = Shape::Capsule {
            a: [0.0; 3],
            b: [0.0; 3],
            radius: 0.0,
        };
        let mut shapes = RobotShapes {
            capsules,
            placed: [point; ROBOT_SHAPES],
            spheres: [([0.0; 3], 0.0); ROBOT_SHAPES],
            table_sphere: Shape::Box(table).bounding_sphere(),
            table,
            placed_at: None,
        };
        shapes.place(model, &Pose::default(), &[0.0; 6], [0.0; 2]);
        shapes
    }

    /// Places every shape for joints `q` \[rad\] on a base at `base_in_world`, each finger closed
    /// by `finger_travel[f]` \[m\] (0 = open, `gripper.finger_travel` = closed; used as given, the
    /// convention of `Sim::finger_travel`). `model` is the one the shapes were built with. Placing
    /// them again where they already are (the same bits) computes nothing.
    pub fn place(
        &mut self,
        model: &ArmModel,
        base_in_world: &Pose,
        q: &[f64; 6],
        finger_travel: [f64; 2],
    ) {
        let key = placement_key(base_in_world, q, finger_travel);
        if self.placed_at == Some(key) {
            return;
        }
        self.placed_at = Some(key);
        let (links, flange) = model.link_poses_and_flange(q);
        for (i, link) in links.iter().enumerate() {
            let frame = base_in_world.iso * link;
            let (from, to, radius) = self.capsules[i];
            let world = |p: [f64; 3]| (frame * Point3::from(p)).coords.into();
            self.placed[i] = Shape::Capsule {
                a: world(from),
                b: world(to),
                radius,
            };
        }
        let tool0 = base_in_world.iso * flange.iso;
        self.placed[7] = Shape::Box(placed_box(&tool0, scene::palm_box(model)));
        for (f, travel) in finger_travel.into_iter().enumerate() {
            let finger = tool0 * scene::finger_in_tool0(model, f, travel);
            self.placed[8 + f] = Shape::Box(placed_box(&finger, scene::strut_box(model, f)));
            self.placed[10 + f] = Shape::Box(placed_box(&finger, scene::pad_box(model)));
        }
        for (sphere, shape) in self.spheres.iter_mut().zip(&self.placed) {
            *sphere = shape.bounding_sphere();
        }
    }

    /// The table box in the world.
    pub fn table(&self) -> &Cuboid {
        &self.table
    }

    /// The deepest penetrating pair among robot–table and robot–robot pairs that
    /// `filter.is_collision` counts: `(part, part, depth [m])`, depth > 0 — the meaning of
    /// `ContactReport::collision` from the narrow phase. `None` when nothing penetrates.
    ///
    /// `CollisionFilter` allocates on each lookup; [`RobotShapes::collision_among`] with a
    /// [`CheckedPairs`] built once does not.
    pub fn collision(&self, filter: &CollisionFilter) -> Option<(Part, Part, f64)> {
        self.deepest(|a, b| filter.is_collision(a, b))
    }

    /// [`RobotShapes::collision`] over the pairs `pairs` counts, allocation-free.
    pub fn collision_among(&self, pairs: &CheckedPairs) -> Option<(Part, Part, f64)> {
        self.deepest(|a, b| pairs.counts(a, b))
    }

    /// Every pair `pairs` counts that penetrates: `(part, part, depth [m])`, depth > 0, in the
    /// order of [`RobotShapes::PARTS`] (the table last in each row).
    pub fn penetrating_among(&self, pairs: &CheckedPairs) -> Vec<(Part, Part, f64)> {
        let mut out = Vec::new();
        self.each_penetrating(|a, b| pairs.counts(a, b), |found| out.push(found));
        out
    }

    /// The deepest penetrating pair among those `counts`.
    fn deepest(&self, counts: impl Fn(Part, Part) -> bool) -> Option<(Part, Part, f64)> {
        let mut deepest: Option<(Part, Part, f64)> = None;
        self.each_penetrating(counts, |(a, b, depth)| {
            if deepest.is_none_or(|(_, _, d)| depth > d) {
                deepest = Some((a, b, depth));
            }
        });
        deepest
    }

    /// Calls `found` with every penetrating pair among those `counts`, `(part, part, depth
    /// \[m\])`; bounding spheres screen the pairs first.
    fn each_penetrating(
        &self,
        counts: impl Fn(Part, Part) -> bool,
        mut found: impl FnMut((Part, Part, f64)),
    ) {
        let mut consider = |a: Part, x: &Shape, xs, b: Part, y: &Shape, ys| {
            if !may_touch(xs, ys) || !counts(a, b) {
                return;
            }
            let depth = -signed_distance(x, y);
            if depth > 0.0 {
                found((a, b, depth));
            }
        };
        let table = Shape::Box(self.table);
        for i in 0..ROBOT_SHAPES {
            let (a, x, xs) = (Self::PARTS[i], &self.placed[i], &self.spheres[i]);
            for j in i + 1..ROBOT_SHAPES {
                consider(a, x, xs, Self::PARTS[j], &self.placed[j], &self.spheres[j]);
            }
            consider(a, x, xs, Part::Table, &table, &self.table_sphere);
        }
    }

    /// Penetration depth \[m\] of `a` into `b` (robot parts or the table; exact), 0 when they
    /// are apart or only touch; `None` for the cube or a part paired with itself.
    pub fn penetration(&self, a: Part, b: Part) -> Option<f64> {
        let table = Shape::Box(self.table);
        let shape = |p: Part| CheckedPairs::slot(p).map(|i| self.placed.get(i).unwrap_or(&table));
        let (x, y) = (shape(a)?, shape(b)?);
        (a != b).then(|| (-signed_distance(x, y)).max(0.0))
    }

    /// A lower bound on the distance \[m\] from every robot part (links, palm, struts, pads) to
    /// `cuboid` (world), 0 when touching: exact for the link capsules, the largest
    /// separating-axis gap for the boxes (exact when a face separates them).
    pub fn clearance_to(&self, cuboid: &Cuboid) -> f64 {
        let (centre, radius) = Shape::Box(*cuboid).bounding_sphere();
        let mut best = f64::INFINITY;
        for (shape, (c, r)) in self.placed.iter().zip(&self.spheres) {
            // The spheres' gap bounds the shapes' distance from below: skip hopeless parts.
            let gap = (0..3)
                .map(|k| (c[k] - centre[k]).powi(2))
                .sum::<f64>()
                .sqrt()
                - r
                - radius;
            if gap >= best {
                continue;
            }
            let distance = match shape {
                Shape::Capsule { a, b, radius } => segment_box_distance(*a, *b, cuboid) - radius,
                Shape::Box(c) => box_box_separation(c, cuboid),
            };
            best = best.min(distance);
        }
        best.max(0.0)
    }
}

/// Which pairs of robot parts (and robot part–table) a [`CollisionFilter`] counts as
/// collisions, looked up once: `counts` allocates nothing.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CheckedPairs {
    /// `counted[i][j]`: pair (`slot(i)`, `slot(j)`) counts; slot 12 is the table.
    counted: [[bool; ROBOT_SHAPES + 1]; ROBOT_SHAPES + 1],
}

impl CheckedPairs {
    /// The verdicts of `filter` on every pair of robot parts and the table.
    pub fn new(filter: &CollisionFilter) -> Self {
        let counted = std::array::from_fn(|i| {
            std::array::from_fn(|j| filter.is_collision(Self::part(i), Self::part(j)))
        });
        CheckedPairs { counted }
    }

    /// These pairs restricted to those `keep` accepts.
    pub fn only(&self, keep: impl Fn(Part, Part) -> bool) -> CheckedPairs {
        let counted = std::array::from_fn(|i| {
            std::array::from_fn(|j| self.counted[i][j] && keep(Self::part(i), Self::part(j)))
        });
        CheckedPairs { counted }
    }

    /// Does a contact between `a` and `b` count as a collision? (`false` for the cube.)
    pub fn counts(&self, a: Part, b: Part) -> bool {
        match (Self::slot(a), Self::slot(b)) {
            (Some(i), Some(j)) => self.counted[i][j],
            _ => false,
        }
    }

    /// The part of slot `i` (the inverse of [`CheckedPairs::slot`]).
    fn part(i: usize) -> Part {
        RobotShapes::PARTS.get(i).copied().unwrap_or(Part::Table)
    }

    fn slot(part: Part) -> Option<usize> {
        match part {
            Part::Table => Some(ROBOT_SHAPES),
            Part::Cube | Part::Fixture => None,
            p => RobotShapes::PARTS.iter().position(|q| *q == p),
        }
    }
}
