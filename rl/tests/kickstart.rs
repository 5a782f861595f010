//! Kickstarting: the teachers' term pulls the policy to their actions on the entries they label,
//! for the raw inputs the rollout met, and ignores the entries they mask out; the generalist's
//! teachers label the entries their agents command; a run with a teacher that does not fit is
//! refused before its folder is touched.

use burn::tensor::Device;
use fairgrasp_policy::checkpoint::load_actor;
use fairgrasp_policy::recipe::EnvFor;
use fairgrasp_policy::shipped::ShippedPolicy;
use fairgrasp_rl::agent::grasp_agent::ACT_DIM;
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::free_env::FreeEnv;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::ppo::normalizer::RunningNorm;
use fairgrasp_rl::ppo::teacher::{Kickstart, Teacher};
use fairgrasp_rl::ppo::vec_api::VecEnvironment;
use fairgrasp_rl::ppo::{Ppo, PpoConfig};
use fairgrasp_rl::run::kickstart::{self, KickstartConfig};
use fairgrasp_rl::run::train::{TrainConfig, train};

/// Labels entry 0 with 0.5 in every env; writes 3 into entry 1's target but masks it out (no
/// opinion there).
struct HalfOnEntryZero;
impl Teacher for HalfOnEntryZero {
    fn label(&self, _env: usize, _input: &[f32], target: &mut [f32], mask: &mut [f32]) {
        target[0] = 0.5;
        mask[0] = 1.0;
        target[1] = 3.0;
    }
}

/// Labels entry 2 with the raw input's first value (its label depends on the state).
struct EchoFirstInput;
impl Teacher for EchoFirstInput {
    fn label(&self, _env: usize, input: &[f32], target: &mut [f32], mask: &mut [f32]) {
        target[2] = input[0];
        mask[2] = 1.0;
    }
}

/// PPO on the free env (30 inputs `((t + 7·e + d) mod 13) · 0.1`, a constant reward).
fn free_ppo() -> (FreeEnv, Ppo) {
    let env = FreeEnv::new(4, 30, ACT_DIM);
    let device = Device::flex().autodiff();
    let config = PpoConfig {
        n_steps: 32,
        batch_size: 64,
        n_epochs: 2,
        learning_rate: 1e-3,
        ..PpoConfig::default()
    };
    let model = ActorCritic::new(30, ACT_DIM, &ModelConfig::default(), 3, &device);
    (
        env,
        Ppo::new(config, model, RunningNorm::new(30, true), device, 3),
    )
}

/// The free env's raw input at time `t` for env `e`.
fn free_input(t: usize, e: usize) -> Vec<f32> {
    (0..30)
        .map(|d| ((t + 7 * e + d) % 13) as f32 * 0.1)
        .collect()
}

/// The mean action for one of the free env's inputs after 30 updates, and the kickstarting
/// loss of the first and last update.
fn trained(kickstart: Option<Kickstart>) -> (Vec<f32>, f32, f32) {
    let (mut env, mut ppo) = free_ppo();
    ppo.kickstart = kickstart;
    let losses: Vec<f32> = (0..30)
        .map(|_| ppo.iterate(&mut env, 0.0).unwrap().kickstart_loss)
        .collect();
    (
        ppo.mean_action(&free_input(0, 0)).unwrap(),
        losses[0],
        losses[29],
    )
}

#[test]
fn kickstarting_pulls_the_labelled_entry_to_the_teacher_and_ignores_masked_labels() {
    let (alone, first, last) = trained(None);
    assert_eq!((first, last), (0.0, 0.0), "no teacher, no term");
    let (taught, first, last) = trained(Some(Kickstart {
        teacher: Box::new(HalfOnEntryZero),
        weight: 5.0,
        anneal: false,
    }));
    // The reward is a constant: PPO alone leaves entry 0 near its initial ~0.
    assert!(
        alone[0].abs() < 0.2,
        "PPO alone moved entry 0 to {}",
        alone[0]
    );
    assert!(
        (taught[0] - 0.5).abs() < 0.05,
        "entry 0 = {}, the teacher says 0.5",
        taught[0]
    );
    assert!(
        last < 0.05 * first,
        "the term fell from {first} to only {last}"
    );
    // Entry 1's target is masked out: were it used, entry 1 would head for 3.
    assert!(
        taught[1] < 1.0,
        "entry 1 = {}: pulled by a masked label",
        taught[1]
    );
}

