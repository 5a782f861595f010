//! `fairgrasp report`: charts, `report.md` and `report.ipynb` from comparison and run folders.

use std::path::{Path, PathBuf};

use crate::charts::curves;
use crate::charts::draw_all::draw_comparison_charts;
use crate::comparison_table::{
    Comparison, key_paired_markdown, markdown_table, paired_markdown, pivot_markdown, tuning_text,
};
use crate::document::{Document, toml_block};
use crate::error::{ReportError, write_file};
use crate::notebook::to_notebook;
use crate::output_folder::{Existing, StagedFolder};
use crate::runs::RunFolder;
use crate::trajectory::{self, Trajectory};

/// A folder given to the report.
#[derive(Clone, Debug)]
pub enum Input {
    /// A folder written by `fairgrasp compare` (holds `compare.json`).
    Comparison {
        dir: PathBuf,
        comparison: Comparison,
        /// The recorded episodes, in the order of `comparison.recorded`.
        trajectories: Vec<Trajectory>,
    },
    /// A training run folder (holds `metrics.csv`).
    Run(RunFolder),
}

impl Input {
    /// Recognises and loads a comparison or run folder.
    pub fn load(path: &Path) -> Result<Self, ReportError> {
        if !path.exists() {
            return Err(ReportError::NotAReportInput {
                path: path.to_path_buf(),
                what: "no such folder".into(),
            });
        }
        if path.join("compare.json").is_file() {
            let comparison = crate::comparison_table::load(&path.join("compare.json"))?;
            let trajectories = comparison
                .recorded
                .iter()
                .map(|r| trajectory::load(&path.join(&r.trajectory)))
                .collect::<Result<_, _>>()?;
            return Ok(Self::Comparison {
                dir: path.to_path_buf(),
                comparison,
                trajectories,
            });
        }
        if path.join("metrics.csv").is_file() || !path.is_dir() {
            return RunFolder::load(path).map(Self::Run);
        }
        Err(ReportError::NotAReportInput {
            path: path.to_path_buf(),
            what: "neither a comparison folder (compare.json, from `fairgrasp compare`) nor a \
                   training run folder (metrics.csv, from `fairgrasp train`)"
                .into(),
        })
    }
}

/// File name fragments of methods and presets, the same as the comparison's recorded episodes.
pub use fairgrasp_types::fs::slug;

/// Writes charts, `report.md` and `report.ipynb` for `inputs` into the folder `out`, written
/// whole or not at all ([`StagedFolder`]; `existing` says whether an earlier fairgrasp report
/// there may be replaced); returns every file written. All inputs are loaded (and refused if
/// broken), and `out` is checked, before anything is written; `out` may not be, or contain,
/// an input. The charts are drawn on one thread per core.
pub fn build_report(
    inputs: &[PathBuf],
    out: &Path,
    existing: Existing,
) -> Result<Vec<PathBuf>, ReportError> {
    let loaded = load_inputs(inputs, out)?;
    if let Some(input) = input_inside(inputs, out) {
        return Err(ReportError::OutputFolder {
            path: out.to_path_buf(),
            what: format!(
                "is (or contains) the input folder {}: writing the report there would replace \
                 what it reads; choose another --out",
                input.display()
            ),
        });
    }
    let staged = StagedFolder::create(out, existing, "fairgrasp report")?;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let written = write_report(&loaded, staged.path(), out, threads)?;
    staged.commit()?;
    Ok(written.iter().map(|name| out.join(name)).collect())
}

/// Loads every input folder (see [`Input::load`]); `out` names the report in the error for
/// an empty list.
pub fn load_inputs(inputs: &[PathBuf], out: &Path) -> Result<Vec<Input>, ReportError> {
    if inputs.is_empty() {
        return Err(ReportError::NotAReportInput {
            path: out.to_path_buf(),
            what: "no input folder given".into(),
        });
    }
    inputs.iter().map(|p| Input::load(p)).collect()
}

