//! `RobotShapes` against rapier's own colliders: on random joints, finger travels and mounts,
//! every counted pair's penetration and the clearance to a random cube agree with parry's exact
//! queries on the colliders `scene::build` made.
//!
//! Method: the env's bodies are moved to the configuration (links and palm by FK as
//! `Sim::place_kinematic_arm` does, the fingers at their travel along the prismatic axis), each
//! collider's world pose is its body's pose times its offset on the body, and parry answers
//! for every pair (f32): for penetration the narrow phase's contact manifolds and two GJK/EPA
//! queries (see [`Reference`] for which is exact where), for clearance `parry::query::distance`.
//! No physics step runs, so nothing moves between the two answers.

use fairgrasp_env::sim::contacts::CollisionFilter;
use fairgrasp_env::sim::convert::{from_rapier, to_rapier};
use fairgrasp_env::sim::scene::{Part, finger_in_tool0};
use fairgrasp_env::sim::shapes::{CheckedPairs, RobotShapes};
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_kinematics::geometry::Cuboid;
use fairgrasp_kinematics::{EndFrame, Pose};
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rapier3d::parry;
use rapier3d::parry::query::{ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher};
use rapier3d::parry::shape::Shape;
use rapier3d::prelude::*;

type Pose3 = rapier3d::math::Pose;
/// Joints \[rad\] and finger travels \[m\].
type Configuration = ([f64; 6], [f64; 2]);

/// Level, tilted, elevated and turned mounts (tilts within the 15° validation limit).
const MOUNTS: [([f64; 3], [f64; 3]); 4] = [
    ([0.0, 0.0, 0.6], [0.0, 0.0, 0.0]),
    ([0.1, -0.2, 0.75], [0.2, 0.0, 0.7]),
    ([-0.3, 0.1, 0.62], [0.0, -0.2, -2.0]),
    ([0.0, 0.0, 0.9], [0.12, 0.12, 3.0]),
];

fn env_on(mount: &([f64; 3], [f64; 3])) -> TaskEnv {
    let mut config = EnvConfig::default();
    (config.arm.base_xyz, config.arm.base_rpy) = *mount;
    TaskEnv::new(config).expect("a valid mount")
}

/// Random joints within the limits \[rad\] and finger travels within [0, travel] \[m\]; every
/// other draw puts the TCP, pointing down, from 3 cm below to 8 cm above the table top (by IK),
/// so that the pads and the palm graze the table.
fn random_configuration(env: &TaskEnv, rng: &mut ChaCha8Rng) -> Configuration {
    let model = env.model();
    let travel = [0; 2].map(|_| rng.random_range(0.0..=model.gripper.finger_travel));
    let q = std::array::from_fn(|i| rng.random_range(model.joints[i].lower..model.joints[i].upper));
    if rng.random_bool(0.5) {
        let tcp_on_table = Pose::from_xyz_rpy(
            [
                rng.random_range(0.25..0.6),
                rng.random_range(-0.3..0.3),
                rng.random_range(-0.03..0.08),
            ],
            [std::f64::consts::PI, 0.0, rng.random_range(-3.1..3.1)],
        );
        let target = env.mount().table_in_base.compose(&tcp_on_table);
        if let Ok(Some(ik)) = model.ik_nearest(&target, EndFrame::Tcp, &q) {
            return (ik.joints, travel);
        }
    }
    (q, travel)
}

/// Moves rapier's robot bodies to joints `q` and finger travels `travel`.
fn place_bodies(env: &mut TaskEnv, q: &[f64; 6], travel: [f64; 2]) {
    let model = env.model().clone();
    let base = *env.base_in_world();
    let (world, handles) = env.world_mut();
    let tool0 = base.iso * model.fk_flange(q).iso;
    let links = model.link_poses(q).map(|p| base.iso * p);
    let fingers = [0, 1].map(|f| tool0 * finger_in_tool0(&model, f, travel[f]));
    let targets = handles
        .links
        .iter()
        .zip(links)
        .chain([(&handles.palm, tool0)]);
    for (handle, pose) in targets.chain(handles.fingers.iter().zip(fingers)) {
        world.bodies[*handle].set_position(to_rapier(&pose), true);
    }
}

/// Every robot and table collider: its part, world pose and shape.
fn colliders(env: &mut TaskEnv) -> Vec<(Part, Pose3, SharedShape)> {
    let (world, handles) = env.world_mut();
    let mut out: Vec<_> = handles
        .parts
        .iter()
        .filter(|(_, part)| *part != Part::Cube)
        .map(|(handle, part)| {
            let c = &world.colliders[handle];
            let body = world.bodies[c.parent().expect("on a body")].position();
            let offset = c.position_wrt_parent().copied().unwrap_or_default();
            (part, *body * offset, c.shared_shape().clone())
        })
        .collect();
    out.sort_by_key(|(part, _, _)| format!("{part:?}"));
    out
}

