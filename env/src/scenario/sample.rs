//! Per-episode scenarios: object position, yaw, friction, mass and joint noise, drawn from a seed,
//! each one checked to admit a top-down grasp within the FR3's joint limits.
use std::f64::consts::TAU;

use fairgrasp_kinematics::Pose;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use crate::cell::derived::Cell;
use crate::cell::mount::Mount;
use crate::config::EnvConfig;
use crate::scenario::error_mix::draw::{draw_error_family, keep_only};
use crate::scenario::fixture::settings::{FixtureSite, SiteKeys};
use crate::scenario::fixture::{FixturePose, draw_fixture};
use crate::scenario::graspable::top_down_grasp;
use crate::scenario::noise::{gauss, uniform_in_sector};
use crate::scenario::nudge::draw_nudge;
use crate::scenario::perception_noise::draw_perception_errors;
use fairgrasp_kinematics::ArmModel;

/// Redraws allowed before a scenario is given up as ungraspable.
const MAX_DRAWS: usize = 1000;

/// One episode's starting conditions. Positions and yaws are in the table frame (see
/// [`Mount`]: on the table top under the base, z up, x along the base's heading), which for a
/// level base is `base_link`'s x, y.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scenario {
    /// The seed it was drawn from.
    pub seed: u64,
    /// Object centre x, y in the table frame \[m\].
    pub object_xy: [f64; 2],
    /// Object yaw about the world vertical, relative to the base's heading \[rad\].
    pub object_yaw: f64,
    /// Object friction coefficient.
    pub friction: f64,
    /// Object mass \[kg\].
    pub mass: f64,
    /// Home joints plus noise \[rad\].
    pub start_joints: [f64; 6],
    /// Error added to the observed object position, in the table frame \[m\] (perception noise).
    pub observed_position_error: [f64; 3],
    /// Error added to the observed object yaw \[rad\] (perception noise).
    pub observed_yaw_error: f64,
    /// The push the cube gets during the approach (the `nudged` family), if any.
    pub nudge: Option<crate::scenario::nudge::Nudge>,
    /// The cell's camera calibration error (`randomization.camera_offset`, the same for every
    /// episode of a config), applied to what is observed.
    pub camera_offset: Option<crate::scenario::camera_offset::CameraOffset>,
    /// Where the place task's fixture stands (`None` for the lift task).
    pub fixture: Option<FixturePose>,
}

/// The object pose in `base_link` for a scenario: resting on the table top at `xy` in the table
/// frame, turned by `yaw` about the world vertical (a config's mount, see [`Mount`]).
pub fn object_pose_in_base(config: &EnvConfig, base: &Pose, xy: [f64; 2], yaw: f64) -> Pose {
    Mount::new(*base, config.scene.table_height).resting_object_in_base(
        xy,
        yaw,
        config.scene.cube_size,
    )
}

/// Why no scenario could be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct UngraspableRegion {
    pub draws: usize,
    pub radius: [f64; 2],
    pub angle: [f64; 2],
    /// The fixed object position when `randomization.position` is off.
    pub fixed_xy: Option<[f64; 2]>,
    /// Height of the base origin above the table top \[m\] (negative: below it).
    pub base_height_above_table: f64,
    /// Tilt of the base from upright \[rad\].
    pub base_tilt: f64,
    /// The task's fixture, when some cube positions left it no place (`None`: every failed
    /// draw was the cube's own); boxed, so that an env's error stays small.
    pub fixture: Option<Box<FixtureMiss>>,
}

/// Cube positions beside which the task's fixture found no place: where its numbers are.
#[derive(Debug, Clone, PartialEq)]
pub struct FixtureMiss {
    /// The names of its site's settings (its task's table).
    pub keys: &'static SiteKeys,
    /// Its site, as the config gives it.
    pub site: FixtureSite,
    /// Cube positions drawn, and how many of them left the fixture no place.
    pub cubes: usize,
    pub misses: usize,
}

impl FixtureMiss {
    /// Why the fixture found no place, naming its table's numbers.
    fn describe(&self) -> String {
        let (k, site) = (self.keys, &self.site);
        let table = k.table;
        if site.randomize {
            format!(
                "no place for the fixture of [{table}] beside {} of {} cube positions drawn: \
                 its sector {} {:?} / {} {:?}, at least {} {} m from the cube, has no position \
                 the FR3 reaches top-down with the cube held; change [{table}]'s numbers (or \
                 the cube's sector, randomization.radius / angle)",
                self.misses,
                self.cubes,
                k.radius,
                site.radius,
                k.angle,
                site.angle,
                k.min_distance_from_cube,
                site.min_distance_from_cube,
            )
        } else {
            format!(
                "the fixture of [{table}] at {} {:?} ({table}.randomize = false) is not at \
                 least {} {} m from the cube or is not reached top-down with the cube held, \
                 beside {} of {} cube positions drawn; move it",
                k.xy[0].trim_end_matches("[0]"),
                site.xy,
                k.min_distance_from_cube,
                site.min_distance_from_cube,
                self.misses,
                self.cubes,
            )
        }
    }
}