/// The first input that is `out` or lies inside it (both existing).
fn input_inside<'a>(inputs: &'a [PathBuf], out: &Path) -> Option<&'a PathBuf> {
    let out = out.canonicalize().ok()?;
    inputs.iter().find(|input| {
        input
            .canonicalize()
            .is_ok_and(|input| input.starts_with(&out))
    })
}

/// Writes charts, `report.md` and `report.ipynb` for the loaded `inputs` into the existing
/// folder `dir` (a [`StagedFolder`]'s path), which will end up at `shown_as` (the name the
/// report gives the folder); returns the files written, relative to `dir`. The charts are drawn
/// on `threads` threads.
pub fn write_report(
    loaded: &[Input],
    dir: &Path,
    shown_as: &Path,
    threads: usize,
) -> Result<Vec<String>, ReportError> {
    let out = dir;
    let mut written = Vec::new();
    let mut doc = Document::new("fairgrasp report: grasping the FR3's cube");
    doc.markdown(
        "Generated by `fairgrasp report` from the folders below. Every number comes from a \
         seeded run and can be reproduced with the commands quoted in each section. The text \
         cells are yours to edit: replace the *Discussion* prompts with your own analysis.",
    );
    let mut runs: Vec<RunFolder> = Vec::new();
    let mut missing_runs: Vec<String> = Vec::new();
    let many = loaded
        .iter()
        .filter(|i| matches!(i, Input::Comparison { .. }))
        .count()
        > 1;
    for (k, input) in loaded.iter().enumerate() {
        match input {
            Input::Run(run) => runs.push(run.clone()),
            Input::Comparison {
                dir,
                comparison,
                trajectories,
            } => {
                let prefix = if many {
                    format!("c{}_", k + 1)
                } else {
                    String::new()
                };
                // A comparison read from the folder being written is named by its final name.
                let shown = if dir == out { shown_as } else { dir.as_path() };
                comparison_section(
                    &mut doc,
                    (dir, shown, comparison, trajectories),
                    (out, &prefix, threads),
                    &mut written,
                )?;
                for folder in &comparison.run_folders {
                    match RunFolder::load(Path::new(folder)) {
                        Ok(run) => runs.push(run),
                        Err(e) => missing_runs.push(e.to_string()),
                    }
                }
            }
        }
    }
    runs.dedup_by(|a, b| a.path.canonicalize().ok() == b.path.canonicalize().ok());
    if !runs.is_empty() {
        runs_section(&mut doc, &runs, out, &mut written)?;
    }
    if !missing_runs.is_empty() {
        doc.markdown(format!(
            "Learning curves of these policies are missing (their run folders could not be \
             read):\n\n{}",
            missing_runs
                .iter()
                .map(|m| format!("- {m}\n"))
                .collect::<String>()
        ));
    }
    write_file(&out.join("report.md"), doc.to_markdown().as_bytes())?;
    written.push("report.md".into());
    let json = serde_json::to_string_pretty(&to_notebook(&doc, out)?).expect("JSON serialises");
    write_file(&out.join("report.ipynb"), json.as_bytes())?;
    written.push("report.ipynb".into());
    Ok(written)
}

