//! Resampling an episode's joints (one waypoint per env step) to a controller's servo period
//! with Ruckig: between consecutive waypoints, the jerk-limited trajectory from one waypoint's
//! position and velocity to the next one's, lasting the env step (longer only where the limits
//! demand it); after the last waypoint, Ruckig's stop; the result sampled every period, then
//! held at the end.
//! Each waypoint has the position and the velocity the simulated arm had there, so the stream
//! passes through the episode's states on time; between them Ruckig's jerk-limited profile
//! stands in for the simulated arm's (which changes acceleration at once).

use rsruckig::prelude::*;

use crate::motion::MotionError;
use crate::stream::limits::StreamLimits;
use crate::stream::servo::{GripperEvent, ServoStream};

/// Jerk limit of the resampled trajectory \[rad/s³\]: fairgrasp's choice (FAIRINO publishes none);
/// high enough that a segment keeps the env step's duration under the 10 rad/s² limit.
pub const MAX_JERK: f64 = 2000.0;
/// Fraction of the velocity limits the resampled trajectory may use (the rest is margin for
/// the sampled check, which sees only differences between samples).
const VELOCITY_FRACTION: f64 = 0.95;

/// An episode's joints as the env recorded them.
#[derive(Clone, Copy, Debug)]
pub struct EpisodeJoints<'a> {
    /// The joints \[rad\] after the reset and after every env step.
    pub waypoints: &'a [[f64; 6]],
    /// The joints' velocities \[rad/s\] at the same moments
    /// ([`fairgrasp_env::TaskEnv::joint_velocities`]).
    pub velocities: &'a [[f64; 6]],
    /// Duration of an env step \[s\].
    pub step_sec: f64,
    /// The gripper command of every env step (`waypoints.len() − 1` of them, or none).
    pub gripper: &'a [f64],
}

/// A stream and how it relates to the episode it came from.
#[derive(Clone, Debug)]
pub struct Resampled {
    pub stream: ServoStream,
    /// Time \[s\] at which the stream reaches each waypoint.
    pub waypoint_sec: Vec<f64>,
    /// Segments that took longer than the env step (the limits demanded it).
    pub stretched_segments: usize,
    /// The episode's duration \[s\] (waypoints × step).
    pub episode_sec: f64,
}

fn daov(values: [f64; 6]) -> DataArrayOrVec<f64, 6> {
    daov_stack![
        values[0], values[1], values[2], values[3], values[4], values[5]
    ]
}

