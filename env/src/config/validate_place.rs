//! Checking `[task.place]` ([`PlaceConfig`]). Called by `EnvConfig::validate`.

use crate::config::check::{check, check_range};
use crate::config::error::ConfigError;
use crate::config::place::PlaceConfig;
use crate::scenario::grip_tilt::settings::check_grip_tilt;

/// Refuses a fixture or criterion that cannot mean what it says, naming the field.
pub(crate) fn check_place(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    check_fixture(p, cube_size)?;
    check_observation_noise(p)?;
    check_contact_conditions(p)?;
    check_search(p)
}

/// The pocket's sizes, the seated and clear criteria, the grasp, where the fixture stands.
fn check_fixture(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    for (value, field, lo, hi, rule) in [
        (
            p.clearance,
            "task.place.clearance",
            0.0,
            0.02,
            "must be in (0, 0.02] m",
        ),
        (
            p.wall_height,
            "task.place.wall_height",
            0.0,
            0.05,
            "must be in (0, 0.05] m",
        ),
        (
            p.wall_thickness,
            "task.place.wall_thickness",
            0.0,
            0.05,
            "must be in (0, 0.05] m",
        ),
        (
            p.seated_height,
            "task.place.seated_height",
            0.0,
            0.02,
            "must be in (0, 0.02] m",
        ),
        (
            p.max_tilt,
            "task.place.max_tilt",
            0.0,
            0.5,
            "must be in (0, 0.5] rad",
        ),
        (
            p.clear_height,
            "task.place.clear_height",
            0.0,
            0.3,
            "must be in (0, 0.3] m",
        ),
        (
            p.min_distance_from_cube,
            "task.place.min_distance_from_cube",
            0.0,
            1.0,
            "must be in (0, 1] m",
        ),
    ] {
        check(value > lo && value <= hi, field, value, rule)?;
    }
    check(
        p.grasp_height.abs() < 0.5 * cube_size,
        "task.place.grasp_height",
        p.grasp_height,
        "must hold the cube: less than half its edge above or below its centre",
    )?;
    check(
        p.fixture_xy.iter().all(|v| v.abs() <= 2.0),
        "task.place.fixture_xy",
        p.fixture_xy,
        "must be within 2 m of the base [m]",
    )?;
    check_range(&p.fixture_radius, "task.place.fixture_radius", 0.0)?;
    check_range(
        &p.fixture_angle,
        "task.place.fixture_angle",
        -std::f64::consts::PI,
    )
}

/// How well the cell knows the fixture's pose.
fn check_observation_noise(p: &PlaceConfig) -> Result<(), ConfigError> {
    check(
        (0.0..=0.05).contains(&p.observed_position_noise),
        "task.place.observed_position_noise",
        p.observed_position_noise,
        "must be in [0, 0.05] m",
    )?;
    check(
        (0.0..=0.5).contains(&p.observed_yaw_noise),
        "task.place.observed_yaw_noise",
        p.observed_yaw_noise,
        "must be in [0, 0.5] rad",
    )
}

/// The grip's tilt and the fixture's friction, drawn per episode.
fn check_contact_conditions(p: &PlaceConfig) -> Result<(), ConfigError> {
    check_grip_tilt(&p.grip_tilt)?;
    if let Some(friction) = &p.fixture_friction {
        check_range(friction, "task.place.fixture_friction", 0.0)?;
        check(
            friction[1] <= 2.0,
            "task.place.fixture_friction",
            friction,
            "must be within [0, 2] (a friction coefficient)",
        )?;
    }
    Ok(())
}

/// The force search's tuned settings (`[task.place.search]`).
fn check_search(p: &PlaceConfig) -> Result<(), ConfigError> {
    let s = &p.search;
    for (value, field, lo, hi, rule) in [
        (
            s.contact_force,
            "task.place.search.contact_force",
            0.1,
            30.0,
            "must be in [0.1, 30] N",
        ),
        (
            s.pitch,
            "task.place.search.pitch",
            0.0005,
            0.02,
            "must be in [0.0005, 0.02] m per turn",
        ),
        (
            s.speed,
            "task.place.search.speed",
            0.001,
            0.1,
            "must be in [0.001, 0.1] m/s",
        ),
    ] {
        check((lo..=hi).contains(&value), field, value, rule)?;
    }
    if let Some(band) = s.floor_band {
        check(
            band > 0.0 && band <= p.wall_height,
            "task.place.search.floor_band",
            band,
            "must be in (0, task.place.wall_height] m",
        )?;
    }
    Ok(())
}
