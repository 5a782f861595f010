//! The vectorised step allocates nothing of its own in steady state.
//!
//! What is counted: every heap allocation (`alloc`, `alloc_zeroed`, `realloc`) made by any thread
//! of this test process, worker threads included, through a counting global allocator, while the
//! measured steps run. The grasp envs and the scripted baseline may allocate inside their own
//! `step`/`reset`/`act` (rapier, the grasp planner); that part is measured separately by doing
//! exactly the same work one env at a time (same episode seeds, same actions), and the test
//! asserts that the vectorised path (`VecEnv`, `TaskVecEnv` and the `StepBatch` it hands to PPO)
//! adds exactly zero allocations to it. This file holds one test so no other test's allocations
//! are counted.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

use fairgrasp_env::episode::Policy;
use fairgrasp_env::vec::VecEnv;
use fairgrasp_env::{Action, EnvConfig, TaskEnv, config::presets};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig, Mode};
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::vec_api::VecEnvironment;

struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; only a counter is added.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made (by every thread) while `f` runs.
fn allocations(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    f();
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

/// The fewest allocations of three identical measurements (each builds its envs anew, so each
/// makes the same allocations): the counter sees every thread of the process, and the test
/// harness's own threads now and then allocate during one (a CI run counted 4 more for the
/// envs alone than for VecEnv, and none in the next runs); such noise only ever adds.
fn fewest(measure: impl Fn() -> u64) -> u64 {
    (0..3).map(|_| measure()).min().unwrap()
}

const N_ENVS: usize = 4;
const THREADS: usize = 2;
const BASE_SEED: u64 = 7;
/// Steps before counting: every env has ended and auto-reset an episode by then.
const WARM_UP: usize = 25;
/// Counted steps.
const MEASURED: usize = 40;

fn config() -> EnvConfig {
    let mut c = presets::load("full").unwrap();
    c.task.max_steps = 10;
    c
}

/// Env `e`'s action: exactly representable in f32, so the pure agent hands the env the same f64.
fn action(e: usize) -> [f32; ACT_DIM] {
    [0.25 * e as f32 - 0.5, 0.5, -0.25, 0.0, 0.125, 0.0, -1.0]
}

/// One env stepped alone, auto-resetting with the vectorised env's seeds
/// (`BASE_SEED + e · 1 000 000 + k`); with `baseline`, the baseline acts on every observation
/// (and on an ended episode's last one) and its action is what the env receives.
struct Alone {
    env: TaskEnv,
    e: usize,
    episodes: u64,
    baseline: Option<ScriptedGrasp>,
    next: Action,
}

impl Alone {
    fn new(config: &EnvConfig, e: usize, with_baseline: bool) -> Self {
        let mut alone = Self {
            env: TaskEnv::new(config.clone()).unwrap(),
            e,
            episodes: 0,
            baseline: with_baseline.then(|| ScriptedGrasp::new(config, BaselineConfig::default())),
            next: Action(action(e).map(f64::from)),
        };
        alone.start();
        alone
    }

    fn start(&mut self) {
        let seed = BASE_SEED + self.e as u64 * 1_000_000 + self.episodes;
        self.episodes += 1;
        let (obs, _) = self.env.reset(seed).unwrap();
        if let Some(b) = &mut self.baseline {
            b.reset(seed);
            self.next = b.act(&obs);
        }
    }

    fn step(&mut self) {
        let step = self.env.step(&self.next).unwrap();
        if step.terminated || step.truncated {
            if let Some(b) = &mut self.baseline {
                b.act(&step.obs);
            }
            self.start();
        } else if let Some(b) = &mut self.baseline {
            self.next = b.act(&step.obs);
        }
    }
}

/// Allocations of `MEASURED` steps of every env alone, after `WARM_UP` steps.
fn alone(config: &EnvConfig, with_baseline: bool) -> u64 {
    (0..N_ENVS)
        .map(|e| {
            let mut run = Alone::new(config, e, with_baseline);
            (0..WARM_UP).for_each(|_| run.step());
            allocations(|| (0..MEASURED).for_each(|_| run.step()))
        })
        .sum()
}

fn vec_env(config: &EnvConfig) -> u64 {
    let mut v = VecEnv::new(config, N_ENVS, THREADS, BASE_SEED).unwrap();
    let actions: Vec<Action> = (0..N_ENVS)
        .map(|e| Action(action(e).map(f64::from)))
        .collect();
    v.reset().unwrap();
    for _ in 0..WARM_UP {
        v.step(&actions).unwrap();
    }
    allocations(|| {
        for _ in 0..MEASURED {
            v.step(&actions).unwrap();
        }
    })
}

fn grasp_vec_env(config: &EnvConfig, mode: Mode) -> u64 {
    let agent = AgentConfig {
        mode,
        ..AgentConfig::default()
    };
    let mut v = TaskVecEnv::new(config, agent, N_ENVS, THREADS, BASE_SEED).unwrap();
    // Pure: the fixed actions; residual: a zero correction, so the env gets the baseline's.
    let actions: Vec<f32> = match mode {
        Mode::Pure => (0..N_ENVS).flat_map(action).collect(),
        Mode::Residual => vec![0.0; N_ENVS * ACT_DIM],
    };
    v.reset().unwrap();
    for _ in 0..WARM_UP {
        v.step(&actions).unwrap();
    }
    allocations(|| {
        for _ in 0..MEASURED {
            v.step(&actions).unwrap();
        }
    })
}

#[test]
fn a_vectorised_step_adds_no_allocation_to_the_envs_own() {
    let config = config();
    let envs_alone = fewest(|| alone(&config, false));
    let envs_and_baselines_alone = fewest(|| alone(&config, true));
    let vec = fewest(|| vec_env(&config));
    let pure = fewest(|| grasp_vec_env(&config, Mode::Pure));
    let residual = fewest(|| grasp_vec_env(&config, Mode::Residual));
    eprintln!(
        "allocations over {MEASURED} steps × {N_ENVS} envs ({THREADS} threads): envs alone \
         {envs_alone}, VecEnv {vec}, TaskVecEnv pure {pure}; envs + baselines alone \
         {envs_and_baselines_alone}, TaskVecEnv residual {residual}"
    );
    assert_eq!(vec, envs_alone, "VecEnv's own allocations");
    assert_eq!(
        pure, envs_alone,
        "TaskVecEnv's own allocations (pure agent)"
    );
    assert_eq!(
        residual, envs_and_baselines_alone,
        "TaskVecEnv's own allocations (residual agent)"
    );
}
