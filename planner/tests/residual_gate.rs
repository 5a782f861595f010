//! The residual interface ([`ResidualScript`]) before any training: a zero residual is the
//! open-loop script exactly; a held correction moves the grasp by that much; the close can be
//! advanced and delayed; and the gate of issue 13 — a hand-written residual that knows the true
//! pose reaches ≥ 97 % on each family through the same interface.

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, Outcome, Policy, run_episode};
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{Action, EnvConfig, Observation, TaskEnv};
use fairgrasp_planner::lift::residual::{FEATURE_DIM, ResidualScript};
use fairgrasp_planner::{
    BaselineConfig, OracleResidual, Phase, ScriptedGrasp, TaskCorrection, TaskResidual,
};

const EPISODES: usize = 60;

/// A residual policy that outputs the same action every step (after `from_step`).
struct Constant {
    residual: ResidualScript,
    action: [f64; 7],
    from_step: usize,
    step: usize,
    /// Phase seen at each step, and the TCP when the close began.
    phases: Vec<Phase>,
    tcp_at_close: Option<[f64; 3]>,
    correction_at_close: Option<TaskCorrection>,
    closing_step: Option<usize>,
}

impl Constant {
    fn new(config: &EnvConfig, action: [f64; 7], from_step: usize) -> Self {
        Self {
            residual: ResidualScript::new(config),
            action,
            from_step,
            step: 0,
            phases: Vec::new(),
            tcp_at_close: None,
            correction_at_close: None,
            closing_step: None,
        }
    }
}

impl Policy for Constant {
    fn reset(&mut self, seed: u64) {
        self.residual.reset(seed);
        self.step = 0;
        self.phases.clear();
        self.tcp_at_close = None;
        self.correction_at_close = None;
        self.closing_step = None;
    }

    fn act(&mut self, obs: &Observation) -> Action {
        let a = if self.step >= self.from_step {
            self.action
        } else {
            [0.0; 7]
        };
        self.step += 1;
        let phase = self.residual.script().phase();
        if phase == Phase::Close && self.tcp_at_close.is_none() {
            self.tcp_at_close = Some(obs.tcp_position);
            self.correction_at_close = Some(self.residual.script().correction());
            self.closing_step = Some(self.phases.len());
        }
        self.phases.push(phase);
        self.residual.act(obs, &a)
    }
}

#[test]
fn a_zero_residual_is_the_open_loop_script_exactly() {
    let config = presets::load("miscalibrated").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(&config, 3, 4).unwrap();
    let mut script = ScriptedGrasp::new(&config, BaselineConfig::default());
    let mut zero = Constant::new(&config, [0.0; 7], 0);
    for s in &scenarios {
        let a = run_episode(&mut env, &mut script, s, None).unwrap();
        let b = run_episode(&mut env, &mut zero, s, None).unwrap();
        assert_eq!(a, b, "seed {}", s.seed);
    }
}

#[test]
fn a_held_correction_moves_the_grasp_by_that_much_and_is_frozen_once_closed() {
    let config = presets::load("fixed").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let s = &scenario_set(&config, 0, 1).unwrap()[0];
    let mut plain = Constant::new(&config, [0.0; 7], 0);
    run_episode(&mut env, &mut plain, s, None).unwrap();
    // +3 cm along x (0.6 × the 5 cm limit), commanded all episode.
    let mut shifted = Constant::new(&config, [0.6, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], 0);
    run_episode(&mut env, &mut shifted, s, None).unwrap();
    let (a, b) = (plain.tcp_at_close.unwrap(), shifted.tcp_at_close.unwrap());
    // base_link is the table frame on the level `fixed` mount.
    assert!(
        (b[0] - a[0] - 0.03).abs() < 0.002,
        "{a:?} → {b:?}, want +3 cm along x"
    );
    assert!(
        (b[1] - a[1]).abs() < 0.002 && (b[2] - a[2]).abs() < 0.002,
        "{a:?} → {b:?}"
    );
    // The correction stopped following the command when the gripper closed.
    let closing = shifted.correction_at_close.unwrap();
    assert_eq!(shifted.residual.script().correction(), closing);
    assert!((closing.offset[0] - 0.03).abs() < 0.001, "{closing:?}");
    assert!(shifted.phases.len() > shifted.closing_step.unwrap() + 10);
}

