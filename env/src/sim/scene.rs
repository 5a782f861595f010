//! Building the rapier world once: table, cube, the FR3 (servo or multibody) and the gripper.
//!
//! World frame: z up, the table top at `scene.table_height`. All rapier quantities are f32;
//! the kinematics stay f64 and are converted at this boundary.

use fairgrasp_kinematics::{ArmModel, Pose};
use nalgebra::Isometry3;
use rapier3d::prelude::*;

use crate::config::{ArmSimulation, EnvConfig};
use crate::scenario::fixture::settings::FixtureSite;
use crate::sim::collision_filter::set_collision_groups;
pub use crate::sim::convert::from_rapier;
use crate::sim::convert::{to_rapier, vec3};
use crate::sim::finger_drive::{FINGER_DAMPING, FINGER_STIFFNESS};

pub use crate::sim::part::{ColliderParts, Part, ROBOT_PARTS};

/// Handles of everything in the world.
#[derive(Clone, Debug)]
pub struct SceneHandles {
    /// Arm links base_link … wrist3_link.
    pub links: [RigidBodyHandle; 7],
    pub palm: RigidBodyHandle,
    /// Left and right finger bodies.
    pub fingers: [RigidBodyHandle; 2],
    pub finger_joints: [ImpulseJointHandle; 2],
    pub cube: RigidBodyHandle,
    pub cube_collider: ColliderHandle,
    pub table_collider: ColliderHandle,
    /// Multibody joint handles j1 … j6 (multibody arm only).
    pub arm_joints: Option<[MultibodyJointHandle; 6]>,
    /// The task's fixture (a fixed body; `None` for a task without one).
    pub fixture: Option<RigidBodyHandle>,
    /// Which part each collider is.
    pub parts: ColliderParts,
}

/// Finger joint origin in the palm (= tool0) frame, open position \[m\], and closing axis.
pub fn finger_anchor(model: &ArmModel, finger: usize) -> ([f64; 3], [f64; 3]) {
    let g = &model.gripper;
    let x = g.finger_travel + 0.5 * g.pad_size[0];
    let z = g.palm_size[2];
    if finger == 0 {
        ([-x, 0.0, z], [1.0, 0.0, 0.0])
    } else {
        ([x, 0.0, z], [-1.0, 0.0, 0.0])
    }
}

/// Pad centre in the finger frame \[m\] (pads are centred on the TCP height).
pub fn pad_offset(model: &ArmModel) -> [f64; 3] {
    [
        0.0,
        0.0,
        model.gripper.tcp_offset - model.gripper.palm_size[2],
    ]
}

/// Half thickness of the table slab \[m\]: its top face is at `scene.table_height`.
pub const TABLE_HALF_THICKNESS: f64 = 0.05;
/// Half height of a finger strut \[m\]: it spans z ∈ [0, 2 · this] in the finger frame, from the
/// palm's outer face up to the pad.
pub const STRUT_HALF_HEIGHT: f64 = 0.0105;
/// How far a strut's centre sits outboard of its finger frame \[m\], away from the other finger.
pub const STRUT_OUTBOARD: f64 = 0.002;

/// The table box in the world: half extents and centre \[m\]. It is centred under the base
/// (`base_xy`, world) with its top face at `scene.table_height`.
pub fn table_box(config: &EnvConfig, base_xy: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let s = &config.scene;
    let half = [
        s.table_size[0] / 2.0,
        s.table_size[1] / 2.0,
        TABLE_HALF_THICKNESS,
    ];
    let centre = [base_xy[0], base_xy[1], s.table_height - half[2]];
    (half, centre)
}

/// The palm box on `tool0`: half extents and centre in `tool0` \[m\] (it spans z ∈ [0, size.z]).
pub fn palm_box(model: &ArmModel) -> ([f64; 3], [f64; 3]) {
    let p = model.gripper.palm_size;
    ([p[0] / 2.0, p[1] / 2.0, p[2] / 2.0], [0.0, 0.0, p[2] / 2.0])
}

/// Finger `finger`'s strut box: half extents and centre in the finger frame \[m\].
pub fn strut_box(model: &ArmModel, finger: usize) -> ([f64; 3], [f64; 3]) {
    let g = &model.gripper;
    let outboard = if finger == 0 {
        -STRUT_OUTBOARD
    } else {
        STRUT_OUTBOARD
    };
    (
        [g.pad_size[0] / 2.0, g.pad_size[1] / 2.0, STRUT_HALF_HEIGHT],
        [outboard, 0.0, STRUT_HALF_HEIGHT],
    )
}

