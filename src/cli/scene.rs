//! `fairgrasp scene`: the scene's numbers, and every contact right after a reset — what counts
//! as a collision, what is ignored and why — over one or many reset seeds.

use std::process::ExitCode;

use clap::Args;
use fairgrasp_env::contacts::{PairKind, TouchingPair};
use fairgrasp_env::randomize::Scenario;
use fairgrasp_env::{Action, GraspEnv};
use serde_json::json;

use super::baseline::{ArmArg, preset_config};

#[derive(Args, Debug)]
pub struct SceneArgs {
    /// Preset name or env config (.toml).
    #[arg(long, default_value = "seed")]
    preset: String,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmArg,
    /// Reset seed of the scene shown in detail.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Also check this many resets (seeds 0..N) and count those that start in a collision.
    #[arg(long, default_value_t = 0)]
    seeds: u64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// The contacts after resetting to `scenario` and one step that holds the arm still.
/// Also returns how far the object is from where it was spawned, on the table plane [m] (a spawn
/// overlap pushes it away).
fn contacts_at_start(
    env: &mut GraspEnv,
    scenario: &Scenario,
) -> anyhow::Result<(Vec<TouchingPair>, f64)> {
    env.reset_to(scenario);
    env.step(&Action::hold_open())?;
    let after = env.object_in_base().xyz();
    let [x, y] = scenario.object_xy;
    let moved = (after[0] - x).hypot(after[1] - y);
    Ok((env.touching_pairs(), moved))
}

/// The scenario of `seed`, or the config's unchecked one and the reason it was refused.
fn scenario_or_refusal(env: &GraspEnv, seed: u64) -> (Scenario, Option<String>) {
    match Scenario::sample(env.config(), env.model(), env.base_in_world(), seed) {
        Ok(s) => (s, None),
        Err(e) => (Scenario::unchecked(env.config(), seed), Some(e.to_string())),
    }
}

fn kind_text(p: &TouchingPair) -> &'static str {
    match p.kind {
        PairKind::Collision => "COLLISION (counted)",
        PairKind::Object if p.a.is_robot() || p.b.is_robot() => "object touches the robot at spawn",
        PairKind::Object => "resting contact (not a collision)",
        PairKind::Ignored => "ignored pair",
        PairKind::Scene => "scene contact",
    }
}

/// A start is bad when something counts as a collision or the object spawned touching the robot.
fn is_bad(p: &TouchingPair) -> bool {
    p.kind == PairKind::Collision
        || (p.kind == PairKind::Object && (p.a.is_robot() || p.b.is_robot()))
}

pub fn run(a: &SceneArgs) -> anyhow::Result<ExitCode> {
    let config = preset_config(&a.preset, a.arm)?;
    let mut env = GraspEnv::new(config.clone())?;
    let model = env.model().clone();
    let (scenario, refusal) = scenario_or_refusal(&env, a.seed);
    let (pairs, moved) = contacts_at_start(&mut env, &scenario)?;
    let object = env.object_in_base().xyz();
    // Capsule pairs of the kinematic model that overlap at the home pose.
    let capsules = model.placed_capsules(&config.arm.home_joints);
    let mut overlaps = Vec::new();
    for (i, c) in capsules.iter().enumerate() {
        for d in &capsules[i + 1..] {
            let gap = fairgrasp_kinematics::collision::segment_distance(c.a, c.b, d.a, d.b)
                - c.radius
                - d.radius;
            if gap < 0.0 {
                overlaps.push((c.name, d.name, gap, model.collision_ignored(c.name, d.name)));
            }
        }
    }
    let mut bad_starts = Vec::new();
    for seed in 0..a.seeds {
        let (scenario, refused) = scenario_or_refusal(&env, seed);
        if refused.is_some() || contacts_at_start(&mut env, &scenario)?.0.iter().any(is_bad) {
            bad_starts.push(seed);
        }
    }
    let name = |p: &TouchingPair| (p.a.name(&model), p.b.name(&model));
    let bad_now = refusal.is_some() || pairs.iter().any(is_bad);
    if a.json {
        let v = json!({
            "preset": a.preset, "seed": a.seed, "refused": refusal,
            "object_xyz_base": object, "object_pushed_m": moved,
            "contacts": pairs.iter().map(|p| json!({
                "a": name(p).0, "b": name(p).1, "distance_m": p.distance, "verdict": kind_text(p),
            })).collect::<Vec<_>>(),
            "capsule_overlaps_at_home": overlaps.iter().map(|(x, y, g, ignored)| json!({
                "a": x, "b": y, "overlap_m": -g, "ignored": ignored,
            })).collect::<Vec<_>>(),
            "seeds_checked": a.seeds, "bad_starts": bad_starts,
        });
        println!("{v}");
    } else {
        let s = &config.scene;
        let p = &config.physics;
        println!(
            "Scene of `{}` ({:?} arm), reset seed {}",
            a.preset, a.arm, a.seed
        );
        println!(
            "  table    top {:.3} m above the floor, {:.2} × {:.2} m, friction {}",
            s.table_height, s.table_size[0], s.table_size[1], s.table_friction
        );
        println!(
            "  cube     {:.3} m, {:.3} kg, friction {} (before randomisation), at ({:.3}, {:.3}, {:.3}) m in base_link",
            s.cube_size, s.cube_mass, s.cube_friction, object[0], object[1], object[2]
        );
        println!(
            "  gripper  {} N squeeze per finger, pad friction {}, opening 0–{:.0} mm",
            config.gripper.force,
            config.gripper.pad_friction,
            1e3 * model.gripper.opening(0.0)
        );
        println!(
            "  physics  dt {:.5} s × {} substeps = {:.4} s per env step, {} solver iterations",
            p.dt,
            p.substeps,
            p.dt * p.substeps as f64,
            p.solver_iterations
        );
        if let Some(why) = &refusal {
            println!("\nfairgrasp refuses this start at reset: {why}");
            println!("Shown anyway, forced to the config's own cube position:");
        }
        println!("\nContacts after the reset and one step holding still (rapier narrow phase):");
        if pairs.is_empty() {
            println!("  none");
        }
        for p in &pairs {
            let (x, y) = name(p);
            println!(
                "  {x:>16} – {y:<16} {:7.2} mm  {}",
                1e3 * p.distance,
                kind_text(p)
            );
        }
        println!(
            "  The cube is {:.2} mm from where it was spawned (resting: ~0; spawned overlapping: pushed out).",
            1e3 * moved
        );
        println!(
            "  Never computed (collision groups): the base on its table, adjacent links, the \
             gripper's own parts."
        );
        println!("\nCapsules of the kinematic model overlapping at the home pose:");
        for (x, y, gap, ignored) in &overlaps {
            let verdict = if *ignored {
                "ignored: adjacent or listed in FR3.md"
            } else {
                "COUNTED"
            };
            println!("  {x:>16} – {y:<16} {:7.1} mm  {verdict}", 1e3 * gap);
        }
        if a.seeds > 0 {
            println!(
                "\n{} of {} resets (seeds 0–{}) start in a collision or with the cube touching the robot{}",
                bad_starts.len(),
                a.seeds,
                a.seeds - 1,
                if bad_starts.is_empty() {
                    String::new()
                } else {
                    format!(": seeds {:?}", &bad_starts[..bad_starts.len().min(10)])
                }
            );
        }
        if bad_now {
            println!(
                "\nThis start is broken: fix the config (move the cube, shrink the shapes) before \
                 training on it."
            );
        }
    }
    Ok(if bad_now || !bad_starts.is_empty() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
