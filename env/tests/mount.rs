//! The mount and its table frame: "up" is the world's, for any base pose.

use fairgrasp_env::{EnvConfig, Mount, TaskEnv};
use fairgrasp_kinematics::Pose;

fn mount(xyz: [f64; 3], rpy: [f64; 3]) -> Mount {
    Mount::new(Pose::from_xyz_rpy(xyz, rpy), 0.6)
}

#[test]
fn a_level_base_on_the_table_has_the_table_frame_at_its_origin() {
    let m = mount([0.3, -0.1, 0.6], [0.0, 0.0, 1.1]);
    let (dp, dr) = m.table_in_base.distance_to(&Pose::identity());
    assert!(dp < 1e-12 && dr < 1e-12, "{dp} {dr}");
    assert!(m.tilt() < 1e-12);
}

#[test]
fn the_table_frame_is_level_under_the_base_and_follows_its_heading() {
    let m = mount([0.2, 0.4, 0.75], [0.1, -0.12, 2.5]);
    let t = m.table_in_world;
    // Origin on the table top, straight below the base origin.
    let o = t.xyz();
    assert!((o[0] - 0.2).abs() < 1e-12 && (o[1] - 0.4).abs() < 1e-12 && (o[2] - 0.6).abs() < 1e-12);
    // z along the world vertical; x along the base's x projected onto the table.
    let z = t.transform_vector([0.0, 0.0, 1.0]);
    assert!(z[2] > 1.0 - 1e-12);
    let bx = m.base_in_world.transform_vector([1.0, 0.0, 0.0]);
    let tx = t.transform_vector([1.0, 0.0, 0.0]);
    let cross = bx[0] * tx[1] - bx[1] * tx[0];
    assert!(cross.abs() < 1e-12 && bx[0] * tx[0] + bx[1] * tx[1] > 0.0);
    assert!((m.base_height_above_table() - 0.15).abs() < 1e-12);
    // The tilt: roll and pitch together, yaw aside.
    let expected = (0.1f64.cos() * 0.12f64.cos()).acos();
    assert!((m.tilt() - expected).abs() < 1e-12);
}

#[test]
fn heights_and_yaws_are_measured_along_the_world_vertical_not_base_z() {
    let m = mount([0.0, 0.0, 0.6], [0.0, 0.2, 0.0]); // pitched 11.5°
    // A point 0.4 m along base x is not on the table plane: base x dips by sin(0.2).
    let h = m.height_above_table([0.4, 0.0, 0.0]);
    assert!((h + 0.4 * 0.2f64.sin()).abs() < 1e-12, "{h}");
    // A cube resting on the table at yaw 0.3 reads yaw 0.3 back, whatever the tilt.
    let cube = m.resting_object_in_base([0.35, 0.1], 0.3, 0.05);
    assert!((m.yaw_on_table(&cube) - 0.3).abs() < 1e-12);
    assert!((m.height_above_table(cube.xyz()) - 0.025).abs() < 1e-12);
    // Its yaw about base z (what earlier versions observed) differs once the base is pitched.
    let x = cube.transform_vector([1.0, 0.0, 0.0]);
    assert!((x[1].atan2(x[0]) - 0.3).abs() > 1e-3);
}

#[test]
fn the_env_reports_the_mount_it_was_built_with() {
    let mut cfg = EnvConfig::default();
    cfg.arm.base_rpy = [0.05, 0.1, -0.7];
    cfg.arm.base_xyz = [0.0, 0.0, 0.5];
    let env = TaskEnv::new(cfg.clone()).unwrap();
    assert_eq!(*env.mount(), Mount::from_config(&cfg));
    assert!((env.mount().base_height_above_table() + 0.1).abs() < 1e-12);
}
