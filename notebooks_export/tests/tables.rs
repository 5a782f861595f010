//! compare.csv, compare.json and the printed table say the same; bad folders are named.

mod common;

use common::{method_result, temp_dir, write_comparison, write_run};
use fairgrasp_report::comparison_table::{self, Comparison, Outcome};
use fairgrasp_report::{Input, ReportError, RunFolder};

/// Splits a CSV line (fields here hold no quotes except around commas).
fn fields(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(String::new()),
            _ => out.last_mut().unwrap().push(c),
        }
    }
    out
}

#[test]
fn csv_json_and_text_table_agree() {
    let dir = temp_dir("tables-agree");
    let mut c = write_comparison(&dir, Vec::new());
    c.results[1].method = "residual, with a comma".into();
    c.methods[1] = c.results[1].method.clone();
    let csv = comparison_table::to_csv(&c);
    let reread: Comparison = serde_json::from_str(&c.to_json()).unwrap();
    assert!(
        reread == c,
        "compare.json does not read back to the same comparison"
    );
    let lines: Vec<&str> = csv.lines().collect();
    let header = fields(lines[0]);
    // The summary, an outcome count each, then the cycle time and the takt's six.
    assert_eq!(header.len(), 12 + Outcome::ALL.len() + 6);
    assert_eq!(lines.len(), 1 + c.results.len());
    let table = comparison_table::text_table(&c);
    for (line, r) in lines[1..].iter().zip(&c.results) {
        let row = fields(line);
        assert_eq!(row.len(), header.len(), "{line}");
        let col = |name: &str| &row[header.iter().position(|h| h == name).unwrap()];
        assert_eq!(col("method"), &r.method);
        assert_eq!(col("preset"), &r.preset);
        assert_eq!(
            col("success_rate").parse::<f64>().unwrap(),
            r.report.success_rate
        );
        assert_eq!(col("ci_low").parse::<f64>().unwrap(), r.report.ci_low);
        assert_eq!(
            col("within_takt_rate").parse::<f64>().unwrap(),
            r.report.within_takt_rate
        );
        assert_eq!(col("takt_s"), "", "a lift comparison runs on no takt");
        for &o in Outcome::ALL {
            assert_eq!(
                col(o.as_str()).parse::<usize>().unwrap(),
                r.report.outcomes.get(&o).copied().unwrap_or(0)
            );
        }
        // The printed line for this method and preset carries the same rounded numbers.
        let printed = table
            .lines()
            .find(|l| l.starts_with(&r.preset) && l.contains(&r.method))
            .unwrap_or_else(|| panic!("no table line for {} on {}", r.method, r.preset));
        let rate: f64 = col("success_rate").parse().unwrap();
        let ci_hi: f64 = col("ci_high").parse().unwrap();
        assert!(
            printed.contains(&format!("{:.1} % (", 100.0 * rate)),
            "{printed}"
        );
        assert!(
            printed.contains(&format!("–{:.1})", 100.0 * ci_hi)),
            "{printed}"
        );
        assert!(
            printed.contains(&comparison_table::failure_breakdown(r)),
            "{printed}"
        );
    }
    let md = comparison_table::markdown_table(&c);
    assert_eq!(md.lines().count(), 2 + c.results.len());
}

