//! `fairgrasp eval --squeeze-chart`: what the shipped squeezing residual learned, drawn and
//! written as rows whose physics can be checked (the squeeze a cube needs is its weight over
//! twice the pad–cube friction), and the paths it must not write are refused before anything
//! runs.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::command;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-squeeze-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn policy() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/policies/residual_heavy_slippery/checkpoint")
        .display()
        .to_string()
}

fn eval(dir: &Path, chart: &str) -> Output {
    command()
        .current_dir(dir)
        .args(["eval", "--policy", &policy(), "--preset", "heavy_slippery"])
        .args(["--episodes", "12", "--seed", "7", "--threads", "2"])
        .args(["--squeeze-chart", chart])
        .output()
        .unwrap()
}

#[test]
fn the_chart_and_its_rows_show_the_grip_against_the_squeeze_each_cube_needed() {
    let dir = temp_dir("rows");
    let out = eval(&dir, "squeeze.png");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("squeeze chart"), "{stdout}");
    let png = std::fs::read(dir.join("squeeze.png")).unwrap();
    assert!(fairgrasp_types::output::png_is_ours(&png));
    let csv = std::fs::read_to_string(dir.join("squeeze.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("seed,mass_kg,friction,needed_n,at_lift_n,weakest_after_lift_n,outcome")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12);
    let mut successes = 0;
    for r in &rows {
        let num = |i: usize| r[i].parse::<f64>().unwrap();
        let (mass, friction, needed) = (num(1), num(2), num(3));
        // heavy_slippery: 0.3–1.0 kg, μ 0.05–0.3; the pads' μ is 0.8, averaged with the cube's.
        assert!(
            (0.3..=1.0).contains(&mass) && (0.05..=0.3).contains(&friction),
            "{r:?}"
        );
        let expected = mass * 9.81 / (2.0 * 0.5 * (0.8 + friction));
        assert!((needed - expected).abs() < 0.01, "{r:?}: {expected}");
        if r[6] == "success" {
            successes += 1;
            // A lifted cube was squeezed with at least about what it needed (Coulomb's limit;
            // the squeeze keeps rising after the lift begins), and never above 12 N.
            let (at_lift, weakest) = (num(4), num(5));
            assert!(at_lift >= 0.85 * needed && at_lift <= 12.0 + 1e-9, "{r:?}");
            assert!(weakest <= at_lift + 1e-9 && weakest >= 1.0, "{r:?}");
        }
    }
    assert!(successes >= 9, "{csv}");
}

#[test]
fn paths_the_chart_must_not_write_are_refused_before_any_episode_runs() {
    let dir = temp_dir("refused");
    let not_png = eval(&dir, "squeeze.jpg");
    assert!(!not_png.status.success());
    assert!(String::from_utf8_lossy(&not_png.stderr).contains("ending in .png"));
    std::fs::write(dir.join("mine.png"), b"a user's picture").unwrap();
    let foreign = eval(&dir, "mine.png");
    assert!(!foreign.status.success());
    assert!(String::from_utf8_lossy(&foreign.stderr).contains("never replaced"));
    assert_eq!(
        std::fs::read(dir.join("mine.png")).unwrap(),
        b"a user's picture"
    );
    std::fs::write(dir.join("rows.csv"), b"keep me").unwrap();
    let csv_taken = eval(&dir, "rows.png");
    assert!(!csv_taken.status.success());
    assert!(String::from_utf8_lossy(&csv_taken.stderr).contains("rows.csv exists"));
    assert_eq!(std::fs::read(dir.join("rows.csv")).unwrap(), b"keep me");
    assert!(!dir.join("rows.png").exists());
    // Nothing ran: no episode report on stdout.
    assert!(!String::from_utf8_lossy(&csv_taken.stdout).contains("success rate"));
}
