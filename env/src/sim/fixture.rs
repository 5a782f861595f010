//! A task's fixture: one fixed body of boxes standing on the table, its origin on the table top
//! (z up along the world vertical) — the place task's square pocket of four walls (its floor is
//! the table itself), the stack task's second cube. Its boxes are the task's
//! ([`TaskSpec::fixture_boxes`](crate::config::task::TaskSpec::fixture_boxes)). Built once with
//! the world; each episode moves it to the scenario's pose ([`crate::sim::Sim::place_fixture`]).

use rapier3d::prelude::*;

use crate::config::EnvConfig;
use crate::sim::part::{ColliderParts, Part};

/// Inserts the fixture of the task of `config` (a fixed body, its boxes with the table's
/// friction) at `pose` in the world, and records its colliders as [`Part::Fixture`].
pub fn insert_fixture(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    config: &EnvConfig,
    pose: Pose,
) -> RigidBodyHandle {
    let body = world.bodies.insert(RigidBodyBuilder::fixed().pose(pose));
    let boxes = (config.task.kind.spec().fixture_boxes)(&config.task, config.scene.cube_size);
    for (half, centre) in boxes {
        let wall = ColliderBuilder::cuboid(half[0] as f32, half[1] as f32, half[2] as f32)
            .translation(Vector::new(
                centre[0] as f32,
                centre[1] as f32,
                centre[2] as f32,
            ))
            .friction(config.scene.table_friction as f32)
            .build();
        let h = world
            .colliders
            .insert_with_parent(wall, body, &mut world.bodies);
        parts.insert(h, Part::Fixture);
    }
    body
}