/// A finger's pad box: half extents and centre in the finger frame \[m\].
pub fn pad_box(model: &ArmModel) -> ([f64; 3], [f64; 3]) {
    let p = model.gripper.pad_size;
    ([p[0] / 2.0, p[1] / 2.0, p[2] / 2.0], pad_offset(model))
}

/// The finger frame of finger `finger` in `tool0` after closing by `travel` \[m\] (0 = open) along
/// its axis (see [`finger_anchor`]); the fingers do not rotate.
pub fn finger_in_tool0(model: &ArmModel, finger: usize, travel: f64) -> Isometry3<f64> {
    let (anchor, axis) = finger_anchor(model, finger);
    let p: [f64; 3] = std::array::from_fn(|k| anchor[k] + travel * axis[k]);
    Isometry3::translation(p[0], p[1], p[2])
}

/// Robot parts exert no forces on each other: the overlapping capsules of neighbouring links
/// would otherwise push apart. Their contacts are still computed where a finger (a dynamic body)
/// is involved; contacts between two bodies that forces never move — the servo arm's kinematic
/// links and palm, and the fixed table ([`Part::never_moved_by_forces`]) — are not computed by
/// rapier at all (its default collision types): the env checks those pairs with the exact
/// shapes at the end of every step ([`crate::sim::shapes::RobotShapes`]), the only moment they
/// are read (computing them every substep was a third of the narrow phase's time).
fn robot_solver_groups() -> InteractionGroups {
    InteractionGroups::new(
        Group::GROUP_1,
        Group::ALL ^ Group::GROUP_1,
        InteractionTestMode::And,
    )
}

/// Inserts a collider of the robot on `body` with the robot's solver groups, and records which
/// part it is.
fn insert_robot_collider(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    collider: ColliderBuilder,
    body: RigidBodyHandle,
    part: Part,
) {
    let mut collider = collider.solver_groups(robot_solver_groups());
    if matches!(part, Part::Palm | Part::Finger(_)) {
        // Their far speculative contacts are dropped (`sim::world::FarContacts`).
        collider = collider.active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
    }
    let collider = collider.build();
    let h = world
        .colliders
        .insert_with_parent(collider, body, &mut world.bodies);
    parts.insert(h, part);
}

/// An empty world with gravity along −z and the config's integration parameters.
fn new_world(config: &EnvConfig) -> PhysicsWorld {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9.81);
    let ip = &mut world.integration_parameters;
    ip.dt = config.physics.dt as f32;
    ip.num_solver_iterations = config.physics.solver_iterations;
    ip.contact_softness.natural_frequency = config.physics.contact_natural_frequency as f32;
    // Recycled contacts may be stale by up to 5 cm of relative motion: wrong for a grasp, where
    // the cube slides millimetres along the pads. Always recompute them.
    ip.contact_recycling = false;
    ip.warmstart_joints = true;
    world
}

/// Inserts the table (a fixed box whose top is at `scene.table_height`, centred under the base
/// at `base_xy`, world) and the cube at `cube_pose` (world); returns the table's collider, the
/// cube's body and its collider.
fn insert_table_and_cube(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    config: &EnvConfig,
    base_xy: [f64; 3],
    cube_pose: &Isometry3<f64>,
) -> (ColliderHandle, RigidBodyHandle, ColliderHandle) {
    let s = &config.scene;
    let table_body = world.bodies.insert(RigidBodyBuilder::fixed());
    let (half, centre) = table_box(config, [base_xy[0], base_xy[1]]);
    let table = ColliderBuilder::cuboid(half[0] as f32, half[1] as f32, half[2] as f32)
        .translation(vec3(centre))
        .friction(s.table_friction as f32)
        .build();
    let table_collider = world
        .colliders
        .insert_with_parent(table, table_body, &mut world.bodies);
    parts.insert(table_collider, Part::Table);
    let cube = world.bodies.insert(
        RigidBodyBuilder::dynamic()
            .pose(to_rapier(cube_pose))
            .ccd_enabled(false),
    );
    let e = (s.cube_size / 2.0) as f32;
    let cube_collider = ColliderBuilder::cuboid(e, e, e)
        .mass(s.cube_mass as f32)
        .friction(s.cube_friction as f32)
        .build();
    let cube_collider = world
        .colliders
        .insert_with_parent(cube_collider, cube, &mut world.bodies);
    parts.insert(cube_collider, Part::Cube);
    (table_collider, cube, cube_collider)
}