/// parry's answers on one pair of colliders: penetration depths \[m\], 0 when apart.
///
/// None of them is exact on every pair, so a pair agrees when one of them does:
/// - the narrow phase (what rapier's `contacts::analyze` reads: the deepest point of the contact
///   manifolds of parry's default dispatcher) is exact for two capsules and for a capsule whose
///   core segment stays outside the box, but its clipped points can lie deeper than the
///   penetration depth once the core enters the box, and it misses some shallow capsule–box
///   overlaps altogether;
/// - GJK/EPA on the two shapes (`parry::query::contact`) is exact for two boxes; on the curved
///   capsules it can miss a penetration or come out millimetres shallow;
/// - for a capsule and a box, the capsule's radius minus (or plus) the core segment's GJK
///   distance (or EPA depth) to the box; f32 GJK on the segment is sometimes millimetres off.
struct Reference {
    narrow: f64,
    gjk: f64,
    core: Option<f64>,
}

impl Reference {
    /// The answer nearest to `ours`.
    fn nearest(&self, ours: f64) -> f64 {
        [Some(self.narrow), Some(self.gjk), self.core]
            .into_iter()
            .flatten()
            .min_by(|x, y| (x - ours).abs().total_cmp(&(y - ours).abs()))
            .unwrap_or(self.narrow)
    }
}

/// Penetration depth \[m\] of two shapes by GJK, then EPA if they intersect; negative: apart.
fn gjk_depth(p1: &Pose3, g1: &dyn Shape, p2: &Pose3, g2: &dyn Shape) -> f64 {
    let d = parry::query::distance(p1, g1, p2, g2).expect("supported shapes");
    if d.distance > 0.0 {
        return -f64::from(d.distance);
    }
    let c = parry::query::contact(p1, g1, p2, g2, 0.0).expect("supported shapes");
    c.map_or(0.0, |c| f64::from(-c.dist))
}

fn reference((p1, s1): (&Pose3, &SharedShape), (p2, s2): (&Pose3, &SharedShape)) -> Reference {
    let mut manifolds: Vec<ContactManifold<(), ()>> = Vec::new();
    let (g1, g2) = (s1.as_ref(), s2.as_ref());
    DefaultQueryDispatcher
        .contact_manifolds(&p1.inv_mul(p2), g1, g2, 0.0, &mut manifolds, &mut None)
        .expect("supported shapes");
    let deepest = manifolds
        .iter()
        .flat_map(|m| m.points.iter().map(|p| p.dist))
        .fold(0.0f32, f32::min);
    let core = match (g1.as_capsule(), g2.as_capsule()) {
        (Some(c), None) => Some(f64::from(c.radius) + gjk_depth(p1, &c.segment, p2, g2)),
        (None, Some(c)) => Some(f64::from(c.radius) + gjk_depth(p1, g1, p2, &c.segment)),
        _ => None,
    };
    Reference {
        narrow: f64::from(-deepest),
        gjk: gjk_depth(p1, g1, p2, g2).max(0.0),
        core: core.map(|d| d.max(0.0)),
    }
}

