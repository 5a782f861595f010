//! A real six-axis sensor's reading of a true wrench: per axis, in the sensor's own frame, a
//! Gaussian noise, then its resolution (`[sensor.wrench]`). The noise of a reading is drawn from
//! the scenario's seed and the step's index alone, so an episode replays bit for bit and the
//! scenario's own draws are untouched.

use fairgrasp_kinematics::Pose;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::config::WrenchSensorConfig;
use crate::scenario::noise::gauss;
use crate::sensor::wrench::Wrench;

/// A stream of its own for the sensor's noise, apart from the scenario's draws.
const NOISE_STREAM: u64 = 0x5e45_0a11_f7a1_1e55;

/// What the sensor at `sensor_pose` (`base_link`) reads of the true wrench `truth` (`base_link`,
/// torque about the sensor's origin) at step `step` of the scenario `seed`, returned in
/// `base_link`: the truth turned into the sensor's frame, each axis given N(0, σ²) and rounded to
/// the resolution, turned back.
pub fn read_with_noise(
    truth: &Wrench,
    sensor_pose: &Pose,
    sensor: &WrenchSensorConfig,
    seed: u64,
    step: usize,
) -> Wrench {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ NOISE_STREAM);
    rng.set_stream(step as u64);
    let local = truth.in_frame(sensor_pose);
    let noisy = |v: [f64; 3], sigma: f64, resolution: f64, rng: &mut ChaCha8Rng| {
        v.map(|x| quantise(x + gauss(rng, sigma), resolution))
    };
    let read = Wrench {
        force: noisy(
            local.force,
            sensor.force_noise,
            sensor.force_resolution,
            &mut rng,
        ),
        torque: noisy(
            local.torque,
            sensor.torque_noise,
            sensor.torque_resolution,
            &mut rng,
        ),
    };
    read.in_frame(&sensor_pose.inverse())
}

/// `x` rounded to a multiple of `resolution` (unchanged for a resolution of 0).
fn quantise(x: f64, resolution: f64) -> f64 {
    if resolution > 0.0 {
        (x / resolution).round() * resolution
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sensor(force_noise: f64, force_resolution: f64) -> WrenchSensorConfig {
        WrenchSensorConfig {
            force_noise,
            torque_noise: 0.0,
            force_resolution,
            torque_resolution: 0.0,
            friction: false,
        }
    }

    #[test]
    fn a_reading_is_the_same_for_the_same_seed_and_step_and_spreads_by_its_sigma() {
        let pose = Pose::from_xyz_rpy([0.3, 0.1, 0.2], [3.0, 0.2, 0.5]);
        let truth = Wrench {
            force: [1.0, -2.0, 3.0],
            torque: [0.01, 0.02, -0.03],
        };
        let s = sensor(0.05, 0.0);
        let a = read_with_noise(&truth, &pose, &s, 7, 12);
        assert_eq!(a, read_with_noise(&truth, &pose, &s, 7, 12));
        assert_ne!(a, read_with_noise(&truth, &pose, &s, 7, 13));
        // Per axis N(0, 0.05²): over 4 000 readings the sample σ is within 5 % of it.
        let xs: Vec<f64> = (0..4000)
            .map(|k| read_with_noise(&truth, &pose, &s, 3, k).force[0] - truth.force[0])
            .collect();
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        let sd = (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / xs.len() as f64).sqrt();
        assert!((sd - 0.05).abs() < 0.0025, "σ {sd}");
        assert!(mean.abs() < 0.003, "mean {mean}");
        // The torque has no noise here: it is read exactly.
        let t = read_with_noise(&truth, &pose, &s, 3, 5).torque;
        assert!(
            (0..3).all(|i| (t[i] - truth.torque[i]).abs() < 1e-12),
            "{t:?}"
        );
    }

    #[test]
    fn a_reading_is_a_multiple_of_the_resolution_in_the_sensors_frame() {
        let pose = Pose::from_xyz_rpy([0.3, 0.1, 0.2], [3.1, 0.0, 0.4]);
        let truth = Wrench {
            force: [0.33, -1.27, 2.01],
            torque: [0.0; 3],
        };
        let read = read_with_noise(&truth, &pose, &sensor(0.0, 0.25), 1, 1);
        let local = read.in_frame(&pose).force;
        for v in local {
            assert!(((v / 0.25).round() * 0.25 - v).abs() < 1e-9, "{local:?}");
        }
        let exact = truth.in_frame(&pose).force;
        assert!((0..3).all(|i| (local[i] - exact[i]).abs() <= 0.125 + 1e-9));
    }
}
