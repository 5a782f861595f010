//! A minimal scripted grasp for the tests: joint-space P control toward IK targets.
#![allow(dead_code)]

use fairgrasp_env::scenario::top_down_grasp;
use fairgrasp_env::{Action, ArmSimulation, EnvConfig, Step, TaskEnv};

/// Action driving the joints toward `target` \[rad\] with gripper command `grip`.
pub fn toward(env: &TaskEnv, target: [f64; 6], grip: f64) -> Action {
    let q = env.joints();
    let scale = env.config().arm.action_scale;
    let mut a = [0.0; 7];
    for i in 0..6 {
        a[i] = ((target[i] - q[i]) * 4.0 / scale).clamp(-1.0, 1.0);
    }
    a[6] = grip;
    Action(a)
}

/// A config for the given arm model in which success never ends the episode (lift 1 m).
pub fn config(arm: ArmSimulation) -> EnvConfig {
    let mut cfg = EnvConfig::default();
    cfg.arm.model = arm;
    cfg.task.lift_height = 1.0;
    cfg.task.max_steps = 400;
    cfg
}

/// Runs `steps` steps toward `target`; panics on an env error; returns the last step.
pub fn drive(env: &mut TaskEnv, target: [f64; 6], grip: f64, steps: usize) -> Step {
    let mut last = None;
    for _ in 0..steps {
        let action = toward(env, target, grip);
        let step = env.step(&action).expect("step");
        assert!(
            !step.terminated && !step.truncated,
            "episode ended early: {:?}",
            step.info
        );
        last = Some(step);
    }
    last.expect("at least one step")
}

/// Grasp and pre-grasp joints for the current object, nearest to the current joints.
pub fn grasp_targets(env: &TaskEnv) -> ([f64; 6], [f64; 6]) {
    top_down_grasp(
        env.model(),
        env.mount(),
        &env.object_in_base(),
        &env.joints(),
    )
    .expect("graspable")
}

/// Joints that put the TCP 12 cm beside the grasp pose (clear of the cube) and 6.5 cm below it,
/// where the open fingers are inside the table.
pub fn beside_and_below_grasp(env: &TaskEnv) -> [f64; 6] {
    let (grasp, _) = grasp_targets(env);
    let mut below = env.model().fk_tcp(&grasp);
    below.iso.translation.vector.y += 0.12;
    below.iso.translation.vector.z -= 0.065;
    env.model()
        .ik_nearest(&below, fairgrasp_kinematics::EndFrame::Tcp, &grasp)
        .expect("valid pose")
        .expect("reachable")
        .joints
}