impl UngraspableRegion {
    fn describe(&self) -> String {
        let fixture = self.fixture.as_ref();
        let what = match self.fixed_xy {
            // Every cube position was refused for want of a place for the fixture: its table's
            // numbers make the draw impossible.
            _ if fixture.is_some_and(|f| f.misses == f.cubes) => {
                fixture.map(|f| f.describe()).unwrap_or_default()
            }
            Some(xy) => format!(
                "scene.cube_xy {xy:?} (randomization.position = false) has no collision-free \
                 top-down grasp within the FR3's joint limits, or the cube would spawn inside \
                 the arm; move it (the shipped presets use 0.25–0.45 m from the base)"
            ),
            None => format!(
                "no graspable object position in {} draws: randomization.radius {:?} / angle \
                 {:?} lies outside what the FR3 reaches top-down",
                self.draws, self.radius, self.angle
            ),
        };
        let what = match fixture {
            Some(f) if f.misses < f.cubes => format!(
                "{what} ({} of the {} cube positions drawn left the fixture of [{}] no place)",
                f.misses, f.cubes, f.keys.table
            ),
            _ => what,
        };
        let level = self.base_tilt < 1e-6 && self.base_height_above_table.abs() < 1e-6;
        if level {
            return what;
        }
        format!(
            "{what}. The mount may be the cause: the base stands {:.3} m {} the table top, \
             tilted {:.1}° from upright (arm.base_xyz / arm.base_rpy); the shipped presets \
             stand it level on the table top",
            self.base_height_above_table.abs(),
            if self.base_height_above_table < 0.0 {
                "below"
            } else {
                "above"
            },
            self.base_tilt.to_degrees()
        )
    }
}

impl Scenario {
    /// The config's own values with nothing drawn and nothing checked: the cube at
    /// `scene.cube_xy`, yaw 0, the arm at home. For diagnosing a scene that [`Scenario::sample`]
    /// refuses (`fairgrasp scene`).
    pub fn unchecked(config: &EnvConfig, seed: u64) -> Scenario {
        Scenario {
            seed,
            object_xy: config.scene.cube_xy,
            object_yaw: 0.0,
            friction: config.scene.cube_friction,
            mass: config.scene.cube_mass,
            start_joints: config.arm.home_joints,
            observed_position_error: [0.0; 3],
            observed_yaw_error: 0.0,
            nudge: None,
            camera_offset: None,
            fixture: (config.task.kind.spec().site)(&config.task, config.scene.cube_size)
                .map(|site| FixturePose::fixed(&site)),
        }
    }

    /// Draws the scenario for `seed` in the cell `config` describes (redrawing ungraspable
    /// positions with the same generator). Needs no physics world.
    pub fn sample(config: &EnvConfig, seed: u64) -> Result<Scenario, UngraspableRegion> {
        Scenario::sample_in(&Cell::from_config(config), config, seed)
    }

    /// [`Scenario::sample`] for a cell already derived from `config`: the cube and the start
    /// drawn (`draw_start`) until the cube admits a top-down grasp (and, for the place task,
    /// a fixture fits beside it), then the families' own draws.
    pub fn sample_in(
        cell: &Cell,
        config: &EnvConfig,
        seed: u64,
    ) -> Result<Scenario, UngraspableRegion> {
        let r = &config.randomization;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (model, mount) = (&cell.model, cell.mount);
        // Cube positions drawn, and how many left the fixture no place (for the refusal).
        let (mut cubes, mut fixture_misses) = (0, 0);
        for _ in 0..MAX_DRAWS {
            let mut s = draw_start(config, model, seed, &mut rng);
            cubes += 1;
            let pose =
                mount.resting_object_in_base(s.object_xy, s.object_yaw, config.scene.cube_size);
            let Ok(fixture) = fixture_for(config, cell, seed, s.object_xy, &s.start_joints) else {
                fixture_misses += 1;
                if r.position {
                    continue; // another cube position may leave room for the fixture
                }
                break;
            };
            if top_down_grasp(model, &mount, &pose, &s.start_joints).is_some() {
                s.fixture = fixture;
                if let (Some(mix), Some(f)) = (&config.task.place.mix, &mut s.fixture) {
                    let cube_error = (&mut s.observed_position_error, &mut s.observed_yaw_error);
                    keep_only(draw_error_family(mix, seed), cube_error, f);
                }
                s.nudge = r.nudge.as_ref().and_then(|n| {
                    draw_nudge(
                        n,
                        config,
                        model,
                        &mount,
                        seed,
                        s.object_xy,
                        s.object_yaw,
                        &s.start_joints,
                    )
                });
                return Ok(s);
            }
            if !r.position {
                break; // a fixed position will not become graspable by redrawing
            }
        }
        Err(UngraspableRegion {
            draws: MAX_DRAWS,
            radius: r.radius,
            angle: r.angle,
            fixed_xy: (!r.position).then_some(config.scene.cube_xy),
            base_height_above_table: mount.base_height_above_table(),
            base_tilt: mount.tilt(),
            fixture: fixture_miss(config, cubes, fixture_misses),
        })
    }
}

