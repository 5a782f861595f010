//! The engineer's fix for a miscalibrated camera: calibrate the cell, then run the open-loop
//! script on corrected observations ("script + calibration" in `compare`).
//!
//! The calibration is simulated as it is done in a real cell ([`fairgrasp_kinematics::calibrate`],
//! `fairgrasp calibrate points`): a marker is placed at [`TOUCHES`] spots where cubes are drawn
//! (the preset's own scenario sampler, with the calibration's seed [`CALIBRATION_SEED`], never an
//! evaluation seed); the camera reports each (through the preset's perception model: its
//! calibration error and its noise); the TCP is touched to each, known through FK up to a touch
//! error of ±[`TOUCH_ERROR`] per axis. The point fit of "seen" against "touched" is the camera's
//! error as a rigid transform; its inverse corrects every later observation. On a preset without
//! a camera error, the fit is the identity up to the touch error. Where the camera's error is not
//! one fixed transform (drawn anew per episode: `hard`, `wrist_camera`), the fit's residuals
//! exceed the 5 mm bound and the calibration is refused, as `fairgrasp calibrate` refuses it in a
//! real cell: the engineer then keeps the camera as it is, and so does the script.

use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::scenario::perception::{ObservedObject, observe_object};
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{Action, EnvConfig, Mount, Observation};
use fairgrasp_kinematics::Pose;
use fairgrasp_kinematics::analytic_ik::wrap_pi;
use fairgrasp_kinematics::calibrate::{PointFit, PointFitOptions, PointPair, fit_points};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::lift::script::{BaselineConfig, ScriptedGrasp};

/// Marker spots touched per calibration.
pub const TOUCHES: usize = 8;
/// The largest error of one touch, per axis \[m\] (a careful touch with a pointed tool).
pub const TOUCH_ERROR: f64 = 0.001;
/// The seed of the calibration's marker spots and touch errors.
pub const CALIBRATION_SEED: u64 = 0xCA11_B8A7E;

/// A camera's calibration: what corrects its observations.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraCalibration {
    /// The point fit: `T` with `T · p_true ≈ p_seen` (both in `base_link`), its residuals; or
    /// why it was refused (then nothing is corrected).
    pub fit: Result<PointFit, String>,
    /// `T⁻¹`, applied to every observed position [`base_link` → `base_link`].
    correction: Pose,
    /// The correction's turn about the world vertical \[rad\], added to the observed yaw.
    yaw_correction: f64,
}

impl CameraCalibration {
    /// Calibrates the camera of `config`'s cell (see the module docs).
    pub fn of(config: &EnvConfig) -> Result<CameraCalibration, String> {
        let mount = Mount::from_config(config);
        let spots = scenario_set(config, CALIBRATION_SEED, TOUCHES).map_err(|e| e.to_string())?;
        let mut rng = ChaCha8Rng::seed_from_u64(CALIBRATION_SEED);
        let pairs: Vec<PointPair> = spots
            .iter()
            .map(|s| {
                let truth =
                    mount.resting_object_in_base(s.object_xy, s.object_yaw, config.scene.cube_size);
                let seen = observe_object(&mount, &truth, Some(s)).position;
                let t = truth.xyz();
                let e: [f64; 3] = [0; 3].map(|_| TOUCH_ERROR * rng.random_range(-1.0..=1.0));
                PointPair {
                    world: seen,
                    base: [t[0] + e[0], t[1] + e[1], t[2] + e[2]],
                }
            })
            .collect();
        let fit = match fit_points(&pairs, &PointFitOptions::default()) {
            Ok(fit) => fit,
            Err(e) => {
                return Ok(CameraCalibration {
                    fit: Err(e.to_string()),
                    correction: Pose::identity(),
                    yaw_correction: 0.0,
                });
            }
        };
        let correction = fit.base_in_world.inverse();
        // The correction's turn, seen in the table frame: where it sends the table's x axis.
        let table = mount.table_in_base;
        let in_table = table.inverse().compose(&correction).compose(&table);
        let x = in_table.transform_vector([1.0, 0.0, 0.0]);
        Ok(CameraCalibration {
            fit: Ok(fit),
            correction,
            yaw_correction: x[1].atan2(x[0]),
        })
    }

    /// An observation with its object corrected by the calibration.
    pub fn correct(&self, obs: &Observation) -> Observation {
        let mut out = *obs;
        let p = self.correction.transform_point(obs.object_position());
        out.object_rel_tcp = [0, 1, 2].map(|i| p[i] - obs.tcp_position[i]);
        out.object_yaw = wrap_pi(obs.object_yaw + self.yaw_correction);
        out
    }
}

/// The open-loop script on observations corrected by a [`CameraCalibration`].
pub struct CalibratedScript {
    script: ScriptedGrasp,
    calibration: CameraCalibration,
}

impl CalibratedScript {
    pub fn new(config: &EnvConfig, calibration: CameraCalibration) -> Self {
        Self {
            script: ScriptedGrasp::new(config, BaselineConfig::default()),
            calibration,
        }
    }
}

impl Policy for CalibratedScript {
    fn reset(&mut self, seed: u64) {
        self.script.reset(seed);
    }
    fn act(&mut self, obs: &Observation) -> Action {
        self.script.act(&self.calibration.correct(obs))
    }
    fn observe_truth(&mut self, _truth: &ObservedObject) {}
    fn gave_up(&self) -> Option<Outcome> {
        self.script.gave_up()
    }
    fn phase(&self) -> Option<&'static str> {
        Policy::phase(&self.script)
    }
}