#[test]
fn inconsistent_comparisons_are_refused() {
    let r = method_result("baseline", "sector", 10, 7, 0);
    let c = Comparison {
        command: String::new(),
        presets: vec!["sector".into()],
        methods: vec!["baseline".into()],
        preset_configs: Default::default(),
        run_folders: vec![],
        recorded: vec![],
        replay: vec![],
        tuning: vec![],
        results: vec![r.clone()],
    };
    assert_eq!(c.check(), Ok(()));
    let dir = temp_dir("tables-bad-json");
    let teleported = c.to_json().replace("\"collision\"", "\"teleported\"");
    std::fs::write(dir.join("compare.json"), teleported).unwrap();
    let e = comparison_table::load(&dir.join("compare.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("compare.json") && e.contains("unknown variant `teleported`"),
        "{e}"
    );
    let mut wrong = c.clone();
    wrong.results[0].report.successes = 8;
    assert!(wrong.check().unwrap_err().0.contains("success_rate"));
    let mut short = c.clone();
    short.results[0].report.results.pop();
    assert!(short.check().unwrap_err().0.contains("9 episode records"));

    std::fs::write(dir.join("compare.json"), "{\"presets\": 3}").unwrap();
    let e = comparison_table::load(&dir.join("compare.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("compare.json") && e.contains("not a fairgrasp compare.json"),
        "{e}"
    );
}

#[test]
fn missing_and_malformed_run_folders_are_named() {
    let dir = temp_dir("tables-bad-runs");
    let missing = dir.join("nope");
    let e = Input::load(&missing).unwrap_err();
    assert!(matches!(e, ReportError::NotAReportInput { .. }));
    assert!(e.to_string().contains("nope: no such folder"), "{e}");

    std::fs::create_dir_all(dir.join("empty")).unwrap();
    let e = Input::load(&dir.join("empty")).unwrap_err().to_string();
    assert!(e.contains("neither a comparison folder"), "{e}");
    let e = RunFolder::load(&dir.join("empty")).unwrap_err().to_string();
    assert!(e.contains("no metrics.csv"), "{e}");

    write_run(&dir.join("bad_number"), 5, 0);
    let text = std::fs::read_to_string(dir.join("bad_number/metrics.csv")).unwrap();
    let broken = text.replacen(",20,", ",twenty,", 2);
    std::fs::write(dir.join("bad_number/metrics.csv"), broken).unwrap();
    let e = RunFolder::load(&dir.join("bad_number"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("metrics.csv") && e.contains("line 2, column `episodes`: `twenty`"),
        "{e}"
    );

    write_run(&dir.join("no_entropy"), 5, 0);
    let text = std::fs::read_to_string(dir.join("no_entropy/metrics.csv")).unwrap();
    std::fs::write(
        dir.join("no_entropy/metrics.csv"),
        text.replacen("entropy", "ent", 1),
    )
    .unwrap();
    let e = RunFolder::load(&dir.join("no_entropy"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no `entropy` column"), "{e}");

    write_run(&dir.join("ragged"), 5, 0);
    let mut text = std::fs::read_to_string(dir.join("ragged/metrics.csv")).unwrap();
    text.push_str("7,1\n");
    std::fs::write(dir.join("ragged/metrics.csv"), text).unwrap();
    let e = RunFolder::load(&dir.join("ragged"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 7: 2 fields, the header has 16"), "{e}");

    write_run(&dir.join("no_config"), 5, 0);
    std::fs::remove_file(dir.join("no_config/config.toml")).unwrap();
    let e = RunFolder::load(&dir.join("no_config"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("without config.toml"), "{e}");
}

#[test]
fn the_pivot_tables_numbers_are_compare_csvs() {
    let dir = temp_dir("tables-pivot");
    let c = write_comparison(&dir, Vec::new());
    let csv = comparison_table::to_csv(&c);
    let lines: Vec<&str> = csv.lines().collect();
    let header = fields(lines[0]);
    let text = comparison_table::pivot_text(&c);
    let markdown = comparison_table::pivot_markdown(&c);
    // One row per method after the header and the rule, one column per preset; then a blank
    // line and the cycle's table, the same shape.
    assert_eq!(text.lines().count(), 2 * (2 + c.methods.len()) + 1);
    let head: Vec<&str> = text.lines().next().unwrap().split_whitespace().collect();
    assert_eq!(
        &head[2..],
        c.presets.iter().map(String::as_str).collect::<Vec<_>>()
    );
    for line in &lines[1..] {
        let row = fields(line);
        let col = |name: &str| row[header.iter().position(|h| h == name).unwrap()].clone();
        let (method, preset) = (col("method"), col("preset"));
        let rate = 100.0 * col("success_rate").parse::<f64>().unwrap();
        let column = c.presets.iter().position(|p| *p == preset).unwrap();
        let printed = text.lines().find(|l| l.starts_with(&method)).unwrap();
        let cells: Vec<&str> = printed[method.len()..].split_whitespace().collect();
        assert_eq!(cells[column], format!("{rate:.1}"), "{method} on {preset}");
        let md = markdown
            .lines()
            .find(|l| l.starts_with(&format!("| {method} |")))
            .unwrap();
        let cell = md.split(" | ").nth(1 + column).unwrap();
        let low = 100.0 * col("ci_low").parse::<f64>().unwrap();
        assert!(
            cell.starts_with(&format!("**{rate:.1}**<br>{low:.1}–")),
            "{cell}"
        );
    }
}

#[test]
fn the_leading_paired_tests_are_against_the_baseline_and_the_best_script_without_the_oracle() {
    let n = 40;
    let mut learned = method_result("residual PPO: r", "sector", n, 30, 1);
    learned.policy = Some("r/checkpoint".into());
    let results = vec![
        method_result("scripted baseline", "sector", n, 20, 2),
        method_result("closed-loop script", "sector", n, 35, 3),
        method_result("oracle script", "sector", n, 40, 4),
        learned,
    ];
    let c = Comparison {
        command: "test".into(),
        presets: vec!["sector".into()],
        methods: results.iter().map(|r| r.method.clone()).collect(),
        preset_configs: Default::default(),
        run_folders: vec![],
        recorded: vec![],
        replay: vec![],
        tuning: vec![],
        results,
    };
    let key = fairgrasp_types::learned_vs_key_scripts(&c).unwrap();
    let against: Vec<&str> = key.iter().map(|t| t.b.as_str()).collect();
    assert_eq!(against, ["scripted baseline", "closed-loop script"]);
    assert_eq!(fairgrasp_types::learned_vs_scripts(&c).unwrap().len(), 3);
    let text = comparison_table::key_paired_text(&c).unwrap();
    assert!(!text.contains("oracle"), "{text}");
}
