//! The place task's fixture: a square pocket of four walls standing on the table, one fixed
//! body whose origin is the pocket's centre on the table top (z up along the world vertical).
//! The pocket's floor is the table itself. Built once with the world; each episode moves it to
//! the scenario's pose ([`crate::sim::Sim::place_fixture`]).

use rapier3d::prelude::*;

use crate::config::{EnvConfig, PlaceConfig};
use crate::sim::part::{ColliderParts, Part};

/// The four walls' half extents and centres in the fixture frame \[m\]: two along x (which also
/// close the corners) and two along y.
pub fn wall_boxes(place: &PlaceConfig, cube_size: f64) -> [([f64; 3], [f64; 3]); 4] {
    let h = place.pocket_half_side(cube_size);
    let (t, z) = (place.wall_thickness, 0.5 * place.wall_height);
    let across = h + 0.5 * t;
    let long = [0.5 * t, h + t, z];
    let short = [h, 0.5 * t, z];
    [
        (long, [across, 0.0, z]),
        (long, [-across, 0.0, z]),
        (short, [0.0, across, z]),
        (short, [0.0, -across, z]),
    ]
}

/// Inserts the fixture (a fixed body, its walls with the table's friction) at `pose` in the
/// world, and records its colliders as [`Part::Fixture`].
pub fn insert_fixture(
    world: &mut PhysicsWorld,
    parts: &mut ColliderParts,
    config: &EnvConfig,
    pose: Pose,
) -> RigidBodyHandle {
    let body = world.bodies.insert(RigidBodyBuilder::fixed().pose(pose));
    for (half, centre) in wall_boxes(&config.task.place, config.scene.cube_size) {
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