#[test]
fn the_rollout_labels_each_sample_with_its_teachers_action_for_that_samples_raw_input() {
    // The label is the raw input's first value (0 to 1.2, by step and env). Labels from the
    // normalised input, or rows shifted against the inputs, would teach another function.
    let (mut env, mut ppo) = free_ppo();
    ppo.kickstart = Some(Kickstart {
        teacher: Box::new(EchoFirstInput),
        weight: 5.0,
        anneal: false,
    });
    for _ in 0..60 {
        ppo.iterate(&mut env, 0.0).unwrap();
    }
    let mut worst = 0.0f32;
    for (t, e) in [(0, 0), (3, 1), (5, 2), (11, 3), (8, 0), (12, 2)] {
        let input = free_input(t, e);
        let out = ppo.mean_action(&input).unwrap();
        worst = worst.max((out[2] - input[0]).abs());
    }
    assert!(
        worst < 0.1,
        "entry 2 is {worst} away from the raw input's first value"
    );
}

fn generalist() -> TrainConfig {
    TrainConfig::from_toml_file("../assets/experiments/residual_generalist.toml".as_ref()).unwrap()
}

#[test]
fn the_generalists_teachers_label_the_entries_their_agents_command_with_their_own_actions() {
    let config = generalist();
    let envs = config.env_configs(EnvFor::Evaluation).unwrap();
    let k = kickstart::load(config.kickstart.as_ref().unwrap(), &config.agent, &envs).unwrap();
    // Real inputs: one env of each preset (full, nudged, wrist_camera, heavy_slippery).
    let mut vec_env = TaskVecEnv::mixed(&envs, config.agent.clone(), 4, 1, 11).unwrap();
    let dim = vec_env.obs_dim();
    let raw = vec_env.reset().unwrap().to_vec();
    let mut targets = vec![9.0; 4 * ACT_DIM];
    let mut mask = vec![9.0; 4 * ACT_DIM];
    k.label_step(&raw, dim, ACT_DIM, &mut targets, &mut mask);
    // Offsets x, y, z, yaw and the close timing; the squeeze (4) only from the teacher that
    // has it; entry 5 is unused.
    let without = [1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0];
    let with = [1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 1.0];
    let teachers = [
        (ShippedPolicy::ResidualNudged, without),
        (ShippedPolicy::ResidualNudged, without),
        (ShippedPolicy::ResidualWristCamera, without),
        (ShippedPolicy::ResidualHeavySlippery, with),
    ];
    for (e, (policy, expected_mask)) in teachers.into_iter().enumerate() {
        let row = e * ACT_DIM..(e + 1) * ACT_DIM;
        assert_eq!(&mask[row.clone()], &expected_mask, "env {e}");
        let (meta, actor) = load_actor(&policy.checkpoint_dir().unwrap()).unwrap();
        let own = actor.mean(&meta.obs_norm.normalize(&raw[e * dim..(e + 1) * dim]));
        for j in row.clone() {
            let want = if mask[j] > 0.0 { own[j % ACT_DIM] } else { 0.0 };
            assert_eq!(targets[j], want, "env {e}, entry {}", j % ACT_DIM);
        }
    }
    // The teachers differ: on the wrist camera's env, the push's specialist would say otherwise.
    let (meta, nudged) =
        load_actor(&ShippedPolicy::ResidualNudged.checkpoint_dir().unwrap()).unwrap();
    let other = nudged.mean(&meta.obs_norm.normalize(&raw[2 * dim..3 * dim]));
    assert_ne!(&other[..4], &targets[2 * ACT_DIM..2 * ACT_DIM + 4]);
}

#[test]
fn a_run_whose_teachers_do_not_fit_is_refused_before_its_folder_is_touched() {
    let base = generalist();
    let few = TrainConfig {
        kickstart: Some(KickstartConfig {
            teachers: vec!["residual_nudged".into()],
            ..base.kickstart.clone().unwrap()
        }),
        ..base.clone()
    };
    let e = few.validate().unwrap_err();
    assert!(
        e.contains("kickstart.teachers") && e.contains("4 presets"),
        "{e}"
    );
    let weightless = TrainConfig {
        kickstart: Some(KickstartConfig {
            weight: 0.0,
            ..base.kickstart.clone().unwrap()
        }),
        ..base.clone()
    };
    let e = weightless.validate().unwrap_err();
    assert!(e.contains("kickstart.weight = 0"), "{e}");
    // A joint-space residual cannot teach a task-space one; a missing folder is named.
    let dir = std::env::temp_dir().join(format!("fg-kickstart-{}", std::process::id()));
    for (teacher, why) in [
        ("residual_hard", "differs from the run's"),
        ("no/such/checkpoint", "no/such/checkpoint"),
    ] {
        let mut teachers = base.kickstart.clone().unwrap().teachers;
        teachers[2] = teacher.into();
        let wrong = TrainConfig {
            kickstart: Some(KickstartConfig {
                teachers,
                ..base.kickstart.clone().unwrap()
            }),
            ..base.clone()
        };
        wrong.validate().unwrap();
        let e = train(&wrong, &dir, false, &mut |_| {})
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains(&format!("kickstart.teachers: {teacher}")) && e.contains(why),
            "{e}"
        );
        assert!(!dir.exists(), "the run folder was created");
    }
}