/// Resamples `episode` to a stream of one sample every `period_sec` \[s\], with `hold_samples`
/// repeats of the final sample. Each segment between waypoints is Ruckig's time-synchronised
/// trajectory within `limits` (velocity also within `max_step` per period) and [`MAX_JERK`], at
/// least one env step long; after the last waypoint the arm stops (Ruckig's velocity
/// interface). A gripper event is placed where a step's segment starts whenever the command
/// changes.
///
/// The result is not checked here: [`crate::stream::check_stream`] does it.
pub fn resample(
    episode: &EpisodeJoints<'_>,
    period_sec: f64,
    hold_samples: usize,
    limits: &StreamLimits,
) -> Result<Resampled, MotionError> {
    let (waypoints, step_sec) = (episode.waypoints, episode.step_sec);
    if waypoints.is_empty() || episode.velocities.len() != waypoints.len() {
        return Err(MotionError(format!(
            "{} waypoints with {} velocities",
            waypoints.len(),
            episode.velocities.len()
        )));
    }
    let n = waypoints.len();
    let step_limit = limits.max_step / period_sec;
    let vmax: [f64; 6] =
        std::array::from_fn(|i| VELOCITY_FRACTION * limits.max_velocity[i].min(step_limit));
    let velocities = episode.velocities;
    let plan = |k: usize, stop: bool| -> Result<Trajectory<6>, MotionError> {
        let mut otg = Ruckig::<6, ThrowErrorHandler>::new(None, period_sec);
        let mut input = InputParameter::new(None);
        input.current_position = daov(waypoints[k]);
        input.current_velocity = daov(velocities[k].map(|v| v.clamp(-1e3, 1e3)));
        input.max_velocity = daov(vmax);
        input.max_acceleration = daov([limits.max_acceleration; 6]);
        input.max_jerk = daov([MAX_JERK; 6]);
        if stop {
            input.control_interface = ControlInterface::Velocity;
            input.target_velocity = daov([0.0; 6]);
        } else {
            input.target_position = daov(waypoints[k + 1]);
            let v = velocities[k + 1];
            input.target_velocity = daov(std::array::from_fn(|i| v[i].clamp(-vmax[i], vmax[i])));
            input.minimum_duration = Some(step_sec);
        }
        let mut trajectory = Trajectory::new(None);
        otg.calculate(&input, &mut trajectory)
            .map_err(|e| MotionError(format!("segment {k} → {}: {e:?}", k + 1)))?;
        Ok(trajectory)
    };
    let mut segments = Vec::with_capacity(n);
    let mut starts = vec![0.0];
    let mut stretched = 0;
    for k in 0..n {
        let trajectory = plan(k, k + 1 == n)?;
        let duration = trajectory.get_duration();
        if k + 1 < n && duration > step_sec * (1.0 + 1e-9) {
            stretched += 1;
        }
        starts.push(starts[k] + duration);
        segments.push(trajectory);
    }
    let total = *starts.last().expect("one start per waypoint");
    let count = (total / period_sec - 1e-9).ceil().max(0.0) as usize + 1;
    let mut joints = Vec::with_capacity(count + hold_samples);
    let mut segment = 0;
    for s in 0..count {
        let t = (s as f64 * period_sec).min(total);
        while segment + 1 < segments.len() && t > starts[segment + 1] {
            segment += 1;
        }
        joints.push(position_at(&segments[segment], t - starts[segment]));
    }
    let last = *joints.last().expect("at least one sample");
    joints.extend(std::iter::repeat_n(last, hold_samples));
    starts.truncate(n);
    let mut events: Vec<GripperEvent> = Vec::new();
    for (k, &command) in episode.gripper.iter().enumerate() {
        if events.last().is_none_or(|e| e.command != command) {
            // At the sample nearest to the start of the step's segment.
            let sample = (starts[k.min(n - 1)] / period_sec).round() as usize;
            events.push(GripperEvent { sample, command });
        }
    }
    Ok(Resampled {
        stream: ServoStream {
            period_sec,
            joints,
            hold_samples,
            gripper: events,
        },
        waypoint_sec: starts,
        stretched_segments: stretched,
        episode_sec: (n - 1) as f64 * step_sec,
    })
}

