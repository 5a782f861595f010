//! What the task judges, read off the simulation: the place task's facts about the cube and the
//! fixture, and a collision between two parts named as the task's failure.

use fairgrasp_kinematics::ArmModel;
use nalgebra::{Point3, Vector3};

use crate::config::SceneConfig;
use crate::sim::Sim;
use crate::sim::part::Part;
use crate::task::Failure;
use crate::task::state::PlaceFacts;

/// The place task's facts about the cube and the fixture, in `world` \[m\]: `None` without a
/// fixture (the lift task).
pub(crate) fn place_facts(sim: &Sim, scene: &SceneConfig) -> Option<PlaceFacts> {
    let fixture = sim.fixture_pose()?;
    let cube = sim.object_pose();
    let offset = fixture.inverse_transform_point(&Point3::from(cube.translation.vector));
    // The cube's face normals; the one nearest the vertical says how far it leans.
    let r = cube.rotation.to_rotation_matrix();
    let upright = (0..3).map(|i| r[(2, i)].abs()).fold(0.0, f64::max);
    let h = 0.5 * scene.cube_size;
    let lowest = (0..8)
        .map(|k| {
            let corner = Vector3::new(
                if k & 1 == 0 { -h } else { h },
                if k & 2 == 0 { -h } else { h },
                if k & 4 == 0 { -h } else { h },
            );
            (cube * Point3::from(corner)).z
        })
        .fold(f64::INFINITY, f64::min);
    let f = fixture.translation.vector;
    Some(PlaceFacts {
        offset_in_fixture: [offset.x, offset.y],
        bottom_above_table: lowest - scene.table_height,
        tilt: upright.clamp(-1.0, 1.0).acos(),
        fixture: [f.x, f.y, f.z],
    })
}

/// The collision between parts `a` and `b`, named in one order whatever found it (the narrow
/// phase, the exact shapes or the protective stop): the table first, then the arm from its base
/// out, the gripper last (the order of [`Part`]).
pub(crate) fn collision_failure(model: &ArmModel, a: Part, b: Part) -> Failure {
    let (first, second) = if a <= b { (a, b) } else { (b, a) };
    Failure::Collision(
        first.name(model).to_string(),
        second.name(model).to_string(),
    )
}
