//! Property tests of every parser and loader (proptest): thousands of generated inputs each —
//! valid files with one to four edits (bits flipped, ranges cut or repeated, structural
//! characters, invalid UTF-8 and hostile numbers inserted, files truncated), and arbitrary bytes —
//! from a fixed seed, so every run feeds the same inputs; a failure is shrunk to a smallest
//! input. The valid files: the shipped presets (the place cell's too), recipes and training
//! configs, a shipped checkpoint, a run's metrics, a comparison's files, a tune folder's trials.
//! For every input: no panic, no allocation beyond a fixed bound, done within a few seconds, and
//! either a result or a refusal that names the file. For `metrics.csv`'s
//! repair one more property: no line is lost (every line is kept as a row or set aside). URDF
//! files are mutated the same way, and URDF paths that are no URDF file (a FIFO, a device, a
//! folder, links to them or to nothing, a 64 MiB file, a missing or too long name) are refused
//! within 10 s naming the path. The Python API's arguments have their own seeded fuzz
//! (`python/tests/test_hostile_arguments.py`).
//!
//! Allocation is measured per thread by a counting global allocator: the peak of live bytes
//! while one input is loaded, over the bytes live before it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::{Path, PathBuf};
use std::process::Command;

use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

struct Counting;

thread_local! {
    static LIVE: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
}

fn track(delta: isize) {
    // `try_with`: the thread's slots may be gone while it exits.
    let _ = LIVE.try_with(|live| {
        let now = live.get() + delta;
        live.set(now);
        let _ = PEAK.try_with(|peak| peak.set(peak.get().max(now)));
    });
}

// SAFETY: every call is forwarded unchanged to the system allocator; only counters are kept.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        track(layout.size() as isize);
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        track(layout.size() as isize);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        track(new_size as isize - layout.size() as isize);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        track(-(layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The most a load may allocate above what was live before it \[bytes\]: inputs here are at most
/// a few hundred kilobytes, so anything near this is an allocation sized by a claim in the file.
const ALLOCATION_BOUND: isize = 64 << 20;

/// Runs `load` and returns its result with the peak of bytes it allocated.
fn measured<T>(load: impl FnOnce() -> T) -> (T, isize) {
    let before = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(before));
    let out = load();
    (out, PEAK.with(Cell::get) - before)
}

/// Fragments that break structure or numbers.
const FRAGMENTS: [&[u8]; 18] = [
    b"\"",
    b"[",
    b"]",
    b"{",
    b"}",
    b"=",
    b",",
    b"\n",
    b"\xff\xfe",
    b"1e308",
    b"-1",
    b"nan",
    b"18446744073709551615",
    b"99999999999999999999999999",
    b"null",
    b"[[",
    b"\0",
    b"\r\n",
];

/// One edit of a file; positions are fractions of its length, so shrinking keeps them valid.
#[derive(Clone, Debug)]
enum Edit {
    /// One bit flipped.
    FlipBit(Index, u8),
    /// 1–16 bytes cut out.
    Cut(Index, usize),
    /// A fragment of [`FRAGMENTS`] inserted.
    Insert(Index, Index),
    /// 1–64 bytes repeated elsewhere.
    Repeat(Index, usize, Index),
    /// A digit replaced by a hostile number (`1e308`, `-1`, `nan`, 2^64 − 1, 10^26).
    HostileNumber(Index, Index),
    /// The rest cut off.
    Truncate(Index),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<Index>(), 0u8..8).prop_map(|(at, bit)| Edit::FlipBit(at, bit)),
        (any::<Index>(), 1usize..=16).prop_map(|(at, n)| Edit::Cut(at, n)),
        (any::<Index>(), any::<Index>()).prop_map(|(at, f)| Edit::Insert(at, f)),
        (any::<Index>(), 1usize..=64, any::<Index>())
            .prop_map(|(from, n, to)| Edit::Repeat(from, n, to)),
        (any::<Index>(), any::<Index>()).prop_map(|(at, f)| Edit::HostileNumber(at, f)),
        any::<Index>().prop_map(Edit::Truncate),
    ]
}

