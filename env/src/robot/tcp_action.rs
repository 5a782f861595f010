//! The task-space action (`arm.action_space = "tcp"`): a TCP velocity and a yaw rate in the
//! table frame, turned into joint velocities through the arm's Jacobian — kinematics first, for
//! the learner too.
//!
//! Action entries (each in [-1, 1]): 0–2 the TCP's linear velocity along the table frame's x, y,
//! z (× `arm.tcp_speed` m/s); 3 the yaw rate about the table's vertical (× `arm.tcp_yaw_rate`
//! rad/s); 4 and 5 are not used; 6 the gripper, as in joint mode. The gripper is kept pointing
//! straight down (along −z of the table frame, i.e. world gravity) by a proportional term, so a
//! policy only chooses where to go, how to turn about the vertical and when to close.
//!
//! The map is damped least squares, `q̇ = Jᵀ (J Jᵀ + λ² I)⁻¹ [v; ω]` with `J` the TCP's geometric
//! Jacobian in `base_link`; near a singularity it trades accuracy for bounded joint rates. The
//! result is scaled down as a whole (direction kept) if a joint would exceed its velocity limit.

use fairgrasp_kinematics::{ArmModel, EndFrame, Pose, damped_least_squares};
use nalgebra::{Vector3, Vector6};

use crate::cell::derived::Cell;
use crate::config::env_config::{ArmConfig, GripperCommand, TcpSaturation};

/// Damping λ of the least-squares map (mixed units: m and rad).
pub const DAMPING: f64 = 0.01;
/// How fast a tilted gripper is turned back to pointing down \[1/s\].
pub const ORIENTATION_GAIN: f64 = 4.0;

/// A task-space command, in the table frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TcpCommand {
    /// TCP linear velocity \[m/s\] along the table frame's axes.
    pub linear: [f64; 3],
    /// Yaw rate about the table's vertical \[rad/s\].
    pub yaw_rate: f64,
}

impl TcpCommand {
    /// The command of action entries 0–3 (each clipped to [-1, 1]) at `speed` \[m/s\] and
    /// `yaw_rate` \[rad/s\] per unit.
    pub fn from_action(action: &[f64; 7], speed: f64, yaw_rate: f64) -> TcpCommand {
        let a = |i: usize| action[i].clamp(-1.0, 1.0);
        TcpCommand {
            linear: [a(0) * speed, a(1) * speed, a(2) * speed],
            yaw_rate: a(3) * yaw_rate,
        }
    }
}

/// Joint velocities \[rad/s\] at joints `q` \[rad\] that move the TCP as `command` says while
/// turning it back toward pointing down. `table_in_base` is the table frame in `base_link`
/// ([`crate::Mount::table_in_base`]).
pub fn joint_velocities(
    model: &ArmModel,
    table_in_base: &Pose,
    q: &[f64; 6],
    command: &TcpCommand,
) -> [f64; 6] {
    let to_base = table_in_base.iso.rotation;
    let up = to_base * Vector3::z();
    let linear = to_base * Vector3::from(command.linear);
    // The TCP's approach axis is its z; pointing down means z_tcp = −up. The small rotation
    // taking z_tcp onto −up has axis z_tcp × (−up).
    let tcp = model.fk_tcp(q);
    let approach = tcp.iso.rotation * Vector3::z();
    let angular = up * command.yaw_rate + approach.cross(&(-up)) * ORIENTATION_GAIN;
    let twist = Vector6::new(
        linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
    );
    let j = model.jacobian(q, EndFrame::Tcp);
    let Some(qd) = damped_least_squares(&j, &twist, DAMPING) else {
        return [0.0; 6];
    };
    let mut out: [f64; 6] = std::array::from_fn(|i| qd[i]);
    let over = (0..6)
        .map(|i| out[i].abs() / model.joints[i].max_velocity)
        .fold(1.0, f64::max);
    if !over.is_finite() {
        return [0.0; 6];
    }
    for v in &mut out {
        *v /= over;
    }
    out
}

/// The task-space action with its options, for one cell: the one map from a `tcp` action to
/// joint velocities and a gripper command. The env applies it in `tcp` mode; a policy that
/// acts in task space on a `joint`-mode env hands its output through [`Self::to_joint_action`].
#[derive(Clone, Debug)]
pub struct TaskSpaceAction {
    model: ArmModel,
    /// The table frame in `base_link`.
    table_in_base: Pose,
    /// TCP speed per unit of action \[m/s\].
    tcp_speed: f64,
    /// Yaw rate per unit of action \[rad/s\].
    tcp_yaw_rate: f64,
    /// Joint velocity per unit of a joint action \[rad/s\].
    action_scale: f64,
    saturation: TcpSaturation,
    gripper: GripperCommand,
}

impl TaskSpaceAction {
    /// The action of `arm`'s settings (`tcp_speed`, `tcp_yaw_rate`, `action_scale`,
    /// `tcp_saturation`, `gripper_command`) on `cell`'s arm and mount.
    pub fn new(cell: &Cell, arm: &ArmConfig) -> Self {
        Self {
            model: cell.model.clone(),
            table_in_base: cell.mount.table_in_base,
            tcp_speed: arm.tcp_speed,
            tcp_yaw_rate: arm.tcp_yaw_rate,
            action_scale: arm.action_scale,
            saturation: arm.tcp_saturation,
            gripper: arm.gripper_command,
        }
    }

