//! The comparison of methods on presets: reading `compare.json` (its schema is
//! `fairgrasp-types`), `compare.csv`, and the same table as text and as Markdown.

use std::path::Path;

pub use fairgrasp_types::{Comparison, EpisodeRecord, MethodResult, Outcome, RecordedEpisode};
use fairgrasp_types::{PairedTest, learned_vs_key_scripts, learned_vs_scripts};

use crate::error::{ReportError, read_text};

/// Reads and checks `compare.json`.
pub fn load(path: &Path) -> Result<Comparison, ReportError> {
    Comparison::from_json(&read_text(path)?).map_err(|e| ReportError::malformed(path, e.0))
}

/// The header of `compare.csv`.
pub fn csv_header() -> String {
    let mut cols: Vec<&str> = vec![
        "method",
        "preset",
        "arm",
        "seed",
        "episodes",
        "successes",
        "success_rate",
        "ci_low",
        "ci_high",
        "collision_rate",
        "mean_steps_to_success",
        "mean_return",
    ];
    cols.extend(Outcome::ALL.iter().map(|o| o.as_str()));
    cols.extend([
        "mean_cycle_time_s",
        "takt_s",
        "successes_within_takt",
        "within_takt_rate",
        "within_takt_ci_low",
        "within_takt_ci_high",
    ]);
    cols.join(",")
}

