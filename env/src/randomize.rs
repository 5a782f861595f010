//! Per-episode scenarios: object position, yaw, friction, mass and joint noise, drawn from a seed,
//! each one checked to admit a top-down grasp within the FR3's joint limits.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use fairgrasp_kinematics::analytic_ik::joint_distance;
use fairgrasp_kinematics::{AnalyticIkOptions, ArmModel, EndFrame, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use serde::Serialize;

use crate::config::EnvConfig;

/// Height of the pre-grasp pose above the grasp pose [m].
pub const PRE_GRASP_HEIGHT: f64 = 0.10;
/// Redraws allowed before a scenario is given up as ungraspable.
const MAX_DRAWS: usize = 1000;

/// One episode's starting conditions.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Scenario {
    /// The seed it was drawn from.
    pub seed: u64,
    /// Object centre x, y in `base_link` [m].
    pub object_xy: [f64; 2],
    /// Object yaw about the table normal, relative to base x [rad].
    pub object_yaw: f64,
    /// Object friction coefficient.
    pub friction: f64,
    /// Object mass [kg].
    pub mass: f64,
    /// Home joints plus noise [rad].
    pub start_joints: [f64; 6],
    /// Error added to the observed object position, base frame [m] (perception noise).
    pub observed_position_error: [f64; 3],
    /// Error added to the observed object yaw [rad] (perception noise).
    pub observed_yaw_error: f64,
}

/// The object pose in `base_link` for a scenario: resting on the table top.
pub fn object_pose_in_base(config: &EnvConfig, base: &Pose, xy: [f64; 2], yaw: f64) -> Pose {
    // The table top is horizontal in the world; express its height in the base frame.
    let top_world = config.scene.table_height + config.scene.cube_size / 2.0;
    let base_origin_z = base.xyz()[2];
    Pose::from_xyz_rpy([xy[0], xy[1], top_world - base_origin_z], [0.0, 0.0, yaw])
}

/// The in-limit top-down grasp (TCP at the object centre, fingers across a pair of faces) and
/// its pre-grasp 10 cm above, as joint angles: among the yaws `yaw + k·90°` and the IK branches
/// that admit both within the joint limits and without self-collision or table contact (the
/// table top at `table_z` in `base_link`), the pair whose pre-grasp is nearest to `current`
/// [rad]. `None` if none does.
pub fn top_down_grasp(
    model: &ArmModel,
    object_in_base: &Pose,
    table_z: f64,
    current: &[f64; 6],
) -> Option<([f64; 6], [f64; 6])> {
    let xyz = object_in_base.xyz();
    let yaw = object_in_base.rpy()[2];
    let options = AnalyticIkOptions::default();
    let mut best: Option<(f64, [f64; 6], [f64; 6])> = None;
    for k in 0..4 {
        let grasp_yaw = yaw + k as f64 * FRAC_PI_2;
        let grasp = Pose::from_xyz_rpy(xyz, [PI, 0.0, grasp_yaw]);
        let above = Pose::from_xyz_rpy(
            [xyz[0], xyz[1], xyz[2] + PRE_GRASP_HEIGHT],
            [PI, 0.0, grasp_yaw],
        );
        let Ok(grasps) = model.ik_analytic(&grasp, EndFrame::Tcp, &options) else {
            continue;
        };
        let Ok(aboves) = model.ik_analytic(&above, EndFrame::Tcp, &options) else {
            continue;
        };
        for g in grasps.iter().filter(|s| s.in_limits) {
            if !collision_free(model, &g.joints, table_z) {
                continue;
            }
            if let Some(a) = aboves.iter().find(|a| {
                a.in_limits && a.branch == g.branch && collision_free(model, &a.joints, table_z)
            }) {
                let d = joint_distance(&a.joints, current);
                if best.is_none_or(|(bd, _, _)| d < bd) {
                    best = Some((d, g.joints, a.joints));
                }
            }
        }
    }
    best.map(|(_, g, a)| (g, a))
}

/// No self-collision (capsules), and nothing but the base below the table top plus 2 mm.
pub fn collision_free(model: &ArmModel, q: &[f64; 6], table_z: f64) -> bool {
    model.self_collisions(q, 0.0).is_empty() && model.lowest_point(q) > table_z + 0.002
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
}

impl UngraspableRegion {
    fn describe(&self) -> String {
        match self.fixed_xy {
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
        }
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
        }
    }

    /// Draws the scenario for `seed` (redrawing ungraspable positions with the same generator).
    pub fn sample(
        config: &EnvConfig,
        model: &ArmModel,
        base: &Pose,
        seed: u64,
    ) -> Result<Scenario, UngraspableRegion> {
        let r = &config.randomization;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..MAX_DRAWS {
            let object_xy = if r.position {
                // Uniform over the sector's area: radius ~ sqrt(U(r0², r1²)).
                let rad = rng
                    .random_range(r.radius[0].powi(2)..=r.radius[1].powi(2))
                    .sqrt();
                let angle = rng.random_range(r.angle[0]..=r.angle[1]);
                [rad * angle.cos(), rad * angle.sin()]
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
            let mass = config.scene.cube_mass
                * r.mass_scale.map_or(1.0, |m| rng.random_range(m[0]..=m[1]));
            let noise = Normal::new(0.0, r.joint_noise.max(1e-12)).expect("positive sigma");
            let mut start_joints = config.arm.home_joints;
            if r.joint_noise > 0.0 {
                for (q, spec) in start_joints.iter_mut().zip(&model.joints) {
                    *q = (*q + noise.sample(&mut rng)).clamp(spec.lower, spec.upper);
                }
            }
            let gauss = |rng: &mut ChaCha8Rng, sigma: f64| {
                if sigma > 0.0 {
                    Normal::new(0.0, sigma).expect("positive sigma").sample(rng)
                } else {
                    0.0
                }
            };
            let p = r.observed_position_noise;
            // Perception noise lies on the table plane: the cube's height is known.
            let observed_position_error = [gauss(&mut rng, p), gauss(&mut rng, p), 0.0];
            let observed_yaw_error = gauss(&mut rng, r.observed_yaw_noise);
            let pose = object_pose_in_base(config, base, object_xy, object_yaw);
            let table_z = config.scene.table_height - base.xyz()[2];
            if top_down_grasp(model, &pose, table_z, &start_joints).is_some() {
                return Ok(Scenario {
                    seed,
                    object_xy,
                    object_yaw,
                    friction,
                    mass,
                    start_joints,
                    observed_position_error,
                    observed_yaw_error,
                });
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
        })
    }
}

/// A seeded list of `n` scenarios, identical for every policy evaluated on it: scenario `i` is
/// drawn from seed `seed · 1 000 003 + i`.
pub fn scenario_set(
    config: &EnvConfig,
    model: &ArmModel,
    base: &Pose,
    seed: u64,
    n: usize,
) -> Result<Vec<Scenario>, UngraspableRegion> {
    (0..n as u64)
        .map(|i| {
            Scenario::sample(
                config,
                model,
                base,
                seed.wrapping_mul(1_000_003).wrapping_add(i),
            )
        })
        .collect()
}