/// `seed` with `edits` applied in order.
fn apply(seed: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for e in edits {
        let at = |i: &Index, len: usize| i.index(len + 1);
        match e {
            Edit::FlipBit(i, bit) if !bytes.is_empty() => {
                let i = i.index(bytes.len());
                bytes[i] ^= 1 << bit;
            }
            Edit::FlipBit(..) => {}
            Edit::Cut(i, n) => {
                let from = at(i, bytes.len());
                bytes.drain(from..(from + n).min(bytes.len()));
            }
            Edit::Insert(i, f) => {
                let from = at(i, bytes.len());
                bytes.splice(
                    from..from,
                    FRAGMENTS[f.index(FRAGMENTS.len())].iter().copied(),
                );
            }
            Edit::Repeat(from, n, to) => {
                let from = at(from, bytes.len());
                let piece = bytes[from..(from + n).min(bytes.len())].to_vec();
                let to = at(to, bytes.len());
                bytes.splice(to..to, piece);
            }
            Edit::HostileNumber(i, f) => {
                let digits: Vec<usize> = (0..bytes.len())
                    .filter(|&i| bytes[i].is_ascii_digit())
                    .collect();
                if !digits.is_empty() {
                    let d = digits[i.index(digits.len())];
                    let hostile = FRAGMENTS[9 + f.index(5)];
                    bytes.splice(d..=d, hostile.iter().copied());
                }
            }
            Edit::Truncate(i) => {
                let len = at(i, bytes.len());
                bytes.truncate(len);
            }
        }
    }
    bytes
}

/// What a loader is fed: nine in ten inputs are a valid file with one to four edits, one in
/// ten is arbitrary bytes (up to 4 KiB).
fn inputs(seed: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        9 => prop::collection::vec(edit(), 1..=4).prop_map(move |e| apply(&seed, &e)),
        1 => prop::collection::vec(any::<u8>(), 0..4096),
    ]
}

/// A runner of `cases` inputs from a fixed seed (`what` picks it): the same inputs on every run
/// and machine; a failure is shrunk to a smallest input and not written to disk.
fn runner(what: &str, cases: usize) -> TestRunner {
    let config = Config {
        cases: cases as u32,
        failure_persistence: None,
        max_shrink_iters: 2_000,
        ..Config::default()
    };
    let mut seed = [0u8; 32];
    for (i, b) in what.bytes().enumerate() {
        seed[i % 32] ^= b;
    }
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &seed))
}