/// The comparison's opening: what was run, the pivot table and the leading paired tests.
fn results_head(doc: &mut Document, c: &Comparison, out: &Path) -> Result<(), ReportError> {
    let episodes = c.results.first().map_or(0, |r| r.report.episodes);
    doc.markdown(format!(
        "## Comparison: {} on {}\n\nEach method ran on the *same* {episodes} seeded scenarios \
         per preset (cube position, yaw, friction, mass, joint noise drawn from the scenario \
         seed), so differences come from the methods, not from luck of the draw. Success means \
         the cube was lifted and held (lift), or seated in the fixture and released \
         (place); the interval is the 95 % Wilson score interval, which \
         stays honest near 0 % and 100 %.\n\nReproduce: `{}`",
        c.methods.join(", "),
        c.presets.join(", "),
        c.command
    ));
    doc.markdown(format!(
        "Success in % (bold) over its 95 % interval; every row's failures, collisions and \
         steps are in the appendix and in `compare.csv`.\n\n{}",
        pivot_markdown(c)
    ));
    let tuning = tuning_text(c);
    if !tuning.is_empty() {
        doc.markdown(format!(
            "How each control with parameters was set (a learned policy is compared against \
             the control at its best: tuned on training scenarios, never the reported ones, \
             with at least the learner's env steps):\n\n{}",
            tuning
                .lines()
                .map(|l| format!("- {}", l.trim()))
                .collect::<Vec<_>>()
                .join("\n")
        ));
    }
    let malformed = |e: fairgrasp_types::PairingError| {
        ReportError::malformed(&out.join("compare.json"), e.to_string())
    };
    let key = key_paired_markdown(c).map_err(malformed)?;
    if !key.is_empty() {
        doc.markdown(format!(
            "### Paired tests\n\nEach learned method against the open-loop baseline and \
             against the best script of each preset that uses the same information (the \
             oracle, which sees the true pose, is a ceiling, not a control), on the same \
             scenarios: McNemar's exact test counts the scenarios only one of the two solved; \
             p is the two-sided probability of a split at least this uneven if both were \
             equally good. Every other pair is in the appendix.\n\n{key}"
        ));
    }
    Ok(())
}

/// Charts and text for one comparison folder `dir`, named `shown` in the text.
fn comparison_section(
    doc: &mut Document,
    (dir, shown, c, trajectories): (&Path, &Path, &Comparison, &[Trajectory]),
    (out, prefix, threads): (&Path, &str, usize),
    written: &mut Vec<String>,
) -> Result<(), ReportError> {
    results_head(doc, c, out)?;
    let charts = draw_comparison_charts(c, trajectories, out, prefix, threads)?;
    written.push(charts.success.clone());
    doc.image(
        &charts.success,
        "success rate per method and preset with 95 % CI (heatmap)",
    );
    doc.markdown(
        "**Discussion.** Which preset separates the methods? Are the intervals of two methods \
         disjoint, or is the difference within noise? What does the failure breakdown say \
         about *why* a method fails?",
    );
    doc.markdown(
        "### Where the failures are\n\nTop view of the table in the arm's `base_link` frame \
         (the arm base is the cross at the origin): every dot is one episode's cube start, \
         coloured by how the episode ended.",
    );
    for (file, preset) in &charts.workspaces {
        written.push(file.clone());
        doc.image(file, &format!("workspace map, preset {preset}"));
    }
    if !charts.takts.is_empty() {
        doc.markdown(
            "### On the takt\n\nA cell judges a cycle by whether it ends in time: success within \
             the takt (up) against the mean cycle time of the successes (left is faster). Each \
             method is a point on the held-out scenarios; the faint dots are the tuning trials \
             of the controls, on their training scenarios.",
        );
    }
    for (file, preset, _) in &charts.takts {
        written.push(file.clone());
        doc.image(
            file,
            &format!("success within the takt against cycle time, preset {preset}"),
        );
    }
    if !c.recorded.is_empty() {
        doc.markdown(
            "### One episode, step by step\n\nThe same scenario for each method: joint angles \
             and gripper opening over time, the TCP and cube paths seen from above and from \
             the side, and an animated replay (the arm's collision capsules, the fingers, the \
             cube and the table).",
        );
    }
    for (png, gif, title) in &charts.episodes {
        written.extend([png.clone(), gif.clone()]);
        doc.markdown(format!("#### {title}"));
        doc.image(png, title);
        doc.image(gif, &format!("replay: {title}"));
    }
    crate::replay3d::section::replay_section(doc, (dir, c, trajectories), out, prefix, written)?;
    doc.markdown(format!(
        "### The numbers as data\n\n`compare.csv` holds one row per method and preset (rates \
         as fractions); `compare.json` adds every episode's seed, outcome, steps, return and \
         cube start. This cell reads the CSV with Python's standard library only (folder: \
         {}).",
        code_span(&shown.to_string_lossy())
    ));
    // Jupyter runs a notebook from its own folder: name the CSV relative to it when it is there.
    let same = dir
        .canonicalize()
        .ok()
        .zip(out.canonicalize().ok())
        .is_some_and(|(a, b)| a == b);
    let csv = if same {
        PathBuf::from("compare.csv")
    } else {
        dir.join("compare.csv")
            .canonicalize()
            .unwrap_or_else(|_| dir.join("compare.csv"))
    };
    doc.code(format!(
        "import csv\nrows = list(csv.DictReader(open({})))\nfor r in rows:\n    \
         print(f\"{{r['preset']:>8}} {{r['method']:<32}} {{100 * float(r['success_rate']):5.1f}} %\")",
        python_string(&csv.to_string_lossy())
    ));
    appendix(doc, c, out)?;
    doc.markdown("### Environment configs\n\nThe complete config of each preset (TOML; pass the file to `--preset` to rerun it).");
    for (preset, toml) in &c.preset_configs {
        doc.markdown(format!("**{preset}**\n\n{}", toml_block(toml)));
    }
    Ok(())
}