/// `compare.csv`: one row per method and preset, rates as fractions, an empty
/// `mean_steps_to_success` and `mean_cycle_time_s` when nothing succeeded, an empty `takt_s`
/// for a task without a takt (then every success counts as within it).
pub fn to_csv(c: &Comparison) -> String {
    let mut out = csv_header();
    out.push('\n');
    for r in &c.results {
        let e = &r.report;
        let mut fields = vec![
            csv_field(&r.method),
            csv_field(&r.preset),
            r.arm.to_string(),
            r.seed.to_string(),
            e.episodes.to_string(),
            e.successes.to_string(),
            e.success_rate.to_string(),
            e.ci_low.to_string(),
            e.ci_high.to_string(),
            e.collision_rate.to_string(),
            e.mean_steps_to_success
                .map_or(String::new(), |s| s.to_string()),
            e.mean_return.to_string(),
        ];
        fields.extend(Outcome::ALL.iter().map(|&o| e.count(o).to_string()));
        let optional = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
        fields.extend([
            optional(e.mean_cycle_time_s),
            optional(e.takt_s),
            e.successes_within_takt.to_string(),
            e.within_takt_rate.to_string(),
            e.within_takt_ci_low.to_string(),
            e.within_takt_ci_high.to_string(),
        ]);
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    out
}

/// Quotes a CSV field when it holds a comma or a quote.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Failures as `name count` pairs, most frequent first (no successes listed).
pub fn failure_breakdown(r: &MethodResult) -> String {
    let mut failures: Vec<(&Outcome, &usize)> = r
        .report
        .outcomes
        .iter()
        .filter(|(o, n)| **o != Outcome::Success && **n > 0)
        .collect();
    failures.sort_by(|a, b| b.1.cmp(a.1).then(a.0.as_str().cmp(b.0.as_str())));
    if failures.is_empty() {
        return "none".into();
    }
    failures
        .iter()
        .map(|(o, n)| format!("{o} {n}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn pct(x: f64) -> String {
    format!("{:.1}", 100.0 * x)
}

/// The table's cells, shared by the text and Markdown forms.
fn cells(r: &MethodResult) -> [String; 7] {
    let e = &r.report;
    [
        r.preset.clone(),
        r.method.clone(),
        e.episodes.to_string(),
        format!(
            "{} % ({}–{})",
            pct(e.success_rate),
            pct(e.ci_low),
            pct(e.ci_high)
        ),
        format!("{} %", pct(e.collision_rate)),
        e.mean_steps_to_success
            .map_or("n/a".into(), |s| format!("{s:.1}")),
        failure_breakdown(r),
    ]
}

const HEADER: [&str; 7] = [
    "preset",
    "method",
    "episodes",
    "success (95 % CI)",
    "collisions",
    "steps to success",
    "failures",
];

/// The result of `method` on `preset`, if the comparison ran it.
fn result_of<'a>(c: &'a Comparison, method: &str, preset: &str) -> Option<&'a MethodResult> {
    c.results
        .iter()
        .find(|r| r.method == method && r.preset == preset)
}

/// The pivot table as aligned text: one row per method, one column per preset, success in %
/// (the intervals are in `compare.csv` and the Markdown pivot); then the cycle's table.
pub fn pivot_text(c: &Comparison) -> String {
    let mut out = text_pivot(c, "success %", |r| pct(r.report.success_rate));
    out.push('\n');
    let takt = takt_of(c);
    let title = match takt {
        Some(t) => format!("within {t} s % (mean cycle)"),
        None => "mean cycle time".to_string(),
    };
    out += &text_pivot(c, &title, |r| cycle_cell(r, takt));
    out
}

/// An aligned text table of methods × presets headed `title`, each cell `cell` of the result.
fn text_pivot(c: &Comparison, title: &str, cell: impl Fn(&MethodResult) -> String) -> String {
    let mut header = vec![title];
    header.extend(c.presets.iter().map(String::as_str));
    let rows: Vec<Vec<String>> = c
        .methods
        .iter()
        .map(|m| {
            std::iter::once(m.clone())
                .chain(
                    c.presets
                        .iter()
                        .map(|p| result_of(c, m, p).map_or("–".into(), &cell)),
                )
                .collect()
        })
        .collect();
    aligned(&header, &rows)
}

/// The takt of the comparison's presets, if they run on one (the first found).
fn takt_of(c: &Comparison) -> Option<f64> {
    c.results.iter().find_map(|r| r.report.takt_s)
}

/// A cell of the cycle pivot: with a takt, success within it in % and the mean cycle time of
/// the successes \[s\]; without, the mean cycle time alone.
fn cycle_cell(r: &MethodResult, takt: Option<f64>) -> String {
    let e = &r.report;
    let cycle = e
        .mean_cycle_time_s
        .map_or("–".to_string(), |c| format!("{c:.1} s"));
    match takt {
        Some(_) => format!("{} ({cycle})", pct(e.within_takt_rate)),
        None => cycle,
    }
}

/// How each control with parameters was set, one line each (empty without any): what a
/// learned policy is compared against.
pub fn tuning_text(c: &Comparison) -> String {
    c.tuning
        .iter()
        .map(|t| format!("  {} on `{}`: {}\n", t.method, t.preset, t.how))
        .collect()
}

/// The pivot table in Markdown: one row per method, one column per preset, each cell the
/// success rate in % over its 95 % Wilson interval; on a task with a takt, a second table of
/// success within it and the mean cycle time.
pub fn pivot_markdown(c: &Comparison) -> String {
    let mut out = markdown_pivot(c, |e| {
        format!(
            "**{}**<br>{}–{}",
            pct(e.success_rate),
            pct(e.ci_low),
            pct(e.ci_high)
        )
    });
    if let Some(takt) = takt_of(c) {
        out += &format!(
            "\nSuccess within the {takt} s takt (% of the episodes, 95 % Wilson interval) and the \
             mean cycle time of the successes, reset to success:\n\n"
        );
        out += &markdown_pivot(c, |e| {
            let cycle = e
                .mean_cycle_time_s
                .map_or("–".to_string(), |s| format!("{s:.1} s"));
            format!(
                "**{}**<br>{}–{}<br>{cycle}",
                pct(e.within_takt_rate),
                pct(e.within_takt_ci_low),
                pct(e.within_takt_ci_high)
            )
        });
    }
    out
}

/// A Markdown table of methods × presets, each cell `cell` of the result's report.
fn markdown_pivot(c: &Comparison, cell: impl Fn(&fairgrasp_types::EvalReport) -> String) -> String {
    let mut out = format!("| method | {} |\n", c.presets.join(" | "));
    out += &format!("|{}\n", "---|".repeat(c.presets.len() + 1));
    for m in &c.methods {
        let cells: Vec<String> = c
            .presets
            .iter()
            .map(|p| result_of(c, m, p).map_or("–".into(), |r| cell(&r.report)))
            .collect();
        out += &format!("| {} | {} |\n", m, cells.join(" | "));
    }
    out
}

/// The table as aligned text, one line per method and preset.
pub fn text_table(c: &Comparison) -> String {
    let rows: Vec<Vec<String>> = c.results.iter().map(|r| cells(r).to_vec()).collect();
    aligned(&HEADER, &rows)
}

/// A header and rows as columns padded to their widest cell, two spaces apart.
fn aligned(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: &[String]| {
        let padded: Vec<String> = cells
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c}{}", " ".repeat(w - c.chars().count())))
            .collect();
        padded.join("  ").trim_end().to_string() + "\n"
    };
    let head: Vec<String> = header.iter().map(|h| h.to_string()).collect();
    let mut out = line(&head);
    out += &line(&widths.iter().map(|w| "-".repeat(*w)).collect::<Vec<_>>());
    for row in rows {
        out += &line(row);
    }
    out
}

