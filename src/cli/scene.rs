//! `fairgrasp scene`: the scene's numbers, and every contact right after a reset — what counts
//! as a collision, what is ignored and why — over one or many reset seeds.

use std::process::ExitCode;

use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_env::env::diagnostics::{SceneDiagnosis, diagnose_scene};
use fairgrasp_types::ArmSimulation;

use super::baseline::preset_config;

#[derive(Args, Debug)]
pub struct SceneArgs {
    /// Preset name or env config (.toml).
    #[arg(long, default_value = "sector", value_parser = super::args::preset)]
    preset: String,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmSimulation,
    /// Reset seed of the scene shown in detail, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    /// Also check this many resets (seeds 0..N), 0–1000000, and count those that start in a
    /// collision.
    #[arg(long, default_value_t = 0, value_parser = super::args::scenario_count)]
    seeds: usize,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(a: &SceneArgs) -> anyhow::Result<ExitCode> {
    let config = preset_config(&a.preset, a.arm)?;
    let d = diagnose_scene(&config, a.seed, a.seeds as u64)?;
    let bad_now = d.start_is_bad();
    if a.json {
        let mut v = serde_json::to_value(&d)?;
        if let Some(v) = v.as_object_mut() {
            v.insert("preset".into(), a.preset.clone().into());
        }
        println!("{v}");
    } else {
        print_scene_numbers(a, &config, &d);
        print_contacts(&d);
        print_capsule_overlaps(&d);
        if a.seeds > 0 {
            print_bad_starts(a.seeds, &d);
        }
        if bad_now {
            println!(
                "\nThis start is broken: fix the config (move the cube, shrink the shapes) before \
                 training on it."
            );
        }
    }
    Ok(if bad_now || !d.bad_starts.is_empty() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The scene's numbers: table, cube (where the reset put it, in `base_link`), gripper and
/// physics step; and why fairgrasp refuses this start, if it does.
fn print_scene_numbers(a: &SceneArgs, config: &EnvConfig, d: &SceneDiagnosis) {
    let s = &config.scene;
    let p = &config.physics;
    println!(
        "Scene of `{}` ({} arm), reset seed {}",
        a.preset, a.arm, a.seed
    );
    println!(
        "  table    top {:.3} m above the floor, {:.2} × {:.2} m, friction {}",
        s.table_height, s.table_size[0], s.table_size[1], s.table_friction
    );
    println!(
        "  cube     {:.3} m, {:.3} kg, friction {} (before randomisation), at ({:.3}, {:.3}, {:.3}) m in base_link",
        s.cube_size,
        s.cube_mass,
        s.cube_friction,
        d.object_xyz_base[0],
        d.object_xyz_base[1],
        d.object_xyz_base[2]
    );
    println!(
        "  gripper  {} N squeeze per finger, pad friction {}, opening 0–{:.0} mm",
        config.gripper.force,
        config.gripper.pad_friction,
        1e3 * d.max_opening_m
    );
    println!(
        "  physics  dt {:.5} s × {} substeps = {:.4} s per env step, {} solver iterations",
        p.dt,
        p.substeps,
        p.dt * p.substeps as f64,
        p.solver_iterations
    );
    if let Some(why) = &d.refused {
        println!("\nfairgrasp refuses this start at reset: {why}");
        println!("Shown anyway, forced to the config's own cube position:");
    }
}

/// Every contact after the reset and one step holding still, with its distance \[mm\] and
/// verdict; how far the cube was pushed from its spawn; the pairs never computed.
fn print_contacts(d: &SceneDiagnosis) {
    println!(
        "\nContacts after the reset and one step holding still (rapier's narrow phase; the arm's links, palm and table on their exact shapes):"
    );
    if d.contacts.is_empty() {
        println!("  none");
    }
    for c in &d.contacts {
        println!(
            "  {:>16} – {:<16} {:7.2} mm  {}",
            c.a,
            c.b,
            1e3 * c.distance_m,
            c.verdict
        );
    }
    println!(
        "  The cube is {:.2} mm from where it was spawned (resting: ~0; spawned overlapping: pushed out).",
        1e3 * d.object_pushed_m
    );
    println!(
        "  Never computed (collision groups): the base on its table, adjacent links, the \
         gripper's own parts."
    );
}

/// The kinematic model's capsules that overlap at the home pose \[mm\], each counted or
/// ignored.
fn print_capsule_overlaps(d: &SceneDiagnosis) {
    println!("\nCapsules of the kinematic model overlapping at the home pose:");
    for o in &d.capsule_overlaps_at_home {
        let verdict = if o.ignored {
            "ignored: adjacent, or a pair the arm model ignores (docs/FR3.md)"
        } else {
            "COUNTED"
        };
        println!(
            "  {:>16} – {:<16} {:5.1} mm overlap  {verdict}",
            o.a,
            o.b,
            1e3 * o.overlap_m
        );
    }
}

/// How many of the resets with seeds `0..seeds` start in a collision or with the cube touching
/// the robot, and the first ten such seeds.
fn print_bad_starts(seeds: usize, d: &SceneDiagnosis) {
    println!(
        "\n{} of {} resets (seeds 0–{}) start in a collision or with the cube touching the robot{}",
        d.bad_starts.len(),
        seeds,
        seeds - 1,
        if d.bad_starts.is_empty() {
            String::new()
        } else {
            format!(": seeds {:?}", &d.bad_starts[..d.bad_starts.len().min(10)])
        }
    );
}
