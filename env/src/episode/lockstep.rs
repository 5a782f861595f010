//! Several policies on one scenario, simulated once while they agree.
//!
//! An episode is a function of its scenario and of the actions (and grip forces) its policy
//! sends: the env resets to the same state from the same scenario, and its physics is
//! deterministic. Two policies that send bit-identical actions at every step therefore have the
//! same episode — the comparison's scripts often do (the closed-loop script is the open-loop one
//! wherever the observed cube is where it was planned for; the oracle wherever the observation
//! is the truth). [`run_lockstep`] simulates the first policy (the leader) and shows every other
//! one the same observations and truths; a policy that answers with the leader's action at every
//! step gets the leader's episode without a simulation of its own, and those that ever answer
//! differently are run again from the start, the same way among themselves (the first of them
//! leads). The records are those each policy gets from
//! [`run_episode`](crate::episode::run_episode) alone (`planner/tests/lockstep.rs` checks it on
//! presets where the scripts agree and where they do not).

use crate::env::{Action, EnvError, GraspEnv};
use crate::episode::evaluate::{EpisodeRecord, Policy};
use crate::scenario::Scenario;
use crate::scenario::perception::true_object;

/// Are two answers (an action and the grip force asked with it) the same, bit for bit?
fn same_answer(x: (&Action, Option<f64>), y: (&Action, Option<f64>)) -> bool {
    let same_action =
        x.0.0
            .iter()
            .zip(y.0.0.iter())
            .all(|(a, b)| a.to_bits() == b.to_bits());
    let same_force = match (x.1, y.1) {
        (None, None) => true,
        (Some(a), Some(b)) => a.to_bits() == b.to_bits(),
        _ => false,
    };
    same_action && same_force
}

/// One episode of each of `policies` from `scenario`, in their order: the records
/// [`run_episode`](crate::episode::run_episode) gives each policy alone, with one simulation per
/// group of policies whose actions agree at every step (see the module's text). With one policy
/// it is `run_episode`.
pub fn run_lockstep<P: Policy>(
    env: &mut GraspEnv,
    policies: &mut [P],
    scenario: &Scenario,
) -> Result<Vec<EpisodeRecord>, EnvError> {
    let mut records: Vec<Option<EpisodeRecord>> = vec![None; policies.len()];
    // Each round simulates the first policy still without a record; those that parted from
    // it wait for a later round.
    let mut waiting: Vec<usize> = (0..policies.len()).collect();
    while !waiting.is_empty() {
        waiting = simulate_group(env, policies, &waiting, scenario, &mut records)?;
    }
    Ok(records.into_iter().flatten().collect())
}

/// Simulates `group[0]`'s episode, showing the others the same observations and truths; fills
/// the records of the leader and of those that agreed at every step, returns the others.
fn simulate_group<P: Policy>(
    env: &mut GraspEnv,
    policies: &mut [P],
    group: &[usize],
    scenario: &Scenario,
    records: &mut [Option<EpisodeRecord>],
) -> Result<Vec<usize>, EnvError> {
    let (leader, mut agreeing) = (group[0], group[1..].to_vec());
    let mut parted = Vec::new();
    let (mut obs, _) = env.reset_to(scenario);
    for &i in group {
        policies[i].reset(scenario.seed);
    }
    let shared = loop {
        let truth = true_object(env.mount(), &env.object_in_base());
        policies[leader].observe_truth(&truth);
        let action = policies[leader].act(&obs);
        let force = policies[leader].grip_force();
        agreeing.retain(|&i| {
            let p = &mut policies[i];
            p.observe_truth(&truth);
            let answer = p.act(&obs);
            let same = same_answer((&answer, p.grip_force()), (&action, force));
            if !same {
                parted.push(i);
            }
            same
        });
        if let Some(force) = force {
            env.set_grip_force(force)?;
        }
        let step = env.step(&action)?;
        obs = step.obs;
        if let Some(record) = step.info.episode {
            break record;
        }
    };
    for &i in std::iter::once(&leader).chain(&agreeing) {
        records[i] = Some(shared.clone().with_policy_verdict(policies[i].gave_up()));
    }
    parted.sort_unstable();
    Ok(parted)
}