/// The longest one load may take \[s\]: inputs are small, so a slower load is a loop that
/// depends on a claim in the file (a hang, cut short only by this test's own end).
const SECONDS_PER_LOAD: f64 = 5.0;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-props-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `cases` inputs made from `seed` ([`inputs`]) to `file` one by one and loads each with
/// `load`: no panic, allocation within the bound, done within [`SECONDS_PER_LOAD`], and a
/// refusal naming `named` (when given). A failure is shrunk to a smallest input.
fn check_loader(
    what: &str,
    seed: &[u8],
    cases: usize,
    file: &Path,
    named: Option<&Path>,
    load: &dyn Fn() -> Result<(), String>,
) {
    let (loaded, refused) = (Cell::new(0), Cell::new(0));
    let result = runner(what, cases).run(&inputs(seed.to_vec()), |input| {
        std::fs::write(file, &input).unwrap();
        let start = std::time::Instant::now();
        let (result, peak) =
            measured(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(load)));
        let seconds = start.elapsed().as_secs_f64();
        let shown = String::from_utf8_lossy(&input[..input.len().min(2_000)]).into_owned();
        let Ok(result) = result else {
            return Err(TestCaseError::fail(format!("panicked on:\n{shown}")));
        };
        prop_assert!(
            peak < ALLOCATION_BOUND,
            "allocated {peak} bytes on:\n{shown}"
        );
        prop_assert!(
            seconds < SECONDS_PER_LOAD,
            "took {seconds:.1} s on:\n{shown}"
        );
        match result {
            Ok(()) => loaded.set(loaded.get() + 1),
            Err(message) => {
                refused.set(refused.get() + 1);
                if let Some(path) = named {
                    let name = path.display().to_string();
                    prop_assert!(message.contains(&name), "`{message}` does not name {name}");
                }
            }
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{what}: {e}");
    }
    let (loaded, refused) = (loaded.get(), refused.get());
    println!("{what}: {cases} generated inputs, {loaded} loaded, {refused} refused");
    assert!(
        refused > 0,
        "{what}: no input was refused: the inputs test nothing"
    );
}

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn training_and_env_configs() {
    let dir = scratch("toml");
    let file = dir.join("config.toml");
    let seed =
        std::fs::read(Path::new(ROOT).join("assets/policies/residual_nudged/train.toml")).unwrap();
    check_loader("training config", &seed, 3000, &file, Some(&file), &|| {
        fairgrasp_rl::run::TrainConfig::from_toml_file(&file)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    let seed = std::fs::read(Path::new(ROOT).join("assets/configs/wrist_camera.toml")).unwrap();
    check_loader("env config", &seed, 3000, &file, Some(&file), &|| {
        fairgrasp_env::EnvConfig::from_toml_file(&file)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    std::fs::remove_dir_all(&dir).ok();
}

/// The place cell's preset (its mix, takt and every control's search settings), a recipe of
/// `assets/experiments/` (read by `train --config`), and a `fairgrasp tune` folder's
/// `trials.csv` (read again on every resume).
#[test]
fn place_presets_recipes_and_tune_trials() {
    let dir = scratch("place");
    let file = dir.join("place_cell.toml");
    let seed = std::fs::read(Path::new(ROOT).join("assets/configs/place_cell.toml")).unwrap();
    check_loader(
        "place_cell preset",
        &seed,
        2000,
        &file,
        Some(&file),
        &|| {
            fairgrasp_env::EnvConfig::from_toml_file(&file)
                .map(drop)
                .map_err(|e| e.to_string())
        },
    );
    let file = dir.join("recipe.toml");
    let seed =
        std::fs::read(Path::new(ROOT).join("assets/experiments/residual_place_cell.toml")).unwrap();
    check_loader("recipe", &seed, 2000, &file, Some(&file), &|| {
        fairgrasp_policy::recipe::Recipe::from_toml_file(&file)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    let shipped = std::fs::read_to_string(
        Path::new(ROOT).join("assets/tuned/place_cell/force_search_trials.csv"),
    )
    .unwrap();
    // The header's parameter columns, between `generation` and `episodes`.
    let header: Vec<&str> = shipped.lines().next().unwrap().split(',').collect();
    let end = header.iter().position(|c| *c == "episodes").unwrap();
    let names = header[2..end].to_vec();
    let seed: String = shipped.lines().take(12).map(|l| format!("{l}\n")).collect();
    // The rows of the shipped tuning: 150 episodes a trial on place_cell.
    let place_cell = fairgrasp_env::config::presets::load("place_cell").unwrap();
    let rules = fairgrasp_evaluate::tune::trials::RowRules {
        episodes: 150,
        max_steps: place_cell.task.max_steps as u64,
        episode_seconds: place_cell.task.max_steps as f64
            * place_cell.physics.dt
            * place_cell.physics.substeps as f64,
    };
    let file = dir.join("trials.csv");
    check_loader(
        "tune trials.csv",
        seed.as_bytes(),
        2000,
        &file,
        Some(&file),
        &|| {
            fairgrasp_evaluate::tune::trials::load(&file, &names, &rules)
                .map(drop)
                .map_err(|e| e.to_string())
        },
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn checkpoints_meta_and_weights() {
    let dir = scratch("checkpoint");
    let shipped = Path::new(ROOT).join("assets/policies/residual_nudged/checkpoint");
    for name in ["meta.json", "model.bpk", "checksum"] {
        std::fs::copy(shipped.join(name), dir.join(name)).unwrap();
    }
    let meta = dir.join("meta.json");
    let seed = std::fs::read(&meta).unwrap();
    check_loader("meta.json", &seed, 3000, &meta, Some(&meta), &|| {
        fairgrasp_policy::checkpoint::load_meta(&dir)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    std::fs::write(&meta, &seed).unwrap();
    // The weights' parser itself (a load stops at the checksum before it).
    let model = dir.join("model.bpk");
    let weights = std::fs::read(&model).unwrap();
    check_loader("model.bpk", &weights, 1500, &model, None, &|| {
        let bytes = std::fs::read(&model).unwrap();
        fairgrasp_policy::burnpack::read_tensors(&bytes)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    check_loader(
        "checkpoint folder",
        &weights,
        500,
        &model,
        Some(&dir),
        &|| {
            fairgrasp_policy::checkpoint::load_actor(&dir)
                .map(drop)
                .map_err(|e| e.to_string())
        },
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn urdf_files() {
    let dir = scratch("urdf");
    let file = dir.join("robot.urdf");
    for shipped in ["fr3.urdf", "seven_joint_arm.urdf"] {
        let seed = std::fs::read(Path::new(ROOT).join("assets").join(shipped)).unwrap();
        check_loader(shipped, &seed, 1500, &file, Some(&file), &|| {
            fairgrasp_kinematics::urdf::UrdfRobot::from_file(&file)
                .map(drop)
                .map_err(|e| e.to_string())
        });
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The URDF loader's result for `path`, or a failure if it takes longer than 10 s (a FIFO used
/// to block it forever).
fn urdf_within_seconds(path: &Path) -> Result<(), String> {
    let (tx, rx) = std::sync::mpsc::channel();
    let owned = path.to_path_buf();
    std::thread::spawn(move || {
        let result = fairgrasp_kinematics::urdf::UrdfRobot::from_file(&owned)
            .map(drop)
            .map_err(|e| e.to_string());
        tx.send(result).ok();
    });
    rx.recv_timeout(std::time::Duration::from_secs(10))
        .unwrap_or_else(|_| panic!("{}: the URDF loader did not return in 10 s", path.display()))
}

#[test]
fn urdf_paths_that_are_no_urdf_file_are_refused_at_once_naming_the_path() {
    let dir = scratch("urdf-paths");
    let fifo = dir.join("fifo.urdf");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let large = dir.join("large.urdf");
    std::fs::File::create(&large)
        .unwrap()
        .set_len(64 << 20)
        .unwrap();
    let links = [
        ("to_fifo.urdf", fifo.clone()),
        ("to_zero.urdf", PathBuf::from("/dev/zero")),
        ("dangling.urdf", dir.join("gone.urdf")),
        ("to_folder.urdf", dir.clone()),
    ];
    for (name, target) in &links {
        std::os::unix::fs::symlink(target, dir.join(name)).unwrap();
    }
    let long_name = dir.join(format!("{}.urdf", "n".repeat(5_000)));
    let mut paths = vec![
        fifo.clone(),
        large.clone(),
        PathBuf::from("/dev/zero"),
        PathBuf::from("/dev/stdin"),
        dir.clone(),
        dir.join("missing.urdf"),
        long_name,
        PathBuf::from(""),
    ];
    paths.extend(links.iter().map(|(name, _)| dir.join(name)));
    let mut rng = ChaCha8Rng::seed_from_u64(50);
    for round in 0..3 {
        // Seeded order: a loader that leaves state behind (an open FIFO) shows in later ones.
        for i in (1..paths.len()).rev() {
            paths.swap(i, rng.random_range(0..=i));
        }
        for path in &paths {
            let (result, peak) = measured(|| urdf_within_seconds(path));
            let message = result.expect_err(&format!("{}: loaded", path.display()));
            let shown: String = path.display().to_string().chars().take(60).collect();
            assert!(
                message.contains(&shown),
                "round {round}: `{message}` does not name {shown}"
            );
            // Beyond the path it names (the caller's own argument, which the CLI and Python cut
            // to an excerpt), a refusal quotes little.
            let rest = message.len()
                - message.matches(&path.display().to_string()).count() * path.as_os_str().len();
            assert!(
                rest < 300,
                "round {round}: {rest} characters besides the path: {message}"
            );
            assert!(
                peak < ALLOCATION_BOUND,
                "{}: allocated {peak} bytes",
                path.display()
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A comparison folder with recorded episodes, written by the command itself.
fn comparison(dir: &Path) -> PathBuf {
    let out = dir.join("cmp");
    let status = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
        .args([
            "compare",
            "--preset",
            "fixed",
            "--episodes",
            "3",
            "--threads",
            "1",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    out
}

#[test]
fn comparisons_episodes_and_run_metrics() {
    let dir = scratch("report");
    let cmp = comparison(&dir);
    let compare_json = cmp.join("compare.json");
    let seed = std::fs::read(&compare_json).unwrap();
    let file = dir.join("compare.json");
    check_loader("compare.json", &seed, 2000, &file, Some(&file), &|| {
        fairgrasp_report::comparison_table::load(&file)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    let episode = std::fs::read_dir(cmp.join("episodes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "gz"))
        .unwrap();
    let seed = std::fs::read(&episode).unwrap();
    let file = dir.join("episode.json");
    check_loader("episode", &seed, 1000, &file, Some(&file), &|| {
        fairgrasp_report::trajectory::load(&file)
            .map(drop)
            .map_err(|e| e.to_string())
    });
    // A run's metrics.csv, read by plot and report.
    let run = dir.join("run");
    std::fs::create_dir_all(&run).unwrap();
    let shipped = Path::new(ROOT).join("assets/policies/residual_nudged");
    std::fs::copy(shipped.join("config.toml"), run.join("config.toml")).unwrap();
    let seed = std::fs::read(shipped.join("metrics.csv")).unwrap();
    let metrics = run.join("metrics.csv");
    check_loader(
        "metrics.csv",
        &seed,
        2000,
        &metrics,
        Some(&metrics),
        &|| {
            fairgrasp_report::RunFolder::load(&run)
                .map(drop)
                .map_err(|e| e.to_string())
        },
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `--resume`'s repair of `metrics.csv`: whatever the file holds, every line ends up either as
/// a row of the repaired file or in `metrics.rejected.csv`.
#[test]
fn the_metrics_repair_never_loses_a_line() {
    use fairgrasp_rl::run::{checkpoint, metrics::metrics_header, resume::repair_metrics};
    let dir = scratch("repair");
    let shipped = Path::new(ROOT).join("assets/policies/residual_nudged");
    let mut meta = checkpoint::load_meta(&shipped.join("checkpoint")).unwrap();
    meta.metrics_row = None;
    let header = metrics_header();
    let seed = std::fs::read(shipped.join("metrics.csv")).unwrap();
    let metrics = dir.join("metrics.csv");
    let rejected = dir.join("metrics.rejected.csv");
    let count = |bytes: &[u8]| {
        bytes
            .split(|b| *b == b'\n')
            .filter(|l| !l.is_empty())
            .count()
    };
    let result = runner("metrics repair", 1500).run(&inputs(seed.clone()), |input| {
        std::fs::write(&metrics, &input).unwrap();
        let _ = std::fs::remove_file(&rejected);
        let (result, peak) = measured(|| repair_metrics(&dir, &meta, &header));
        prop_assert!(result.is_ok(), "{:?}", result.err());
        prop_assert!(peak < ALLOCATION_BOUND, "allocated {peak} bytes");
        let headers = input
            .split(|b| *b == b'\n')
            .filter(|l| {
                !l.is_empty()
                    && header.as_bytes().starts_with(l)
                    && (l.len() == header.len() || header.as_bytes()[l.len()] == b',')
            })
            .count();
        let after = std::fs::read(&metrics).unwrap();
        let kept = count(&after) - 1;
        let aside = std::fs::read(&rejected).map_or(0, |b| count(&b));
        prop_assert!(
            kept + aside + headers >= count(&input),
            "{} lines in, {kept} kept, {aside} set aside, {headers} headers",
            count(&input)
        );
        Ok(())
    });
    if let Err(e) = result {
        panic!("metrics repair: {e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The allocation bound above means something only if the counter sees allocations.
#[test]
fn the_allocation_counter_sees_a_large_allocation() {
    let (buffer, peak) = measured(|| vec![1u8; 80 << 20]);
    assert!(peak >= 80 << 20, "{peak}");
    drop(buffer);
}
