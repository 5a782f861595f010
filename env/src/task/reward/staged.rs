//! The staged dense reward (`task.reward = "staged"`): reach, grasp, lift, success — bounded per
//! step, for learning from scratch.
//!
//! The pattern is the one that makes pick-up learnable in public benchmarks: ManiSkill's
//! `PickCube` (reach `1 − tanh(5·d)`, a grasped term, shaping toward the goal gated on the grasp,
//! normalised per step, success worth the maximum), robosuite's `Lift` (reach `1 − tanh(10·d)`,
//! a grasp bonus, a lifted bonus) and Isaac Lab's Franka lift (reach, lifted, goal tracking gated
//! on lifting). Here, per step, with `d` the TCP–cube distance \[m\] and `Δz` the cube's rise
//! above its resting height \[m\]:
//!
//! ```text
//! r = ( reach · (1 − tanh(reach_sharpness · d))
//!     + grasped · (grasp + lift · (1 − tanh(lift_sharpness · max(0, lift_height − Δz)))) )
//!     / (reach + grasp + lift)                                      ∈ [0, 1]
//! ```
//!
//! where `grasped` means both pads touch the cube with the cube between them (the pads at least
//! half the cube's width apart: closed fingers pushing the cube with both pads on one side do
//! not count — an exploring policy finds that loophole). A success (which ends the episode) pays
//! `success` instead, a collision or protective stop `collision`. `success` must beat holding the
//! per-step maximum of 1 forever: with discount γ that is worth `1/(1 − γ)`, 20 at γ = 0.95.
//! The evaluation's success criterion does not depend on the reward.

pub use crate::config::reward::StagedReward;
use crate::task::state::{TaskState, tcp_object_distance};

/// The staged reward of a step that ended in `s` with `lift_height` \[m\] the success lift.
pub fn staged_reward(
    s: &TaskState,
    success: bool,
    collision: bool,
    lift_height: f64,
    w: &StagedReward,
) -> f64 {
    if success {
        return w.success;
    }
    if collision {
        return w.collision;
    }
    let reach = w.reach * (1.0 - (w.reach_sharpness * tcp_object_distance(s)).tanh());
    let grasped = s.pad_contact[0] && s.pad_contact[1] && s.gripper_opening >= 0.5 * s.object_size;
    let held = if grasped {
        let short = (lift_height - (s.object[2] - s.object_rest_z)).max(0.0);
        w.grasp + w.lift * (1.0 - (w.lift_sharpness * short).tanh())
    } else {
        0.0
    };
    (reach + held) / (w.reach + w.grasp + w.lift)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(distance: f64, pads: bool, lift: f64) -> TaskState {
        TaskState {
            object: [0.4, 0.0, 0.625 + lift],
            object_rest_z: 0.625,
            tcp: [0.4, 0.0, 0.625 + lift + distance],
            pad_contact: [pads, pads],
            gripper_opening: 0.05,
            object_size: 0.05,
            table_height: 0.6,
            object_xy_from_table_centre: [0.4, 0.0],
            table_half_size: [0.6, 0.6],
            place: None,
        }
    }

    #[test]
    fn each_stage_pays_more_than_the_one_before_and_a_step_never_pays_more_than_1() {
        let w = StagedReward::default();
        let r = |s: &TaskState| staged_reward(s, false, false, 0.03, &w);
        let far = r(&state(0.30, false, 0.0));
        let near = r(&state(0.01, false, 0.0));
        let grasped = r(&state(0.0, true, 0.0));
        let half_lifted = r(&state(0.0, true, 0.015));
        let lifted = r(&state(0.0, true, 0.03));
        assert!(far < near && near < grasped && grasped < half_lifted && half_lifted < lifted);
        assert!((lifted - 1.0).abs() < 1e-12, "{lifted}");
        assert!(far > 0.0 && near <= 1.0 / 3.0 + 1e-12);
        assert_eq!(
            staged_reward(&state(0.0, true, 0.0), true, false, 0.03, &w),
            20.0
        );
        assert_eq!(
            staged_reward(&state(0.0, true, 0.0), false, true, 0.03, &w),
            -1.0
        );
    }

    #[test]
    fn closed_fingers_touching_the_cube_from_one_side_are_not_a_grasp() {
        let w = StagedReward::default();
        let mut s = state(0.0, true, 0.0);
        s.gripper_opening = 0.002;
        let r = staged_reward(&s, false, false, 0.03, &w);
        assert!((r - 1.0 / 3.0).abs() < 1e-12, "{r}");
    }

    #[test]
    fn one_pad_is_not_a_grasp() {
        let w = StagedReward::default();
        let mut s = state(0.0, true, 0.02);
        s.pad_contact = [true, false];
        let r = staged_reward(&s, false, false, 0.03, &w);
        assert!((r - 1.0 / 3.0).abs() < 1e-12, "{r}");
    }
}