/// The position \[rad\] of `trajectory` at `t` \[s\] (clamped to its duration).
fn position_at(trajectory: &Trajectory<6>, t: f64) -> [f64; 6] {
    let mut p = daov([0.0; 6]);
    let t = t.clamp(0.0, trajectory.get_duration());
    trajectory.at_time(
        t,
        &mut Some(&mut p),
        &mut None,
        &mut None,
        &mut None,
        &mut None,
    );
    std::array::from_fn(|i| p[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::check_stream;

    const DT: f64 = 1.0 / 240.0;
    const SUBSTEPS: usize = 20;
    const STEP: f64 = DT * SUBSTEPS as f64;

    /// The env's servo arm (rate limiter at 10 rad/s²) driven by one velocity command per step:
    /// (the joints and velocities after every step, the joints after every substep).
    fn simulate(commands: &[[f64; 6]]) -> [Vec<[f64; 6]>; 3] {
        let mut q = [0.2, -1.4, 1.5, -1.9, -1.57, 0.3];
        let mut qd = [0.0; 6];
        let (mut steps, mut velocities, mut fine) = (vec![q], vec![qd], vec![q]);
        for c in commands {
            for _ in 0..SUBSTEPS {
                for i in 0..6 {
                    qd[i] += (c[i] - qd[i]).clamp(-10.0 * DT, 10.0 * DT);
                    q[i] += qd[i] * DT;
                }
                fine.push(q);
            }
            steps.push(q);
            velocities.push(qd);
        }
        [steps, velocities, fine]
    }

    /// Commands like the script's (smooth) and a pure policy's (full reversals, beyond what the
    /// rate limiter reaches in one step), ending at rest.
    fn commands() -> Vec<[f64; 6]> {
        let mut c = Vec::new();
        for k in 0..40 {
            let s = k as f64 / 40.0;
            let smooth = 0.4 * (std::f64::consts::PI * s).sin();
            let bang = match k {
                0..20 => 0.0,
                _ if (k / 3) % 2 == 0 => 0.5,
                _ => -0.5,
            };
            c.push([smooth, -smooth, 0.5 * smooth, bang, 0.0, -0.3 * smooth]);
        }
        c.extend([[0.0; 6]; 4]);
        c
    }

    #[test]
    fn the_stream_follows_the_simulated_arm_between_waypoints_and_respects_the_limits() {
        let limits = StreamLimits::of(&fairgrasp_kinematics::fairino::fr3());
        let [steps, velocities, fine] = simulate(&commands());
        let gripper: Vec<f64> = (0..44).map(|k| if k < 20 { -1.0 } else { 1.0 }).collect();
        let episode = EpisodeJoints {
            waypoints: &steps,
            velocities: &velocities,
            step_sec: STEP,
            gripper: &gripper,
        };
        for period in [0.001, 0.004, 0.008, 0.016] {
            let r = resample(&episode, period, 10, &limits).unwrap();
            check_stream(&r.stream.joints, period, &limits).expect("within the limits");
        }
        let r = resample(&episode, 0.008, 25, &limits).unwrap();
        let s = &r.stream;
        // The reversals need more than one step under a finite jerk: those steps are stretched,
        // and the stream is compared with the simulation up to the first of them.
        let first_stretch = (1..steps.len())
            .find(|&k| r.waypoint_sec[k] > k as f64 * STEP + 1e-9)
            .map_or(steps.len(), |late| late - 1);
        assert!(first_stretch >= 20, "stretched from step {first_stretch}");
        assert!(
            r.stretched_segments > 0,
            "the reversals need more than a step"
        );
        let mut worst: f64 = 0.0;
        for (m, q) in fine.iter().enumerate().take(first_stretch * SUBSTEPS + 1) {
            let p = s.joints_at(m as f64 * DT);
            let w = (0..6).map(|i| (p[i] - q[i]).abs()).fold(0.0, f64::max);
            worst = worst.max(w);
            if m % SUBSTEPS == 0 {
                // At a waypoint: only the linear interpolation between samples differs.
                assert!(
                    w.to_degrees() < 0.01,
                    "waypoint {}: {:.4}°",
                    m / SUBSTEPS,
                    w.to_degrees()
                );
            }
        }
        // Between waypoints Ruckig's jerk-limited profile differs from the simulated arm's
        // (which switches acceleration at once): most where a joint starts from rest at full
        // acceleration (j4 at step 20: 0.13°).
        assert!(
            worst.to_degrees() < 0.25,
            "{:.4}° from the simulated arm",
            worst.to_degrees()
        );
        let events: Vec<(usize, f64)> = s.gripper.iter().map(|e| (e.sample, e.command)).collect();
        assert_eq!(
            events,
            [
                (0, -1.0),
                ((r.waypoint_sec[20] / 0.008).round() as usize, 1.0)
            ]
        );
        assert_eq!(s.gripper_at(0), Some(-1.0));
        assert_eq!(s.gripper_at(s.joints.len() - 1), Some(1.0));
        let end = s.joints[s.joints.len() - 26];
        assert!(s.joints[s.joints.len() - 26..].iter().all(|q| *q == end));
    }

    #[test]
    fn a_motion_faster_than_the_limits_allow_is_stretched_not_clipped() {
        // 1.2 rad in one env step is 14 rad/s: the segment must take longer than the step.
        let limits = StreamLimits::of(&fairgrasp_kinematics::fairino::fr3());
        let mut waypoints = vec![[0.0, -1.4, 1.5, -1.9, -1.57, 0.3]; 12];
        waypoints[6][0] = 1.2;
        let episode = EpisodeJoints {
            waypoints: &waypoints,
            velocities: &[[0.0; 6]; 12],
            step_sec: STEP,
            gripper: &[],
        };
        let r = resample(&episode, 0.008, 0, &limits).unwrap();
        assert!(r.stretched_segments >= 2, "{}", r.stretched_segments);
        assert!(r.stream.duration_sec() > r.episode_sec + 0.3);
        check_stream(&r.stream.joints, 0.008, &limits).expect("within the limits");
        assert!(r.stream.gripper.is_empty());
    }
}
