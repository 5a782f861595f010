//! Streams as Unix tools treat them: output into a pipe nobody reads ends the command quietly;
//! output onto a full device is a one-line error with exit code 1. Neither is a panic. A command
//! that writes files finishes them first, whenever its stdout's or stderr's reader goes away; on
//! a full disk every such command says which disk in one `error:` line and leaves nothing
//! half-written.

use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

mod common;
use common::command;

#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    // The read end is closed before the command prints anything: its baseline runs first.
    let mut child = command()
        .args([
            "baseline",
            "--preset",
            "fixed",
            "--episodes",
            "8",
            "--threads",
            "1",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.is_empty(), "a closed pipe is not an error: {stderr}");
    // Killed by SIGPIPE, as `yes | head -1` kills `yes`.
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
}

#[test]
fn a_full_stdout_is_a_one_line_error() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = command()
        .args(["fk", "--joints", "0", "0", "0", "0", "0", "0", "--json"])
        .stdout(full)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stderr.starts_with("error: cannot write the output to stdout"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("streams-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs fairgrasp with `args` and its stdout a pipe whose read end is closed at once.
fn with_stdout_closed(args: &[&str]) -> std::process::Output {
    let mut child = command()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

#[test]
fn a_command_that_writes_files_finishes_them_when_nobody_reads_its_stdout() {
    let dir = scratch("closed");
    let recorded = dir.join("recorded");
    let out = with_stdout_closed(&[
        "baseline",
        "--preset",
        "fixed",
        "--episodes",
        "3",
        "--threads",
        "1",
        "--record",
        recorded.to_str().unwrap(),
    ]);
    assert!(recorded.join("episode_0002.json").is_file(), "{out:?}");
    // `plot` prints a line after each episode's chart and replay: a closed pipe used to end
    // it after the first, the other two episodes never drawn.
    let episodes: Vec<String> = (0..3)
        .map(|i| recorded.join(format!("episode_{i:04}.json")))
        .map(|p| p.to_str().unwrap().to_string())
        .collect();
    let mut args = vec!["plot"];
    args.extend(episodes.iter().map(String::as_str));
    let out = with_stdout_closed(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    for i in 0..3 {
        for ext in ["png", "gif"] {
            let file = recorded.join(format!("episode_{i:04}.{ext}"));
            assert!(file.is_file(), "{} missing; {stderr}", file.display());
        }
    }
    assert!(stderr.is_empty(), "a closed pipe is not an error: {stderr}");
    // Then it ends as any command ends on a closed pipe.
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
    // `compare` finishes its folder, and leaves no staging folder.
    let report = dir.join("report");
    let out = with_stdout_closed(&[
        "compare",
        "--preset",
        "fixed",
        "--episodes",
        "2",
        "--threads",
        "1",
        "--out",
        report.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("error"), "{stderr}");
    for file in [
        "report.md",
        "report.ipynb",
        "compare.csv",
        "compare.json",
        "replay.html",
    ] {
        assert!(report.join(file).is_file(), "{file} missing; {stderr}");
    }
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.contains(".partial")), "{names:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A tmpfs mounted on a new folder, unmounted when dropped; None without the permission to
/// mount.
struct SmallDisk(std::path::PathBuf);

impl SmallDisk {
    /// A disk of 1 MiB.
    fn mount() -> Option<SmallDisk> {
        SmallDisk::mount_sized("small-disk", "1m")
    }

    /// A disk of `size` (`64k`, `1m`: mount's tmpfs option) under `name`.
    fn mount_sized(name: &str, size: &str) -> Option<SmallDisk> {
        let dir = scratch(name);
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(&dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        mounted.then_some(SmallDisk(dir))
    }
}

impl Drop for SmallDisk {
    fn drop(&mut self) {
        Command::new("umount").arg(&self.0).status().ok();
        std::fs::remove_dir_all(&self.0).ok();
    }
}

#[test]
fn a_full_disk_is_named_in_the_message() {
    let Some(disk) = SmallDisk::mount() else {
        eprintln!(
            "skipped: no permission to mount a tmpfs (the note's wording is tested in src/error_message.rs)"
        );
        return;
    };
    let out = command()
        .args([
            "compare",
            "--preset",
            "fixed",
            "--episodes",
            "2",
            "--threads",
            "1",
        ])
        .arg("--out")
        .arg(disk.0.join("report"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let error = stderr
        .lines()
        .find(|l| l.starts_with("error: "))
        .unwrap_or("");
    let mounted = format!("mounted on {}: 1.0 MiB in all", disk.0.display());
    assert!(error.contains("ran out of space"), "{stderr}");
    assert!(error.contains(&mounted), "{stderr}");
    assert_eq!(
        error.matches("No space left on device").count(),
        1,
        "the OS's reason once: {error}"
    );
    // Nothing of the unfinished report is left on the disk.
    assert_eq!(std::fs::read_dir(&disk.0).unwrap().count(), 0);
}

/// A command that writes files, as a test runs it: its arguments (its output under `out`) and
/// how its finished output is checked whole.
struct FileCommand {
    name: &'static str,
    args: Vec<String>,
    out: std::path::PathBuf,
    check: fn(&std::path::Path) -> Result<(), String>,
}

/// `path` parsed as JSON, or why not.
fn json_at(path: &std::path::Path) -> Result<serde_json::Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Whether `files` are all in `dir` and each `.json`/`.ipynb` among them parses.
fn whole(dir: &std::path::Path, files: &[&str]) -> Result<(), String> {
    for file in files {
        let path = dir.join(file);
        if !path.is_file() {
            return Err(format!("{} missing", path.display()));
        }
        if file.ends_with(".json") || file.ends_with(".ipynb") {
            json_at(&path)?;
        }
    }
    Ok(())
}

fn compare_whole(dir: &std::path::Path) -> Result<(), String> {
    let files = [
        "report.md",
        "report.ipynb",
        "compare.csv",
        "compare.json",
        "replay.html",
    ];
    whole(dir, &files)
}

fn report_whole(dir: &std::path::Path) -> Result<(), String> {
    whole(dir, &["report.md", "report.ipynb"])
}

fn recording_whole(dir: &std::path::Path) -> Result<(), String> {
    whole(
        dir,
        &[
            "episode_0000.json",
            "episode_0001.json",
            "episode_0002.json",
            "episode_0002.csv",
        ],
    )
}

fn tuning_whole(dir: &std::path::Path) -> Result<(), String> {
    whole(
        dir,
        &["tune.json", "trials.csv", "finalists.csv", "tuned.toml"],
    )?;
    let tuned = std::fs::read_to_string(dir.join("tuned.toml")).map_err(|e| e.to_string())?;
    tuned
        .parse::<toml::Table>()
        .map_err(|e| format!("tuned.toml: {e}"))?;
    let trials = std::fs::read_to_string(dir.join("trials.csv")).map_err(|e| e.to_string())?;
    if trials.lines().count() < 2 || !trials.ends_with('\n') {
        return Err(format!(
            "trials.csv is not a header and whole rows: {trials:?}"
        ));
    }
    Ok(())
}

/// `report`, `compare` (its shipped policies, or `policy`), `baseline --record`, `eval --record`
/// and `tune`, each writing under `dir`; `report` reads the comparison folder `comparison`.
fn file_commands(
    dir: &std::path::Path,
    comparison: &std::path::Path,
    policy: Option<&str>,
) -> Vec<FileCommand> {
    let tiny = ["--preset", "fixed", "--episodes", "3", "--threads", "1"];
    let mut commands = Vec::new();
    let mut add = |name: &'static str, words: &[&str], out: &str, check| {
        let out = dir.join(out);
        let mut args: Vec<String> = words.iter().map(|w| w.to_string()).collect();
        args.push(out.to_str().unwrap().to_string());
        commands.push(FileCommand {
            name,
            args,
            out,
            check,
        });
    };
    let mut compare = vec!["compare", "--preset", "fixed", "--episodes", "2"];
    compare.extend(["--threads", "1"]);
    compare.extend(policy.map(|p| ["--policy", p]).into_iter().flatten());
    compare.push("--out");
    add("compare", &compare, "compared", compare_whole);
    let report = ["report", comparison.to_str().unwrap(), "--out"];
    add("report", &report, "reported", report_whole);
    let baseline = [&["baseline"][..], &tiny, &["--record"]].concat();
    add("baseline", &baseline, "baseline", recording_whole);
    let eval = [&["eval"][..], &tiny, &["--record"]].concat();
    add("eval", &eval, "evaluated", recording_whole);
    let tune = [
        "tune",
        "--preset",
        "heavy_slippery",
        "--control",
        "tuned_grip",
        "--budget",
        "2000",
        "--episodes",
        "2",
        "--validation-episodes",
        "2",
        "--finalists",
        "1",
        "--threads",
        "1",
        "--out",
    ];
    add("tune", &tune, "tuned", tuning_whole);
    commands
}

/// Which reader of a command's output closes its end, and when.
#[derive(Clone, Copy, Debug)]
enum Closing {
    /// stdout is a pipe closed before the command starts (`| true`); stderr is read.
    Stdout,
    /// stdout and stderr are one pipe closed before the command starts (`2>&1 | true`).
    Both,
    /// stdout and stderr are one pipe whose reader quits after the first line (`2>&1 |
    /// head -n 1`): the progress lines after it meet a closed pipe.
    BothAfterOneLine,
    /// stderr is a pipe closed before the command starts; stdout goes to a file.
    Stderr,
}

/// Runs `args` with its streams as `closing` says; its exit status and what stderr said (when
/// stderr is read).
fn run_with_closing(
    args: &[String],
    closing: Closing,
    dir: &std::path::Path,
) -> (std::process::ExitStatus, String) {
    let (mut read_end, write_end) = std::io::pipe().unwrap();
    let mut cmd = command();
    cmd.args(args);
    match closing {
        Closing::Stdout => cmd.stdout(write_end).stderr(Stdio::piped()),
        Closing::Both | Closing::BothAfterOneLine => {
            cmd.stdout(write_end.try_clone().unwrap()).stderr(write_end)
        }
        Closing::Stderr => {
            let file = std::fs::File::create(dir.join("stdout.txt")).unwrap();
            cmd.stdout(file).stderr(write_end)
        }
    };
    let mut child = cmd.spawn().unwrap();
    // The command's copies of the write end go with it: only the child holds one now.
    drop(cmd);
    if let Closing::BothAfterOneLine = closing {
        use std::io::Read;
        let mut byte = [0u8; 1];
        while read_end.read(&mut byte).is_ok_and(|n| n == 1) && byte[0] != b'\n' {}
    }
    drop(read_end);
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        use std::io::Read;
        e.read_to_string(&mut stderr).unwrap();
    }
    (child.wait().unwrap(), stderr)
}

/// Issue 60: `compare 2>&1 | head -n 1` panicked (exit 101) at its next progress line and left
/// no report; `tune` so too, with no tuned.toml. Every command that writes files finishes them,
/// whole, whichever of its streams' readers goes away and when, then ends quietly: by SIGPIPE
/// when its stdout was closed (as `yes | head -1` ends), with success otherwise.
#[test]
fn every_command_that_writes_files_finishes_them_whole_whichever_reader_goes_away() {
    let dir = scratch("readers");
    let comparison = tiny_comparison(&dir);
    for closing in [
        Closing::Stdout,
        Closing::Both,
        Closing::BothAfterOneLine,
        Closing::Stderr,
    ] {
        for c in file_commands(&dir, &comparison, None) {
            std::fs::remove_dir_all(&c.out).ok();
            let (status, stderr) = run_with_closing(&c.args, closing, &dir);
            let at = format!("{} with {closing:?}: {status:?}; stderr: {stderr}", c.name);
            assert!(!stderr.contains("panicked"), "{at}");
            assert!(!stderr.contains("error"), "{at}");
            if let Err(why) = (c.check)(&c.out) {
                panic!("{at}: {why}");
            }
            let quiet = match closing {
                Closing::Stdout | Closing::Both => status.signal() == Some(libc::SIGPIPE),
                // The rest of its output may have fitted in the pipe before the reader quit.
                Closing::BothAfterOneLine => {
                    status.success() || status.signal() == Some(libc::SIGPIPE)
                }
                Closing::Stderr => status.success(),
            };
            assert!(quiet, "{at}");
            let partial = std::fs::read_dir(&dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .find(|n| n.contains(".partial") || n.contains(".recording-"));
            assert_eq!(partial, None, "{at}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A comparison of two `fixed` episodes in `dir/comparison`, for `report` to read.
fn tiny_comparison(dir: &std::path::Path) -> std::path::PathBuf {
    let comparison = dir.join("comparison");
    let made = command()
        .args(["compare", "--preset", "fixed", "--episodes", "2"])
        .args(["--threads", "1", "--out"])
        .arg(&comparison)
        .output()
        .unwrap();
    assert!(made.status.success(), "{made:?}");
    comparison
}

/// Every file under `dir` but `filler` whole: no temporary or staging name, JSON that parses,
/// CSV ending in a whole row; or why not.
fn nothing_half_written(dir: &std::path::Path, filler: &std::path::Path) -> Result<(), String> {
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).map_err(|e| e.to_string())? {
            let path = entry.map_err(|e| e.to_string())?.path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path == filler {
                continue;
            }
            if [".tmp", ".partial", ".recording-"]
                .iter()
                .any(|staging| name.contains(staging))
            {
                return Err(format!("{} left", path.display()));
            }
            if path.is_dir() {
                folders.push(path);
            } else if name.ends_with(".json") || name.ends_with(".ipynb") {
                json_at(&path)?;
            } else if name.ends_with(".csv") {
                let text = std::fs::read_to_string(&path).map_err(|e| e.to_string())?;
                if !text.ends_with('\n') {
                    return Err(format!("{} ends in a torn row", path.display()));
                }
            }
        }
    }
    Ok(())
}

/// Fills `disk` with one file until it is full; returns its path.
fn fill(disk: &std::path::Path) -> std::path::PathBuf {
    use std::io::Write;
    let filler = disk.join("filler");
    let mut f = std::fs::File::create(&filler).unwrap();
    let block = vec![0u8; 4096];
    while f.write_all(&block).is_ok() {}
    filler
}

/// Issue 60: `compare --policy RUN --out DIR` onto a full 64 KiB disk once exited 1 with an
/// empty stderr. On a 64 KiB and a 1 MiB disk, empty or filled, `compare` (with its shipped
/// policies and with `--policy`), `report`, `baseline --record`, `eval --record` and `tune`
/// either finish whole or exit 1 with one `error:` line, the last on stderr, naming the disk
/// (its mount point and size) and the OS's reason once; nothing is left half-written. On a
/// filled disk every one of them fails so.
#[test]
fn every_command_on_a_full_disk_says_which_disk_in_one_line_and_leaves_nothing_half_written() {
    let work = scratch("full-disk-work");
    let comparison = tiny_comparison(&work);
    for (size, shown, filled) in [
        ("64k", "64.0 KiB", false),
        ("64k", "64.0 KiB", true),
        ("1m", "1.0 MiB", false),
    ] {
        let Some(disk) = SmallDisk::mount_sized(&format!("disk-{size}"), size) else {
            eprintln!("skipped: no permission to mount a tmpfs");
            return;
        };
        let mut commands = file_commands(&disk.0, &comparison, None);
        commands.extend(
            file_commands(&disk.0, &comparison, Some("residual_nudged"))
                .into_iter()
                .filter(|c| c.name == "compare"),
        );
        for c in commands {
            for entry in std::fs::read_dir(&disk.0).unwrap() {
                let path = entry.unwrap().path();
                std::fs::remove_dir_all(&path)
                    .or_else(|_| std::fs::remove_file(&path))
                    .unwrap();
            }
            let filler = if filled {
                fill(&disk.0)
            } else {
                disk.0.join("no filler")
            };
            let out = command().args(&c.args).output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
            let at = format!(
                "{} {} on {size} (filled: {filled}): {:?}; stderr: {stderr}",
                c.name,
                c.args.join(" "),
                out.status
            );
            assert!(!stderr.contains("panicked"), "{at}");
            if let Err(why) = nothing_half_written(&disk.0, &filler) {
                panic!("{at}: {why}");
            }
            if out.status.success() && !filled {
                if let Err(why) = (c.check)(&c.out) {
                    panic!("{at}: {why}");
                }
                continue;
            }
            assert_eq!(out.status.code(), Some(1), "{at}");
            let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error")).collect();
            assert_eq!(errors.len(), 1, "{at}");
            assert_eq!(stderr.lines().last(), Some(errors[0]), "{at}");
            let error = errors[0];
            assert!(error.contains("ran out of space"), "{at}");
            let mounted = format!("mounted on {}: {shown} in all", disk.0.display());
            assert!(error.contains(&mounted), "{at}");
            assert_eq!(error.matches("No space left on device").count(), 1, "{at}");
            // A report or a recording is whole or absent (a tuning keeps its whole trials to
            // resume from).
            if c.name != "tune" && c.out.exists() {
                (c.check)(&c.out).unwrap_or_else(|why| panic!("{at}: left, but {why}"));
            }
        }
    }
    std::fs::remove_dir_all(&work).ok();
}
