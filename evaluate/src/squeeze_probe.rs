//! What a squeezing residual learned: per episode, the grip force it commands as the lift
//! begins, beside the squeeze the cube needed and its outcome (`fairgrasp eval
//! --squeeze-chart`).
//!
//! The squeeze a cube needs per finger is its weight over twice the pad–cube friction,
//! `m·g / (2·μ)`, with `μ` the mean of the pads' and the cube's coefficients (rapier's default
//! rule for a contact's friction): below it the cube slides out of the pads as the arm lifts.

use std::sync::{Arc, Mutex, PoisonError};

use fairgrasp_env::episode::{Outcome, Policy, evaluate};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::scenario::perception::ObservedObject;
use fairgrasp_env::{Action, EnvConfig, EnvError, Observation};

/// Standard gravity \[m/s²\] (the env's world uses it).
const GRAVITY: f64 = 9.81;

/// One episode of a squeeze probe.
#[derive(Clone, Debug, PartialEq)]
pub struct SqueezeRow {
    /// The scenario's seed.
    pub seed: u64,
    /// Cube mass \[kg\].
    pub mass_kg: f64,
    /// Cube friction coefficient.
    pub friction: f64,
    /// The squeeze per finger the cube needs \[N\] ([`needed_squeeze`]).
    pub needed_n: f64,
    /// The policy's grip force per finger as the lift began \[N\] (the env's `gripper.force` for
    /// a policy without a squeeze of its own); None if it never lifted.
    pub at_lift_n: Option<f64>,
    /// The weakest grip force per finger from the lift on \[N\] (None if it never lifted).
    pub weakest_after_lift_n: Option<f64>,
    pub outcome: Outcome,
}

/// The squeeze per finger \[N\] that holds `scenario`'s cube against gravity in `config`'s
/// pads: `m·g / (2·μ)`, `μ = (pad_friction + cube friction) / 2`.
pub fn needed_squeeze(config: &EnvConfig, scenario: &Scenario) -> f64 {
    let mu = 0.5 * (config.gripper.pad_friction + scenario.friction);
    scenario.mass * GRAVITY / (2.0 * mu)
}

/// What a probe notes of one episode: its seed, the grip at lift, the weakest grip after it.
type Noted = (u64, f64, f64);

/// A policy that notes its grip force when its phase first turns to `lift`, and the weakest
/// one after that.
struct Probe<P> {
    inner: P,
    default_force: f64,
    seed: u64,
    /// The grip at lift and the weakest since, once lifting.
    lifting: Option<(f64, f64)>,
    sink: Arc<Mutex<Vec<Noted>>>,
}

impl<P> Probe<P> {
    /// Hands the finished episode's notes to the sink.
    fn flush(&mut self) {
        if let Some((at_lift, weakest)) = self.lifting.take() {
            let mut sink = self.sink.lock().unwrap_or_else(PoisonError::into_inner);
            sink.push((self.seed, at_lift, weakest));
        }
    }
}

impl<P> Drop for Probe<P> {
    fn drop(&mut self) {
        self.flush();
    }
}

impl<P: Policy> Policy for Probe<P> {
    fn reset(&mut self, seed: u64) {
        self.flush();
        self.seed = seed;
        self.inner.reset(seed);
    }
    fn act(&mut self, obs: &Observation) -> Action {
        let action = self.inner.act(obs);
        let force = self.inner.grip_force().unwrap_or(self.default_force);
        match &mut self.lifting {
            Some((_, weakest)) => *weakest = weakest.min(force),
            None if self.inner.phase() == Some("lift") => self.lifting = Some((force, force)),
            None => {}
        }
        action
    }
    fn observe_truth(&mut self, truth: &ObservedObject) {
        self.inner.observe_truth(truth);
    }
    fn gave_up(&self) -> Option<Outcome> {
        self.inner.gave_up()
    }
    fn phase(&self) -> Option<&'static str> {
        self.inner.phase()
    }
    fn grip_force(&self) -> Option<f64> {
        self.inner.grip_force()
    }
}

/// Runs a fresh policy from `make` on every scenario (as [`evaluate()`] does, on `threads`
/// threads) and returns one row per scenario, in order.
pub fn probe_squeeze<P: Policy>(
    config: &EnvConfig,
    scenarios: &[Scenario],
    threads: usize,
    make: &(dyn Fn() -> P + Sync),
) -> Result<Vec<SqueezeRow>, EnvError> {
    let sink = Arc::new(Mutex::new(Vec::new()));
    let probe = || Probe {
        inner: make(),
        default_force: config.gripper.force,
        seed: 0,
        lifting: None,
        sink: Arc::clone(&sink),
    };
    let report = evaluate(config, scenarios, threads, None, &probe, &|| {})?;
    let noted = std::mem::take(&mut *sink.lock().unwrap_or_else(PoisonError::into_inner));
    Ok(scenarios
        .iter()
        .zip(&report.results)
        .map(|(s, r)| {
            let mine = noted.iter().find(|n| n.0 == s.seed);
            SqueezeRow {
                seed: s.seed,
                mass_kg: s.mass,
                friction: s.friction,
                needed_n: needed_squeeze(config, s),
                at_lift_n: mine.map(|n| n.1),
                weakest_after_lift_n: mine.map(|n| n.2),
                outcome: r.outcome,
            }
        })
        .collect())
}

/// The rows as CSV (header `seed,mass_kg,friction,needed_n,at_lift_n,weakest_after_lift_n,
/// outcome`; the grips are empty where the episode never lifted).
pub fn squeeze_csv(rows: &[SqueezeRow]) -> String {
    let mut out =
        String::from("seed,mass_kg,friction,needed_n,at_lift_n,weakest_after_lift_n,outcome\n");
    let newtons = |f: Option<f64>| f.map_or(String::new(), |f| format!("{f:.3}"));
    for r in rows {
        out += &format!(
            "{},{:.4},{:.4},{:.3},{},{},{}\n",
            r.seed,
            r.mass_kg,
            r.friction,
            r.needed_n,
            newtons(r.at_lift_n),
            newtons(r.weakest_after_lift_n),
            r.outcome
        );
    }
    out
}

/// Pearson's correlation of the needed squeeze and the squeeze at lift over the episodes that
/// lifted (None with fewer than 3, or when either does not vary).
pub fn correlation(rows: &[SqueezeRow]) -> Option<f64> {
    let pairs: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| r.at_lift_n.map(|f| (r.needed_n, f)))
        .collect();
    let n = pairs.len() as f64;
    if pairs.len() < 3 {
        return None;
    }
    let (mx, my) = pairs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (x, y) in &pairs {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
    }
    (sxx > 1e-12 && syy > 1e-12).then(|| sxy / (sxx * syy).sqrt())
}