    /// The gripper command in [-1, 1] for action entry `raw`.
    pub fn gripper(&self, raw: f64) -> f64 {
        match self.gripper {
            GripperCommand::Continuous => raw.clamp(-1.0, 1.0),
            GripperCommand::Binary if raw < 0.0 => -1.0,
            GripperCommand::Binary => 1.0,
        }
    }

    /// The joint-space action (`q̇ / arm.action_scale` per joint, and the gripper) that a
    /// `joint`-mode env turns into the same motion as this task-space `action` at joints `q`
    /// \[rad\] — exactly, for [`TcpSaturation::ActionScale`] (for `JointLimits` a joint-mode env
    /// clips what exceeds `action_scale`).
    pub fn to_joint_action(&self, q: &[f64; 6], action: &[f64; 7]) -> [f64; 7] {
        let command = TcpCommand::from_action(action, self.tcp_speed, self.tcp_yaw_rate);
        let qd = joint_velocities(&self.model, &self.table_in_base, q, &command);
        let over = match self.saturation {
            TcpSaturation::JointLimits => 1.0,
            TcpSaturation::ActionScale => qd
                .iter()
                .map(|v| v.abs() / self.action_scale)
                .fold(1.0, f64::max),
        };
        let mut out = [0.0; 7];
        for i in 0..6 {
            out[i] = qd[i] / self.action_scale / over;
        }
        out[6] = self.gripper(action[6]);
        out
    }

    /// Joint velocities \[rad/s\] and the gripper command for the task-space `action` at joints
    /// `q` \[rad\] (what the env's `tcp` mode applies).
    pub fn joint_command(&self, q: &[f64; 6], action: &[f64; 7]) -> ([f64; 6], f64) {
        match self.saturation {
            TcpSaturation::JointLimits => {
                let command = TcpCommand::from_action(action, self.tcp_speed, self.tcp_yaw_rate);
                let qd = joint_velocities(&self.model, &self.table_in_base, q, &command);
                (qd, self.gripper(action[6]))
            }
            // Through the joint action, as a joint-mode env would apply it, so that both ways
            // give the same numbers to the last bit.
            TcpSaturation::ActionScale => {
                let a = self.to_joint_action(q, action);
                let qd = std::array::from_fn(|i| a[i].clamp(-1.0, 1.0) * self.action_scale);
                (qd, a[6])
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fairgrasp_kinematics::ArmKind;

    const HOME: [f64; 6] = crate::HOME_JOINTS;

    fn tcp_velocity(model: &ArmModel, q: &[f64; 6], qd: &[f64; 6]) -> Vector6<f64> {
        model.jacobian(q, EndFrame::Tcp) * Vector6::from_column_slice(qd)
    }

    #[test]
    fn a_linear_command_moves_the_tcp_that_way_without_turning_it() {
        let model = ArmKind::Fr3.model();
        let level = Pose::identity();
        // Home points the gripper down, so the orientation term is (almost) idle.
        for linear in [[0.1, 0.0, 0.0], [0.0, -0.1, 0.0], [0.0, 0.0, 0.1]] {
            let command = TcpCommand {
                linear,
                yaw_rate: 0.0,
            };
            let qd = joint_velocities(&model, &level, &HOME, &command);
            let twist = tcp_velocity(&model, &HOME, &qd);
            for k in 0..3 {
                assert!((twist[k] - linear[k]).abs() < 1e-3, "{linear:?}: {twist:?}");
            }
            assert!(twist.fixed_rows::<3>(3).norm() < 0.02, "{twist:?}");
        }
    }

    #[test]
    fn a_yaw_command_turns_about_the_vertical_of_a_tilted_table_frame() {
        let model = ArmKind::Fr3.model();
        let tilted = Pose {
            iso: nalgebra::Isometry3::rotation(Vector3::new(0.1, 0.0, 0.0)),
        };
        let command = TcpCommand {
            linear: [0.0; 3],
            yaw_rate: 0.5,
        };
        let qd = joint_velocities(&model, &tilted, &HOME, &command);
        let twist = tcp_velocity(&model, &HOME, &qd);
        let up = tilted.iso.rotation * Vector3::z();
        let angular = twist.fixed_rows::<3>(3).into_owned();
        // The commanded yaw about the table's vertical, plus a turn that tilts the gripper
        // toward that vertical (perpendicular to it).
        assert!((angular.dot(&up) - 0.5).abs() < 0.02, "{angular:?}");
    }

    #[test]
    fn joint_rates_stay_within_the_velocity_limits() {
        let model = ArmKind::Fr3.model();
        let command = TcpCommand {
            linear: [5.0, -5.0, 5.0],
            yaw_rate: 10.0,
        };
        let qd = joint_velocities(&model, &Pose::identity(), &HOME, &command);
        for (v, spec) in qd.iter().zip(&model.joints) {
            assert!(v.abs() <= spec.max_velocity + 1e-9, "{qd:?}");
        }
        assert!(qd.iter().any(|v| v.abs() > 1.0), "{qd:?}");
    }
}
