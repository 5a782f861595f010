//! Physical facts of the place task's fixture (a square pocket of four 10 mm walls with 2 mm of
//! clearance per side around the 5 cm cube): a cube let go above the pocket within the clearance
//! drops in and stands on its floor; one off by more than the clearance lands on the rim (it
//! leans on a wall, or sits on it when its centre of mass is over it); none sinks into the
//! table or a wall beyond a millimetre.

use fairgrasp_env::{Action, EnvConfig, TaskEnv, TaskKind};
use nalgebra::{Isometry3, Point3, Vector3};

fn place_config() -> EnvConfig {
    let mut cfg = EnvConfig::default();
    cfg.task.kind = TaskKind::Place;
    cfg.task.max_steps = 400;
    cfg.task.place.fixture_xy = [0.30, 0.20];
    // A cube put still in mid-air would count as at rest and skip the physics (the free-space
    // shortcut is for a cube lying on something): simulate every step.
    cfg.physics.free_space = false;
    // The arm stays at home, 20 cm above the cube: asking for 30 cm of clearance keeps a seated
    // cube from ending the episode as a success before it has settled.
    cfg.task.place.clear_height = 0.3;
    cfg
}

/// Where a cube let go `above` \[m\] over the pocket's centre, shifted `dx` \[m\] along the
/// fixture's x and turned `yaw` \[rad\], comes to rest: its centre in the fixture frame and its
/// lowest corner above the table top \[m\], and its tilt from standing on a face \[rad\].
fn drop_cube(dx: f64, yaw: f64, above: f64) -> ([f64; 3], f64, f64) {
    let cfg = place_config();
    let table = cfg.scene.table_height;
    let half = 0.5 * cfg.scene.cube_size;
    let mut env = TaskEnv::new(cfg).unwrap();
    env.reset(0).unwrap();
    let fixture = env.fixture_in_base().expect("a place env has a fixture");
    let base = env.base_in_world().iso;
    let fixture_world = base * fixture.iso;
    let start = fixture_world
        * Isometry3::new(
            Vector3::new(dx, 0.0, half + above),
            Vector3::new(0.0, 0.0, yaw),
        );
    {
        let (world, handles) = env.world_mut();
        let cube = &mut world.bodies[handles.cube];
        cube.set_position(fairgrasp_env::sim::convert::to_rapier(&start), true);
        cube.set_linvel(Default::default(), true);
        cube.set_angvel(Default::default(), true);
    }
    for _ in 0..30 {
        env.step(&Action::hold_open()).unwrap();
    }
    let cube = base * env.object_in_base().iso;
    let local = fixture_world.inverse() * cube;
    let lowest = (0..8)
        .map(|k| {
            let c = Vector3::new(
                if k & 1 == 0 { -half } else { half },
                if k & 2 == 0 { -half } else { half },
                if k & 4 == 0 { -half } else { half },
            );
            (cube * Point3::from(c)).z
        })
        .fold(f64::INFINITY, f64::min);
    let t = local.translation.vector;
    let r = cube.rotation.to_rotation_matrix();
    let upright = (0..3).map(|i| r[(2, i)].abs()).fold(0.0, f64::max);
    ([t.x, t.y, t.z], lowest - table, upright.min(1.0).acos())
}

#[test]
fn a_cube_dropped_within_the_clearance_seats_on_the_pocket_floor() {
    for (dx, yaw) in [(0.0, 0.0), (0.0015, 0.0), (-0.0015, 0.02)] {
        let (centre, bottom, tilt) = drop_cube(dx, yaw, 0.015);
        assert!(tilt < 1f64.to_radians(), "dx {dx}: tilted {tilt} rad");
        assert!(
            bottom.abs() < 0.001,
            "dx {dx}: bottom {bottom} m above the table"
        );
        assert!(
            centre[0].abs() <= 0.002 + 1e-3 && centre[1].abs() <= 0.002 + 1e-3,
            "dx {dx}: centre {centre:?} outside the clearance"
        );
    }
}

#[test]
fn a_cube_off_by_more_than_the_clearance_rests_on_the_rim() {
    // 8 mm off: the cube's edge overlaps the wall by 6 mm of the wall's 10 mm. Its centre of
    // mass is over the pocket, so it tips in and comes to rest leaning on the wall's rim.
    let (centre, bottom, tilt) = drop_cube(0.008, 0.0, 0.015);
    assert!(
        tilt > 5f64.to_radians(),
        "it stands upright: tilt {tilt} rad"
    );
    // 32 mm off: the centre of mass is over the wall (27–37 mm out): it sits on top of it.
    let (_, on_top, _) = drop_cube(0.032, 0.0, 0.015);
    assert!(
        on_top > 0.009,
        "it sank to {on_top} m above the table: it should sit on the wall"
    );
    assert!(bottom > -0.001 && centre[0] > 0.0, "{centre:?} {bottom}");
}

#[test]
fn a_seated_cube_does_not_sink_into_the_table_or_the_walls() {
    // Turned 1.5° about the vertical in a 2 mm gap: its corners come within 0.4 mm of the walls.
    let (centre, bottom, _) = drop_cube(0.0, 1.5f64.to_radians(), 0.01);
    assert!(bottom > -0.001, "sank {} mm into the table", -bottom * 1e3);
    let half_side = 0.025 + 0.002;
    assert!(
        centre[0].abs() + 0.025 <= half_side + 0.001,
        "pushed {} mm into a wall",
        (centre[0].abs() + 0.025 - half_side) * 1e3
    );
}