#[test]
fn the_close_can_be_advanced_or_delayed() {
    let config = presets::load("fixed").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let s = &scenario_set(&config, 0, 1).unwrap()[0];
    let count = |p: &Constant, phase: Phase| p.phases.iter().filter(|x| **x == phase).count();
    let mut plain = Constant::new(&config, [0.0; 7], 0);
    assert_eq!(
        run_episode(&mut env, &mut plain, s, None).unwrap().outcome,
        Outcome::Success
    );
    let descend = count(&plain, Phase::Descend);
    // Wait: the descent lasts up to max_close_delay_steps longer and the grasp still succeeds.
    let mut wait = Constant::new(&config, [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0], 0);
    let r = run_episode(&mut env, &mut wait, s, None).unwrap();
    assert_eq!(r.outcome, Outcome::Success);
    let delay = BaselineConfig::default().max_close_delay_steps;
    assert_eq!(count(&wait, Phase::Descend), descend + delay);
    // Now, from the first descent step: once the filtered command passes 0.5 (a few steps) the
    // fingers close high above the cube and miss it.
    let first_descent = plain
        .phases
        .iter()
        .position(|p| *p == Phase::Descend)
        .unwrap();
    let mut now = Constant::new(&config, [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], first_descent);
    let r = run_episode(&mut env, &mut now, s, None).unwrap();
    let early = count(&now, Phase::Descend);
    assert!(
        (2..=5).contains(&early),
        "closed after {early} of {descend} descent steps"
    );
    assert_ne!(r.outcome, Outcome::Success);
}

#[test]
fn the_features_show_a_push_and_the_correction() {
    let config = presets::load("nudged").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let s = &scenario_set(&config, 1, 1).unwrap()[0];
    let (mut obs, _) = env.reset_to(s);
    let mut residual = ResidualScript::new(&config);
    residual.reset(s.seed);
    let mut f = [0.0; FEATURE_DIM];
    let mut moved_seen = 0.0f64;
    let action = [0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for _ in 0..40 {
        let a = residual.act(&obs, &action);
        obs = env.step(&a).unwrap().obs;
        residual.write_features(&obs, &mut f);
        moved_seen = moved_seen.max(f[5].hypot(f[6]));
    }
    let nudge = s.nudge.expect("nudged scenario");
    let pushed = nudge.offset_xy[0].hypot(nudge.offset_xy[1]);
    let limits = *residual.limits();
    assert!(
        (moved_seen * limits.max_offset - pushed).abs() < 0.01,
        "seen {} m, pushed {pushed} m",
        moved_seen * limits.max_offset
    );
    // The correction feature is the integrated x rate until the close.
    assert!(f[9] > 0.0 && f[10] == 0.0, "{f:?}");
}

#[test]
fn the_oracle_residual_reaches_97_percent_on_each_family_through_the_interface() {
    for name in ["miscalibrated", "miscalibrated_b", "nudged", "wrist_camera"] {
        let config = presets::load(name).unwrap();
        let mut env = TaskEnv::new(config.clone()).unwrap();
        let scenarios = scenario_set(&config, 0, EPISODES).unwrap();
        let mut oracle = OracleResidual::new(&config);
        let results = scenarios
            .iter()
            .map(|s| run_episode(&mut env, &mut oracle, s, None).unwrap())
            .collect();
        let report = EvalReport::from_results(results);
        eprintln!(
            "{name}: oracle residual {:.3} {:?}",
            report.success_rate, report.outcomes
        );
        assert!(report.success_rate >= 0.97, "{name}: {:?}", report.outcomes);
    }
}

#[test]
fn the_wrist_view_enters_the_features_only_when_the_camera_sees_the_cube() {
    let config = presets::load("wrist_camera").unwrap();
    let range = config.randomization.wrist_camera.unwrap().range;
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let s = &scenario_set(&config, 2, 1).unwrap()[0];
    let (mut obs, _) = env.reset_to(s);
    let mut residual = ResidualScript::new(&config);
    residual.reset(s.seed);
    let mut f = [0.0; FEATURE_DIM];
    let (mut seen, mut unseen) = (0, 0);
    for _ in 0..80 {
        let a = residual.act(&obs, &[0.0; 7]);
        obs = env.step(&a).unwrap().obs;
        residual.write_features(&obs, &mut f);
        let truth = env.object_in_base().xyz();
        let d = (0..3)
            .map(|i| (truth[i] - obs.tcp_position[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        match obs.wrist_camera {
            Some(w) => {
                assert!(d <= range + 1e-9, "seen from {d} m");
                // Exact: the truth, not the fixed camera's erroneous view.
                assert!((0..3).all(|i| (w.position[i] - truth[i]).abs() < 1e-9));
                assert_eq!(f[14], 1.0);
                let planned = residual.script().planned_on().unwrap();
                let dx = (w.position[0] - planned.position[0]) / residual.limits().max_offset;
                assert!((f[15] - dx).abs() < 1e-9, "{f:?}");
                seen += 1;
            }
            None => {
                assert!(d > range, "not seen from {d} m");
                assert!(f[14..].iter().all(|v| *v == 0.0), "{f:?}");
                unseen += 1;
            }
        }
    }
    assert!(seen > 0 && unseen > 0, "seen {seen}, unseen {unseen}");
}
