//! A `fairgrasp` binary copied away from the source tree and run from another folder, with an
//! empty environment, finds the shipped policies and presets built into it (what
//! `cargo install --path .` gives a user).

use std::path::{Path, PathBuf};
use std::process::Command;

use fairgrasp_env::EnvConfig;
use serde_json::Value;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under cargo's test temp dir.
fn fresh(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_copied_binary_run_elsewhere_compares_the_built_in_policies_on_a_built_in_preset() {
    let root = fresh("shipped-assets");
    let (bin, work, tmp) = (root.join("bin"), root.join("work"), root.join("tmp"));
    for d in [&bin, &work, &tmp] {
        std::fs::create_dir_all(d).unwrap();
    }
    let exe = bin.join("fairgrasp");
    std::fs::copy(env!("CARGO_BIN_EXE_fairgrasp"), &exe).unwrap();
    let out = Command::new(&exe)
        .current_dir(&work)
        .env_clear()
        .env("TMPDIR", &tmp)
        .args([
            "compare",
            "--policy",
            "all",
            "--preset",
            "fixed",
            "--episodes",
            "1",
            "--threads",
            "1",
            "--out",
            "cmp",
            "--json",
        ])
        .output()
        .expect("the copied binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let names = [
        "residual_miscalibrated",
        "residual_miscalibrated_b",
        "residual_nudged",
        "residual_wrist_camera",
        "residual_heavy_slippery",
        "residual_generalist",
        "pure_full",
        "residual_hard",
    ];
    let mut methods = vec![
        "scripted baseline".to_string(),
        "closed-loop script".into(),
        "oracle script".into(),
        "script + calibration".into(),
        "script + tuned grip".into(),
    ];
    methods.extend(names.iter().map(|n| {
        let mode = n.split('_').next().unwrap();
        format!("{mode} PPO: {n}")
    }));
    assert_eq!(v["methods"], serde_json::json!(methods));

    // The learned policies are the shipped bytes, unpacked under TMPDIR: nothing is read from
    // the source tree the binary was built in.
    for (i, name) in names.iter().enumerate() {
        let policy = PathBuf::from(v["results"][i + 5]["policy"].as_str().unwrap());
        assert!(
            policy.starts_with(&tmp) && !policy.starts_with(repo().join("assets")),
            "{}",
            policy.display()
        );
        for file in ["meta.json", "model.bpk"] {
            let shipped = repo()
                .join("assets/policies")
                .join(name)
                .join("checkpoint")
                .join(file);
            assert_eq!(
                std::fs::read(policy.join(file)).unwrap(),
                std::fs::read(&shipped).unwrap(),
                "{file} of {name}"
            );
        }
        let run = PathBuf::from(v["run_folders"][i].as_str().unwrap());
        assert!(run.starts_with(&tmp) && run.join("metrics.csv").is_file());
    }

    // The preset is the built-in `fixed`, and the files landed in the working folder.
    let config: EnvConfig = toml::from_str(v["preset_configs"]["fixed"].as_str().unwrap()).unwrap();
    let shipped = std::fs::read_to_string(repo().join("assets/configs/fixed.toml")).unwrap();
    assert_eq!(config, EnvConfig::from_toml_str(&shipped).unwrap());
    for file in ["compare.json", "compare.csv", "report.md", "report.ipynb"] {
        assert!(work.join("cmp").join(file).is_file(), "{file} missing");
    }
    std::fs::remove_dir_all(&root).ok();
}
