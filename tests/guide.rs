//! Every `fairgrasp …` command in the docs runs as written, with small budgets, in order: the
//! fenced lines of every page in `docs/` (the student's guides included) and of the README, where
//! `cargo run --release -- CMD` stands for `fairgrasp CMD`. Each page runs in a scratch folder of
//! its own that holds a copy of the repository's `assets/`, so a command can only write there.
//! The two guides, and the two READMEs, must list the same commands.

use std::path::{Component, Path, PathBuf};
use std::process::Command;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The `fairgrasp …` lines inside fenced code blocks, in order (`cargo run --release -- CMD`
/// read as `fairgrasp CMD`).
fn page_commands(file: &str) -> Vec<String> {
    let path = repo().join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if !fenced {
            continue;
        }
        if line.starts_with("fairgrasp ") {
            out.push(line.to_string());
        } else if let Some(rest) = line.strip_prefix("cargo run --release -- ") {
            out.push(format!("fairgrasp {rest}"));
        }
    }
    assert!(!fenced, "{file}: unclosed code fence");
    out
}

/// The pages of `docs/` whose commands run here: every `.md` but the Chinese translations (whose
/// commands must equal their English page's, checked below).
fn docs_pages() -> Vec<String> {
    let mut pages: Vec<String> = std::fs::read_dir(repo().join("docs"))
        .expect("docs/ exists")
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md") && !name.ends_with(".zh-CN.md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    pages.sort();
    pages
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

/// The command of a line, without its `# comment`.
fn command_part(line: &str) -> &str {
    line.split_once('#')
        .map_or(line, |(command, _)| command)
        .trim()
}

/// The command's arguments with a small budget, and the exit code the page promises
/// (`# exits N` in the line's comment; 0 without one).
fn budgeted(line: &str) -> (Vec<String>, i32) {
    let (command, comment) = line.split_once('#').unwrap_or((line, ""));
    let expected = comment
        .split_once("exits ")
        .map(|(_, rest)| {
            let code: String = rest.chars().take_while(char::is_ascii_digit).collect();
            code.parse().expect("a number after `exits`")
        })
        .unwrap_or(0);
    let mut args: Vec<String> = command
        .split_whitespace()
        .skip(1)
        .map(String::from)
        .collect();
    match args[0].as_str() {
        "train" => cap(&mut args, "--timesteps", 2048),
        "baseline" | "eval" => cap(&mut args, "--episodes", 4),
        "compare" => cap(&mut args, "--episodes", 2),
        "tune" if !args.iter().any(|a| a == "--list") => {
            cap(&mut args, "--budget", 1500);
            cap(&mut args, "--episodes", 2);
            cap(&mut args, "--validation-episodes", 2);
            cap(&mut args, "--finalists", 1);
        }
        "scene" if args.iter().any(|a| a == "--seeds") => cap(&mut args, "--seeds", 10),
        "bench" if args[1] == "env" => {
            cap(&mut args, "--steps", 20);
            cap(&mut args, "--resets", 5);
        }
        "bench" if args[1] == "ppo" => cap(&mut args, "--iterations", 1),
        "bench" if args[1] == "soak" => cap(&mut args, "--steps", 100),
        "bench" if args[1] == "ik" => cap(&mut args, "--poses", 200),
        _ => {}
    }
    (args, expected)
}

/// A command may read and write only below the folder it runs in: no absolute path, no `..`.
fn stays_inside(args: &[String]) -> Result<(), String> {
    for a in args {
        let p = Path::new(a);
        if p.is_absolute() || p.components().any(|c| c == Component::ParentDir) {
            return Err(format!(
                "`{a}` reaches outside the folder the command runs in"
            ));
        }
    }
    Ok(())
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Runs every command of `page` in order in a fresh scratch folder holding a copy of `assets/`,
/// and returns that folder (removed by [`Scratch`]'s drop unless the test failed).
fn run_page(page: &str) -> Scratch {
    let name = page.replace(['/', '.'], "_");
    let dir =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("docs-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    copy_dir(&repo().join("assets"), &dir.join("assets"));
    let commands = page_commands(page);
    assert!(!commands.is_empty(), "{page} has no `fairgrasp` command");
    for line in commands {
        let (args, expected) = budgeted(&line);
        if let Err(e) = stays_inside(&args) {
            panic!("{page}: `{line}`: {e}");
        }
        let out = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .expect("the binary runs");
        assert_eq!(
            out.status.code(),
            Some(expected),
            "{page}: `{line}` (run as {args:?} in {}):\n{}\n{}",
            dir.display(),
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    Scratch(dir)
}

/// A page's scratch folder; removed when the test passes, kept for a look when it fails.
struct Scratch(PathBuf);

impl Scratch {
    /// Asserts that the page's commands wrote each of `files` (relative to the folder).
    fn has(&self, page: &str, files: &[&str]) {
        for file in files {
            assert!(
                self.0.join(file).is_file(),
                "{page}: {file} was not written"
            );
        }
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            std::fs::remove_dir_all(&self.0).ok();
        }
    }
}

#[test]
fn both_guides_list_the_same_commands() {
    let en = page_commands("docs/GUIDE.md");
    let zh = page_commands("docs/GUIDE.zh-CN.md");
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
fn both_readmes_list_the_same_commands() {
    let commands = |page| -> Vec<String> {
        page_commands(page)
            .iter()
            .map(|line| command_part(line).to_string())
            .collect()
    };
    let (en, zh) = (commands("README.md"), commands("README.zh-CN.md"));
    assert_eq!(
        en, zh,
        "README.zh-CN.md must show the same commands as README.md"
    );
    assert!(
        en.iter().any(|c| c == "fairgrasp compare"),
        "the README's main command is `cargo run --release -- compare`: {en:?}"
    );
}

/// Every page that holds `fairgrasp` commands is one of the pages the tests below run; a new
/// page needs its test here.
#[test]
fn every_docs_page_with_commands_is_run() {
    let run = [
        "docs/GUIDE.md",
        "docs/baseline.md",
        "docs/contact.md",
        "docs/env.md",
        "docs/index.md",
        "docs/kinematics.md",
        "docs/performance.md",
        "docs/place.md",
        "docs/pure-ppo-in-ten-minutes.md",
        "docs/python.md",
        "docs/real_cell.md",
        "docs/reliability.md",
        "docs/replay-and-tensorboard.md",
        "docs/report.md",
        "docs/rl.md",
        "docs/stack.md",
    ];
    for page in docs_pages() {
        if !page_commands(&page).is_empty() {
            assert!(
                run.contains(&page.as_str()),
                "{page} has commands no test runs"
            );
        }
    }
    for page in run {
        assert!(
            !page_commands(page).is_empty(),
            "{page} has no commands to run"
        );
    }
}

#[test]
fn readme_commands_run_as_written() {
    run_page("README.md").has(
        "README.md",
        &[
            "report/compare.csv",
            "report/report.ipynb",
            "report/success_rate.png",
        ],
    );
}

#[test]
fn guide_commands_run_as_written() {
    // The commands' outputs exist where the guide says they are.
    run_page("docs/GUIDE.md").has(
        "docs/GUIDE.md",
        &[
            "runs/look/episode_0000.gif",
            "runs/look/episode_0000_step40.png",
            "runs/residual_again/plots/learning_curves.png",
            "report/report.ipynb",
            "my_report/report.md",
            "pitfall4.png",
            "runs/hard20/episode_0003.png",
        ],
    );
}

#[test]
fn replay_and_tensorboard_commands_run_as_written() {
    run_page("docs/replay-and-tensorboard.md").has(
        "docs/replay-and-tensorboard.md",
        &[
            "replay.html",
            "residual_vs_script.html",
            "runs/pure_full/metrics.csv",
        ],
    );
}

#[test]
fn index_commands_run_as_written() {
    run_page("docs/index.md");
}

#[test]
fn kinematics_commands_run_as_written() {
    run_page("docs/kinematics.md");
}

#[test]
fn env_commands_run_as_written() {
    run_page("docs/env.md").has("docs/env.md", &["runs/one/episode_0000.csv"]);
}

#[test]
fn baseline_commands_run_as_written() {
    run_page("docs/baseline.md");
}

#[test]
fn place_commands_run_as_written() {
    run_page("docs/place.md");
}

#[test]
fn stack_commands_run_as_written() {
    run_page("docs/stack.md");
}

#[test]
fn rl_commands_run_as_written() {
    run_page("docs/rl.md").has(
        "docs/rl.md",
        &[
            "runs/res_miscalibrated_s0/metrics.csv",
            "runs/pure_full_s1/checkpoints/best/meta.json",
        ],
    );
}

#[test]
fn ten_minute_pure_ppo_commands_run_as_written() {
    run_page("docs/pure-ppo-in-ten-minutes.md").has(
        "docs/pure-ppo-in-ten-minutes.md",
        &["runs/pure_full_10min_s1/checkpoints/best/meta.json"],
    );
}

#[test]
fn contact_commands_run_as_written() {
    run_page("docs/contact.md").has(
        "docs/contact.md",
        &[
            "runs/res_heavy_s0/checkpoints/best/meta.json",
            "runs/compare_heavy/report.md",
            "squeeze.png",
            "squeeze.csv",
        ],
    );
}

#[test]
fn report_commands_run_as_written() {
    run_page("docs/report.md").has(
        "docs/report.md",
        &[
            "report/compare.json",
            "my_report/report.md",
            "curves.png",
            "final_report/report.ipynb",
            "look/episode_0000_step53.png",
        ],
    );
}

#[test]
fn python_commands_run_as_written() {
    run_page("docs/python.md");
}

#[test]
fn reliability_commands_run_as_written() {
    run_page("docs/reliability.md").has(
        "docs/reliability.md",
        &[
            "runs/r/checkpoints/latest/checksum",
            "runs/r.replaced-1/metrics.csv",
        ],
    );
}

#[test]
fn performance_commands_run_as_written() {
    run_page("docs/performance.md");
}

#[test]
fn real_cell_commands_run_as_written() {
    run_page("docs/real_cell.md").has("docs/real_cell.md", &["my_cell.toml"]);
}