/// The appendix: every row of the comparison with its failures, and every learned method
/// against every script.
fn appendix(doc: &mut Document, c: &Comparison, out: &Path) -> Result<(), ReportError> {
    doc.markdown(format!(
        "### Appendix: every method on every preset\n\n{}",
        markdown_table(c)
    ));
    let all = paired_markdown(c)
        .map_err(|e| ReportError::malformed(&out.join("compare.json"), e.to_string()))?;
    if !all.is_empty() {
        doc.markdown(format!(
            "### Appendix: every learned method against every script\n\n{all}"
        ));
    }
    Ok(())
}

/// Learning curves and the configs of training runs.
fn runs_section(
    doc: &mut Document,
    runs: &[RunFolder],
    out: &Path,
    written: &mut Vec<String>,
) -> Result<(), ReportError> {
    doc.markdown(
        "## Training\n\nOne line per run. PPO's losses are not a measure of progress: the \
         policy loss hovers near zero by construction (advantages are normalised) and the value \
         loss follows the scale of the returns. Read the success rate and the evaluation dots; \
         the entropy shows how much the policy still explores.",
    );
    let file = "learning_curves.png";
    curves::learning_curves(runs, &out.join(file))?;
    written.push(file.into());
    doc.image(file, "learning curves");
    for run in runs {
        let steps = run
            .metrics
            .column("timesteps")
            .and_then(|t| t.last().copied())
            .unwrap_or(0.0);
        let mut text = format!(
            "### Run `{}`\n\nFolder `{}`, {} updates, {} environment steps.",
            run.name,
            run.path.display(),
            run.metrics.rows.len(),
            steps
        );
        if let Some(eval) = &run.eval {
            let rate = eval["success_rate"].as_f64().unwrap_or(f64::NAN);
            let (lo, hi) = (
                eval["ci_low"].as_f64().unwrap_or(f64::NAN),
                eval["ci_high"].as_f64().unwrap_or(f64::NAN),
            );
            text += &format!(
                " Final evaluation: {:.1} % success (95 % CI {:.1}–{:.1} %) over {} episodes.",
                100.0 * rate,
                100.0 * lo,
                100.0 * hi,
                eval["episodes"]
            );
        }
        text += &format!(
            "\n\nThe config that produced it:\n\n{}",
            toml_block(&run.config_toml)
        );
        doc.markdown(text);
    }
    doc.markdown(
        "**Discussion.** When did the success rate start to rise, and did the curriculum stage \
         changes cost anything? Did the entropy collapse before the policy was good?",
    );
    Ok(())
}

/// `text` as a Python string literal that holds exactly `text` (JSON's escaping, which Python
/// reads the same: quotes, backslashes and control characters escaped), so a folder name can
/// never end the literal and become code in the notebook.
fn python_string(text: &str) -> String {
    serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into())
}

/// `text` as one Markdown code span: line breaks become spaces, and the span is fenced by more
/// backticks than `text` holds in a row, so a name can neither end it nor start a new block.
fn code_span(text: &str) -> String {
    let flat: String = text
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let longest = flat.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    let fence = "`".repeat(longest + 1);
    format!("{fence} {flat} {fence}")
}
