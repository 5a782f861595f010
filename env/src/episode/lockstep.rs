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
//! [`run_episode`] alone (`planner/tests/lockstep.rs` checks it on
//! presets where the scripts agree and where they do not).

use crate::env::obs::Observation;
use crate::env::{Action, EnvError, TaskEnv};
use crate::episode::evaluate::{EpisodeRecord, Outcome, Policy, run_episode};
use crate::scenario::Scenario;
use crate::scenario::perception::ObservedObject;

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
/// [`run_episode`] gives each policy alone, with one simulation per
/// group of policies whose actions agree at every step (see the module's text). With one policy
/// it is `run_episode`.
pub fn run_lockstep<P: Policy>(
    env: &mut TaskEnv,
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
    env: &mut TaskEnv,
    policies: &mut [P],
    group: &[usize],
    scenario: &Scenario,
    records: &mut [Option<EpisodeRecord>],
) -> Result<Vec<usize>, EnvError> {
    let mut lead = Group {
        policies,
        leader: group[0],
        agreeing: group[1..].to_vec(),
        parted: Vec::new(),
    };
    // The one episode loop (`run_episode`) drives the leader; `Group` shows the others its steps.
    let shared = run_episode(env, &mut lead, scenario, None)?;
    let Group {
        policies,
        leader,
        agreeing,
        mut parted,
    } = lead;
    for &i in std::iter::once(&leader).chain(&agreeing) {
        records[i] = Some(shared.clone().with_policy_verdict(policies[i].gave_up()));
    }
    parted.sort_unstable();
    Ok(parted)
}

/// The leader as one policy: every call goes to it, and `reset`, `observe_truth` and `act` also
/// to the followers still agreeing; `act` moves a follower whose answer differs to `parted`.
struct Group<'a, P> {
    policies: &'a mut [P],
    leader: usize,
    agreeing: Vec<usize>,
    parted: Vec<usize>,
}

impl<P: Policy> Policy for Group<'_, P> {
    fn reset(&mut self, seed: u64) {
        for &i in std::iter::once(&self.leader).chain(&self.agreeing) {
            self.policies[i].reset(seed);
        }
    }
    fn act(&mut self, obs: &Observation) -> Action {
        let action = self.policies[self.leader].act(obs);
        let force = self.policies[self.leader].grip_force();
        let (policies, parted) = (&mut *self.policies, &mut self.parted);
        self.agreeing.retain(|&i| {
            let answer = policies[i].act(obs);
            let same = same_answer((&answer, policies[i].grip_force()), (&action, force));
            if !same {
                parted.push(i);
            }
            same
        });
        action
    }
    fn observe_truth(&mut self, truth: &ObservedObject) {
        for &i in std::iter::once(&self.leader).chain(&self.agreeing) {
            self.policies[i].observe_truth(truth);
        }
    }
    fn gave_up(&self) -> Option<Outcome> {
        self.policies[self.leader].gave_up()
    }
    fn phase(&self) -> Option<&'static str> {
        self.policies[self.leader].phase()
    }
    fn grip_force(&self) -> Option<f64> {
        self.policies[self.leader].grip_force()
    }
}
