//! The agent's task-space action (`agent.action_space = "tcp"`): the policy outputs a TCP
//! velocity and a yaw rate in the table frame (entries 0–3, the gripper at 6, 4–5 unused), and
//! this map turns it into the env's joint-velocity action through the kinematics
//! ([`fairgrasp_env::robot::tcp_action`]), at the joints the observation reports.
//!
//! The env's joint action is `q̇ / arm.action_scale`; if any joint would need more than 1, the
//! whole joint action is scaled down so that the TCP keeps its direction. The gripper is binary,
//! as in Isaac Lab's lift task: open below 0, closed from 0 up. (A continuous command between
//! −1 and 1 leaves the fingers half closed, and an exploring policy then lands them on the cube.)

use fairgrasp_env::robot::tcp_action::{TcpCommand, joint_velocities};
use fairgrasp_env::{Action, EnvConfig, Mount};
use fairgrasp_kinematics::{ArmKind, ArmModel};

/// Task-space to joint-space, for one env configuration.
#[derive(Clone, Debug)]
pub struct ActionMap {
    model: ArmModel,
    mount: Mount,
    /// TCP speed per unit of action [m/s] (`arm.tcp_speed`).
    tcp_speed: f64,
    /// Yaw rate per unit of action [rad/s] (`arm.tcp_yaw_rate`).
    tcp_yaw_rate: f64,
    /// Joint velocity per unit of the env's joint action [rad/s] (`arm.action_scale`).
    action_scale: f64,
}

impl ActionMap {
    pub fn new(env: &EnvConfig) -> ActionMap {
        ActionMap {
            model: ArmKind::Fr3.model(),
            mount: Mount::from_config(env),
            tcp_speed: env.arm.tcp_speed,
            tcp_yaw_rate: env.arm.tcp_yaw_rate,
            action_scale: env.arm.action_scale,
        }
    }

    /// The joint-velocity action for the task-space action `tcp` at joints `q` [rad].
    pub fn to_joint_action(&self, q: &[f64; 6], tcp: &Action) -> Action {
        let command = TcpCommand::from_action(&tcp.0, self.tcp_speed, self.tcp_yaw_rate);
        let qd = joint_velocities(&self.model, &self.mount.table_in_base, q, &command);
        let over = qd
            .iter()
            .map(|v| v.abs() / self.action_scale)
            .fold(1.0, f64::max);
        let mut out = [0.0; 7];
        for i in 0..6 {
            out[i] = qd[i] / self.action_scale / over;
        }
        out[6] = if tcp.0[6] < 0.0 { -1.0 } else { 1.0 };
        Action(out)
    }
}