#[test]
fn penetrations_agree_with_parry_on_random_configurations_and_mounts() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let (mut colliding, mut free, mut pairs_compared, mut worst) = (0, 0, 0, 0.0f64);
    let (mut penetrating, mut narrow_off, mut narrow_missed) = (0, 0, 0);
    let (mut table_hits, mut table_grazes) = (0, 0);
    for mount in &MOUNTS {
        let mut env = env_on(mount);
        let model = env.model().clone();
        let filter = CollisionFilter::new(&model);
        let checked = CheckedPairs::new(&filter);
        let mut shapes = RobotShapes::new(env.config(), &model);
        for _ in 0..150 {
            let (q, travel) = random_configuration(&env, &mut rng);
            place_bodies(&mut env, &q, travel);
            shapes.place(&model, env.base_in_world(), &q, travel);
            let all = colliders(&mut env);
            let (mut deepest, mut narrow_deepest) = (0.0f64, 0.0f64);
            for (i, (a, p1, s1)) in all.iter().enumerate() {
                for (b, p2, s2) in &all[i + 1..] {
                    if !filter.is_collision(*a, *b) {
                        continue;
                    }
                    let theirs = reference((p1, s1), (p2, s2));
                    let ours = shapes.penetration(*a, *b).expect("robot or table parts");
                    let at = format!("{a:?}-{b:?} at {q:?}, {travel:?}: ours {ours}");
                    let depth = theirs.nearest(ours);
                    if depth.max(ours) > 5e-4 {
                        assert!(depth > 0.0 && ours > 0.0, "{at}, parry {depth}");
                    }
                    if theirs.narrow > 5e-4 {
                        assert!(ours > 0.0, "{at}, narrow phase {}", theirs.narrow);
                    }
                    assert!((depth - ours).abs() < 1e-3, "{at}, parry {depth}");
                    worst = worst.max((depth - ours).abs());
                    deepest = deepest.max(depth);
                    narrow_deepest = narrow_deepest.max(theirs.narrow);
                    penetrating += usize::from(depth > 0.0);
                    narrow_off += usize::from(depth > 0.0 && (depth - theirs.narrow).abs() > 1e-3);
                    pairs_compared += 1;
                    if *a == Part::Table || *b == Part::Table {
                        table_hits += usize::from(depth > 5e-4);
                        table_grazes += usize::from(depth > 0.0 && depth < 5e-3);
                    }
                }
            }
            let ours = shapes.collision(&filter);
            assert_eq!(ours, shapes.collision_among(&checked));
            let ours_depth = ours.map_or(0.0, |(_, _, d)| d);
            assert!((ours_depth - deepest).abs() < 1e-3, "{ours:?} vs {deepest}");
            if let Some((a, b, d)) = ours {
                assert!(filter.is_collision(a, b) && d > 0.0);
                assert_eq!(shapes.penetration(a, b), Some(d));
            }
            colliding += usize::from(deepest > 5e-4);
            free += usize::from(deepest == 0.0);
            narrow_missed += usize::from(deepest > 5e-4 && narrow_deepest == 0.0);
        }
    }
    eprintln!(
        "{colliding} colliding, {free} free samples; {pairs_compared} pairs, worst {worst:.2e} m; \
         {penetrating} penetrating pairs, the narrow phase > 1 mm off on {narrow_off}; colliding \
         samples the narrow phase misses: {narrow_missed}; robot–table pairs deeper than \
         0.5 mm: {table_hits}, within 5 mm: {table_grazes}"
    );
    assert!(
        colliding >= 100 && free >= 100,
        "{colliding} colliding, {free} free"
    );
    assert!(
        table_hits >= 100 && table_grazes >= 20,
        "{table_hits}, {table_grazes}"
    );
    assert!(
        narrow_off * 20 < penetrating,
        "narrow phase off on {narrow_off}/{penetrating}"
    );
}

#[test]
fn clearance_to_a_cube_never_exceeds_parrys_distance() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (mut apart, mut close_to_exact) = (0, 0);
    let samples = 2 * 150;
    for mount in &MOUNTS[..2] {
        let mut env = env_on(mount);
        let model = env.model().clone();
        let mut shapes = RobotShapes::new(env.config(), &model);
        for _ in 0..150 {
            let (q, travel) = random_configuration(&env, &mut rng);
            place_bodies(&mut env, &q, travel);
            shapes.place(&model, env.base_in_world(), &q, travel);
            let robot: Vec<_> = colliders(&mut env)
                .into_iter()
                .filter(|(part, _, _)| *part != Part::Table)
                .collect();
            // A cube of 2–8 cm near a random robot part (its collider's centre).
            let near = from_rapier(&robot[rng.random_range(0..robot.len())].1);
            let offset = [0; 3].map(|_| rng.random_range(-0.12..0.12));
            let half = rng.random_range(0.01..0.04);
            let angles = [0; 3].map(|_| rng.random_range(-3.2..3.2));
            let pose = Isometry3::from_parts(
                Translation3::from(near.translation.vector + nalgebra::Vector3::from(offset)),
                UnitQuaternion::from_euler_angles(angles[0], angles[1], angles[2]),
            );
            let cube = parry::shape::Cuboid::new(Vector::splat(half as f32));
            let exact = robot
                .iter()
                .map(|(_, p, s)| {
                    let d = parry::query::distance(p, s.as_ref(), &to_rapier(&pose), &cube);
                    f64::from(d.expect("supported").distance)
                })
                .fold(f64::INFINITY, f64::min);
            let ours = shapes.clearance_to(&Cuboid::new(pose, [half; 3]));
            assert!(
                ours <= exact + 1e-4,
                "clearance {ours} above parry's {exact}"
            );
            apart += usize::from(exact > 1e-3);
            close_to_exact += usize::from(exact > 1e-3 && exact - ours < 1e-3);
        }
    }
    assert!(apart > samples / 4, "only {apart} of {samples} cubes apart");
    assert!(
        close_to_exact * 2 > apart,
        "{close_to_exact} of {apart} within 1 mm"
    );
}