/// Builds the world with the arm at `q`, the fingers open and the cube at `cube_pose` (world).
/// The bodies are inserted in one fixed order (table, cube, fixture, links, palm, joints,
/// fingers): rapier's handles, and with them the simulation, depend on it.
pub fn build(
    config: &EnvConfig,
    model: &ArmModel,
    base_in_world: &Pose,
    q: &[f64; 6],
    cube_pose: &Isometry3<f64>,
) -> (PhysicsWorld, SceneHandles) {
    let mut world = new_world(config);
    let mut parts = ColliderParts::default();
    let base_xy = base_in_world.xyz();
    let (table_collider, cube, cube_collider) =
        insert_table_and_cube(&mut world, &mut parts, config, base_xy, cube_pose);
    let fixture = (config.task.kind.spec().site)(&config.task, config.scene.cube_size)
        .map(|site| insert_fixture_at(&mut world, &mut parts, config, &site, base_xy));
    let dynamic = config.arm.model == ArmSimulation::Multibody;
    let links = insert_arm_links(&mut world, &mut parts, model, base_in_world, q, dynamic);
    let tool0 = base_in_world.iso * model.fk_flange(q).iso;
    let palm = insert_palm(&mut world, &mut parts, model, &tool0, dynamic);
    // Multibody arm: revolute joints j1..j6 with velocity motors, palm fixed on wrist3.
    let arm_joints = dynamic.then(|| insert_multibody_arm(&mut world, model, &links, palm));
    let (fingers, finger_joints) =
        insert_fingers(&mut world, &mut parts, config, model, &tool0, palm);
    set_collision_groups(&mut world, &parts, model);
    let handles = SceneHandles {
        links,
        palm,
        fingers,
        finger_joints,
        cube,
        cube_collider,
        table_collider,
        arm_joints,
        fixture,
        parts,
    };
    (world, handles)
}

/// The task's fixture, at its site's `xy` from the base at `base_xy` (world) until a scenario
/// moves it.
fn insert_fixture_at(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    config: &EnvConfig,
    site: &FixtureSite,
    base_xy: [f64; 3],
) -> RigidBodyHandle {
    let p = site.xy;
    let s = &config.scene;
    let at = Isometry3::translation(p[0] + base_xy[0], p[1] + base_xy[1], s.table_height);
    crate::sim::fixture::insert_fixture(world, parts, config, to_rapier(&at))
}

/// The arm's links at their FK poses for `q` (world), one capsule each: kinematic bodies for the
/// servo arm; for the multibody arm (`dynamic`) the base fixed and the others dynamic with the
/// links' mass properties.
fn insert_arm_links(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    model: &ArmModel,
    base_in_world: &Pose,
    q: &[f64; 6],
    dynamic: bool,
) -> [RigidBodyHandle; 7] {
    let link_poses = model.link_poses(q);
    let mut links = Vec::with_capacity(7);
    for (i, link_pose) in link_poses.iter().enumerate() {
        let pose = to_rapier(&(base_in_world.iso * link_pose));
        let builder = if dynamic && i > 0 {
            let m = &model.inertials[i];
            let props = MassProperties::new(vec3(m.com), m.mass as f32, vec3(m.inertia_diag));
            RigidBodyBuilder::dynamic().additional_mass_properties(props)
        } else if dynamic {
            RigidBodyBuilder::fixed()
        } else {
            RigidBodyBuilder::kinematic_position_based()
        };
        let body = world.bodies.insert(builder.pose(pose));
        let c = &model.capsules[i];
        let collider =
            ColliderBuilder::capsule_from_endpoints(vec3(c.from), vec3(c.to), c.radius as f32)
                .density(0.0);
        insert_robot_collider(world, parts, collider, body, Part::Link(i));
        links.push(body);
    }
    links.try_into().expect("seven links")
}

/// The palm, a box on `tool0` (world): dynamic for the multibody arm, kinematic for the servo
/// arm.
fn insert_palm(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    model: &ArmModel,
    tool0: &Isometry3<f64>,
    dynamic: bool,
) -> RigidBodyHandle {
    let palm_builder = if dynamic {
        RigidBodyBuilder::dynamic()
    } else {
        RigidBodyBuilder::kinematic_position_based()
    };
    let palm = world.bodies.insert(palm_builder.pose(to_rapier(tool0)));
    let (palm_half, palm_centre) = palm_box(model);
    let palm_collider = ColliderBuilder::cuboid(
        palm_half[0] as f32,
        palm_half[1] as f32,
        palm_half[2] as f32,
    )
    .translation(vec3(palm_centre))
    .mass(model.gripper.palm_mass as f32);
    insert_robot_collider(world, parts, palm_collider, palm, Part::Palm);
    palm
}