/// The table in Markdown.
pub fn markdown_table(c: &Comparison) -> String {
    let mut out = format!("| {} |\n", HEADER.join(" | "));
    out += &format!("|{}\n", "---|".repeat(HEADER.len()));
    for r in &c.results {
        out += &format!("| {} |\n", cells(r).join(" | "));
    }
    out
}

/// A p-value as a report shows it (`< 0.0001` below that).
fn p_text(p: f64) -> String {
    if p < 1e-4 {
        "< 0.0001".into()
    } else {
        format!("{p:.4}")
    }
}

const PAIRED_HEADER: [&str; 6] = [
    "preset",
    "learned",
    "script",
    "successes (learned / script)",
    "only learned / only script",
    "McNemar p",
];

fn paired_cells(t: &PairedTest) -> [String; 6] {
    [
        t.preset.clone(),
        t.a.clone(),
        t.b.clone(),
        format!("{} / {} of {}", t.successes_a, t.successes_b, t.episodes),
        format!("{} / {}", t.only_a, t.only_b),
        p_text(t.p_value),
    ]
}

/// The paired tests (every learned method against every script on each preset) as Markdown;
/// empty when the comparison has no learned method or no script. A result list that cannot be
/// paired (another seed, another length) is a malformed comparison.
pub fn paired_markdown(c: &Comparison) -> Result<String, fairgrasp_types::PairingError> {
    Ok(tests_markdown(&learned_vs_scripts(c)?))
}

/// The paired tests as aligned text (empty without a pair).
pub fn paired_text(c: &Comparison) -> Result<String, fairgrasp_types::PairingError> {
    Ok(tests_text(&learned_vs_scripts(c)?))
}

/// The paired tests a report leads with ([`learned_vs_key_scripts`]: every learned method
/// against the open-loop baseline and the preset's best script) as aligned text.
pub fn key_paired_text(c: &Comparison) -> Result<String, fairgrasp_types::PairingError> {
    Ok(tests_text(&learned_vs_key_scripts(c)?))
}

/// The paired tests a report leads with, as Markdown (empty without a pair).
pub fn key_paired_markdown(c: &Comparison) -> Result<String, fairgrasp_types::PairingError> {
    Ok(tests_markdown(&learned_vs_key_scripts(c)?))
}

fn tests_text(tests: &[PairedTest]) -> String {
    if tests.is_empty() {
        return String::new();
    }
    let rows: Vec<Vec<String>> = tests.iter().map(|t| paired_cells(t).to_vec()).collect();
    aligned(&PAIRED_HEADER, &rows)
}

fn tests_markdown(tests: &[PairedTest]) -> String {
    if tests.is_empty() {
        return String::new();
    }
    let mut out = format!("| {} |\n", PAIRED_HEADER.join(" | "));
    out += &format!("|{}\n", "---|".repeat(PAIRED_HEADER.len()));
    for t in tests {
        out += &format!("| {} |\n", paired_cells(t).join(" | "));
    }
    out
}