/// One draw of the cube and the start from `rng`, in the generator's order: position (table
/// frame), yaw, friction, mass, start joints, perception errors. The families' draws (the
/// fixture, the push) come later, from generators of their own; the camera offset is the
/// config's.
fn draw_start(config: &EnvConfig, model: &ArmModel, seed: u64, rng: &mut ChaCha8Rng) -> Scenario {
    let r = &config.randomization;
    let object_xy = if r.position {
        uniform_in_sector(rng, r.radius, r.angle)
    } else {
        config.scene.cube_xy
    };
    let object_yaw = if r.yaw {
        rng.random_range(0.0..TAU)
    } else {
        0.0
    };
    let friction = r.friction.map_or(config.scene.cube_friction, |f| {
        rng.random_range(f[0]..=f[1])
    });
    let mass = config.scene.cube_mass * r.mass_scale.map_or(1.0, |m| rng.random_range(m[0]..=m[1]));
    let start_joints = noisy_home(config, model, rng);
    let (observed_position_error, observed_yaw_error) =
        draw_perception_errors(rng, r.observed_position_noise, r.observed_yaw_noise);
    Scenario {
        seed,
        object_xy,
        object_yaw,
        friction,
        mass,
        start_joints,
        observed_position_error,
        observed_yaw_error,
        nudge: None,
        camera_offset: r.camera_offset,
        fixture: None,
    }
}

/// The home joints with `randomization.joint_noise` added, each within its limits \[rad\].
fn noisy_home(config: &EnvConfig, model: &ArmModel, rng: &mut ChaCha8Rng) -> [f64; 6] {
    let sigma = config.randomization.joint_noise;
    let mut q = config.arm.home_joints;
    if sigma > 0.0 {
        for (q, spec) in q.iter_mut().zip(&model.joints) {
            *q = (*q + gauss(rng, sigma)).clamp(spec.lower, spec.upper);
        }
    }
    q
}

/// The fixture for a cube starting at `object_xy` (`Ok(None)` for a task without one);
/// `Err` when no fixture pose fits beside this cube.
fn fixture_for(
    config: &EnvConfig,
    cell: &Cell,
    seed: u64,
    object_xy: [f64; 2],
    start_joints: &[f64; 6],
) -> Result<Option<FixturePose>, ()> {
    let Some(site) = (config.task.kind.spec().site)(&config.task, config.scene.cube_size) else {
        return Ok(None);
    };
    draw_fixture(
        config,
        &site,
        &cell.model,
        &cell.mount,
        seed,
        object_xy,
        start_joints,
    )
    .map(Some)
    .ok_or(())
}

/// The fixture's part in a failed draw: its site and how many of `cubes` positions left it no
/// place (`None` when none did, or the task has no fixture).
fn fixture_miss(config: &EnvConfig, cubes: usize, misses: usize) -> Option<Box<FixtureMiss>> {
    let spec = config.task.kind.spec();
    let site = (spec.site)(&config.task, config.scene.cube_size)?;
    (misses > 0).then_some(Box::new(FixtureMiss {
        keys: spec.site_keys?,
        site,
        cubes,
        misses,
    }))
}

/// A seeded list of `n` scenarios, identical for every policy evaluated on it: scenario `i` is
/// drawn from seed `seed · 1 000 003 + i`.
pub fn scenario_set(
    config: &EnvConfig,
    seed: u64,
    n: usize,
) -> Result<Vec<Scenario>, UngraspableRegion> {
    let cell = Cell::from_config(config);
    (0..n as u64)
        .map(|i| Scenario::sample_in(&cell, config, seed.wrapping_mul(1_000_003).wrapping_add(i)))
        .collect()
}