/// The two fingers, open: dynamic bodies (a strut and a pad each) on prismatic impulse joints to
/// the `palm` on `tool0` (world), driven by a force-limited position motor (`gripper.force`).
fn insert_fingers(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    config: &EnvConfig,
    model: &ArmModel,
    tool0: &Isometry3<f64>,
    palm: RigidBodyHandle,
) -> ([RigidBodyHandle; 2], [ImpulseJointHandle; 2]) {
    let g = &model.gripper;
    let mut fingers = Vec::new();
    let mut finger_joints = Vec::new();
    for f in 0..2 {
        let (anchor, axis) = finger_anchor(model, f);
        let finger_pose = tool0 * finger_in_tool0(model, f, 0.0);
        let body = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().pose(to_rapier(&finger_pose)));
        let (strut_half, strut_centre) = strut_box(model, f);
        let strut = ColliderBuilder::cuboid(
            strut_half[0] as f32,
            strut_half[1] as f32,
            strut_half[2] as f32,
        )
        .translation(vec3(strut_centre))
        .mass((g.finger_mass * 0.4) as f32);
        insert_robot_collider(world, parts, strut, body, Part::Finger(f));
        let (pad_half, pad_centre) = pad_box(model);
        let pad =
            ColliderBuilder::cuboid(pad_half[0] as f32, pad_half[1] as f32, pad_half[2] as f32)
                .translation(vec3(pad_centre))
                .mass((g.finger_mass * 0.6) as f32)
                .friction(config.gripper.pad_friction as f32);
        insert_robot_collider(world, parts, pad, body, Part::Pad(f));
        let joint = PrismaticJointBuilder::new(vec3(axis))
            .local_anchor1(vec3(anchor))
            .local_anchor2(Vector::ZERO)
            .limits([0.0, g.finger_travel as f32])
            .motor_model(MotorModel::ForceBased)
            .motor_position(0.0, FINGER_STIFFNESS as f32, FINGER_DAMPING as f32)
            .motor_max_force(config.gripper.force as f32)
            .contacts_enabled(false);
        finger_joints.push(world.impulse_joints.insert(palm, body, joint, true));
        fingers.push(body);
    }
    let fingers = fingers.try_into().expect("two fingers");
    (
        fingers,
        finger_joints.try_into().expect("two finger joints"),
    )
}

/// Rotation taking the x axis to the z axis (rapier's revolute joints turn about their frame's x).
fn x_to_z() -> Isometry3<f64> {
    Isometry3::rotation(nalgebra::Vector3::new(
        0.0,
        -std::f64::consts::FRAC_PI_2,
        0.0,
    ))
}

fn insert_multibody_arm(
    world: &mut PhysicsWorld,
    model: &ArmModel,
    links: &[RigidBodyHandle; 7],
    palm: RigidBodyHandle,
) -> [MultibodyJointHandle; 6] {
    let origins = model.link_poses(&[0.0; 6]);
    let mut handles = Vec::with_capacity(6);
    for i in 0..6 {
        // Joint origin in the parent link frame: link_{i+1} = link_i · origin · Rz(q).
        let origin = origins[i].inverse() * origins[i + 1];
        let mut joint = RevoluteJointBuilder::new(Vector::X).build();
        joint.data.set_local_frame1(to_rapier(&(origin * x_to_z())));
        joint.data.set_local_frame2(to_rapier(&x_to_z()));
        let spec = model.joints[i];
        // Adjacent capsules overlap by design (as FAIRINO's own collision model does).
        joint.data.set_contacts_enabled(false);
        joint
            .data
            .set_limits(JointAxis::AngX, [spec.lower as f32, spec.upper as f32]);
        joint
            .data
            .set_motor_model(JointAxis::AngX, MotorModel::ForceBased);
        joint.data.set_motor_velocity(JointAxis::AngX, 0.0, 1.0e3);
        joint
            .data
            .set_motor_max_force(JointAxis::AngX, if i < 3 { 150.0 } else { 28.0 });
        let handle = world
            .multibody_joints
            .insert(links[i], links[i + 1], joint, true)
            .expect("a serial arm has no loops");
        handles.push(handle);
    }
    let flange = Isometry3::translation(0.0, 0.0, model.dh[5].d);
    let fixed = FixedJointBuilder::new()
        .local_frame1(to_rapier(&flange))
        .contacts_enabled(false)
        .build();
    world
        .multibody_joints
        .insert(links[6], palm, fixed, true)
        .expect("palm on wrist3");
    // Self-contacts stay enabled so the contact scan reports self-collisions; the solver groups
    // keep them from producing forces.
    if let Some((mb, _)) = world.multibody_joints.get_mut(handles[0]) {
        mb.set_self_contacts_enabled(true);
    }
    handles.try_into().expect("six joints")
}