/// Micro-timing, dev profile: `cargo test --test shapes -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_of_place_collision_and_clearance() {
    let env = env_on(&MOUNTS[0]);
    let model = env.model().clone();
    let filter = CollisionFilter::new(&model);
    let checked = CheckedPairs::new(&filter);
    let mut shapes = RobotShapes::new(env.config(), &model);
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let configs: Vec<_> = (0..2000)
        .map(|_| random_configuration(&env, &mut rng))
        .collect();
    let cube = Cuboid::new(Isometry3::translation(0.4, 0.0, 0.625), [0.025; 3]);
    let base = *env.base_in_world();
    // The collision-free ones: what a free-space step sees.
    let free: Vec<_> = configs
        .iter()
        .filter(|(q, t)| {
            shapes.place(&model, &base, q, *t);
            shapes.collision_among(&checked).is_none()
        })
        .copied()
        .collect();
    let time = |name: &str, f: &mut dyn FnMut(&Configuration) -> f64| {
        for (set, configs) in [("all", &configs), ("free", &free)] {
            let start = std::time::Instant::now();
            let sum: f64 = configs.iter().map(&mut *f).sum();
            let per = start.elapsed().as_secs_f64() / configs.len().max(1) as f64;
            let n = configs.len();
            eprintln!("{name}, {set} {n}: {:.2} µs per call ({sum:.3})", per * 1e6);
        }
    };
    time("place", &mut |(q, t)| {
        shapes.place(&model, &base, q, *t);
        0.0
    });
    time("place + collision(filter)", &mut |(q, t)| {
        shapes.place(&model, &base, q, *t);
        shapes.collision(&filter).map_or(0.0, |c| c.2)
    });
    time("place + collision_among(pairs)", &mut |(q, t)| {
        shapes.place(&model, &base, q, *t);
        shapes.collision_among(&checked).map_or(0.0, |c| c.2)
    });
    time("place + clearance_to", &mut |(q, t)| {
        shapes.place(&model, &base, q, *t);
        shapes.clearance_to(&cube)
    });
}

#[test]
fn non_finite_joints_and_travels_give_answers_not_panics() {
    let env = env_on(&MOUNTS[0]);
    let model = env.model().clone();
    let filter = CollisionFilter::new(&model);
    let mut shapes = RobotShapes::new(env.config(), &model);
    let cube = Cuboid::new(Isometry3::translation(0.4, 0.0, 0.625), [0.025; 3]);
    for bad in [f64::NAN, f64::INFINITY, -1e300] {
        shapes.place(&model, env.base_in_world(), &[bad; 6], [bad; 2]);
        let _ = shapes.collision(&filter);
        let _ = shapes.clearance_to(&cube);
    }
    // Back to a clear pose: the home joints, open fingers, no collision.
    shapes.place(
        &model,
        env.base_in_world(),
        &fairgrasp_env::HOME_JOINTS,
        [0.0; 2],
    );
    assert_eq!(shapes.collision(&filter), None);
    assert!(shapes.clearance_to(&cube) > 0.0);
}

#[test]
fn shapes_placed_again_answer_as_shapes_placed_once_whatever_changed_in_between() {
    // `place` skips the work when nothing changed since the last placement: each step below
    // changes one input (joints, one finger, the base) or none, and the reused shapes must
    // answer bit for bit as fresh shapes placed once at the same configuration.
    let mut rng = ChaCha8Rng::seed_from_u64(61);
    let cube = Cuboid {
        pose: Isometry3::translation(0.35, 0.05, 0.02),
        half_extents: [0.02; 3],
    };
    let answers = |shapes: &RobotShapes| {
        let mut out = vec![shapes.clearance_to(&cube)];
        for (i, a) in RobotShapes::PARTS.iter().enumerate() {
            for b in RobotShapes::PARTS[i + 1..].iter().chain(&[Part::Table]) {
                out.push(shapes.penetration(*a, *b).unwrap_or(f64::NAN));
            }
        }
        out.into_iter().map(f64::to_bits).collect::<Vec<u64>>()
    };
    for mount in &MOUNTS[..2] {
        let env = env_on(mount);
        let model = env.model().clone();
        let mut reused = RobotShapes::new(env.config(), &model);
        let (mut q, mut travel) = random_configuration(&env, &mut rng);
        let mut base = *env.base_in_world();
        for k in 0..40 {
            match k % 4 {
                0 => q = random_configuration(&env, &mut rng).0,
                1 => travel[k / 4 % 2] = rng.random_range(0.0..=model.gripper.finger_travel),
                2 => base.iso.translation.vector.z += 0.01,
                _ => {}
            }
            reused.place(&model, &base, &q, travel);
            let mut fresh = RobotShapes::new(env.config(), &model);
            fresh.place(&model, &base, &q, travel);
            assert_eq!(
                answers(&reused),
                answers(&fresh),
                "step {k}: {q:?} {travel:?}"
            );
        }
    }
}
