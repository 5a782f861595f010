//! Every `fairgrasp …` command in the guides (docs/GUIDE.md and docs/GUIDE.zh-CN.md) runs as
//! written, with small budgets, in order, from a scratch folder that sees the repository's
//! `assets/`. Both guides must list the same commands.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The `fairgrasp …` lines inside fenced code blocks, in order.
fn guide_commands(file: &str) -> Vec<String> {
    let path = repo().join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced && line.starts_with("fairgrasp ") {
            out.push(line.to_string());
        }
    }
    assert!(!fenced, "{file}: unclosed code fence");
    out
}

/// Sets `flag` to `min(current, cap)`, or adds it with `cap`.
fn cap(args: &mut Vec<String>, flag: &str, cap: u64) {
    match args.iter().position(|a| a == flag) {
        Some(i) => {
            let v: u64 = args[i + 1].parse().expect("a number after the flag");
            args[i + 1] = v.min(cap).to_string();
        }
        None => args.extend([flag.to_string(), cap.to_string()]),
    }
}

/// The command's arguments with a small budget, and the exit code the guide promises.
fn budgeted(line: &str) -> (Vec<String>, i32) {
    let (command, comment) = line.split_once('#').unwrap_or((line, ""));
    let expected = if comment.contains("exits 1") { 1 } else { 0 };
    let mut args: Vec<String> = command
        .split_whitespace()
        .skip(1)
        .map(String::from)
        .collect();
    match args[0].as_str() {
        "train" => args.extend(["--timesteps".into(), "2048".into()]),
        "baseline" | "eval" => cap(&mut args, "--episodes", 4),
        "compare" => cap(&mut args, "--episodes", 2),
        "scene" if args.iter().any(|a| a == "--seeds") => cap(&mut args, "--seeds", 10),
        "bench" if args[1] == "env" => {
            cap(&mut args, "--steps", 20);
            cap(&mut args, "--resets", 5);
        }
        "bench" if args[1] == "ppo" => cap(&mut args, "--iterations", 1),
        _ => {}
    }
    (args, expected)
}

#[test]
fn both_guides_list_the_same_commands() {
    let en = guide_commands("docs/GUIDE.md");
    let zh = guide_commands("docs/GUIDE.zh-CN.md");
    assert!(en.len() >= 30, "only {} commands in GUIDE.md", en.len());
    assert_eq!(
        en, zh,
        "GUIDE.zh-CN.md must run the same commands as GUIDE.md"
    );
    for sub in [
        "joints", "scene", "frames", "fk", "train", "eval", "compare", "report", "plot",
    ] {
        assert!(
            en.iter().any(|c| c.split_whitespace().nth(1) == Some(sub)),
            "the guide never runs `fairgrasp {sub}`"
        );
    }
    for n in [1, 2, 3, 4, 5] {
        assert!(
            en.iter()
                .any(|c| c.contains(&format!("assets/configs/pitfall{n}"))
                    || (n == 2 && c.contains("pure_hard"))),
            "pitfall {n} has no command with its config"
        );
    }
}

#[test]
fn every_guide_command_runs_as_written() {
    let scratch: PathBuf = Path::new(env!("CARGO_TARGET_TMPDIR")).join("guide");
    std::fs::remove_dir_all(&scratch).ok();
    std::fs::create_dir_all(&scratch).unwrap();
    std::os::unix::fs::symlink(repo().join("assets"), scratch.join("assets")).unwrap();
    for line in guide_commands("docs/GUIDE.md") {
        let (args, expected) = budgeted(&line);
        let out = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
            .args(&args)
            .current_dir(&scratch)
            .output()
            .expect("the binary runs");
        assert_eq!(
            out.status.code(),
            Some(expected),
            "`{line}` (run as {args:?}):\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    // The commands' outputs exist where the guide says they are.
    for file in [
        "runs/look/episode_0000.gif",
        "runs/look/episode_0000_step40.png",
        "runs/residual_again/plots/learning_curves.png",
        "report/report.ipynb",
        "my_report/report.md",
        "pitfall4.png",
        "runs/hard20/episode_0003.png",
    ] {
        assert!(scratch.join(file).is_file(), "{file} was not written");
    }
}
