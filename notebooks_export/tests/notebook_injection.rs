//! A comparison folder whose name holds quotes and line breaks stays data: the notebook's code
//! cell parses to exactly its own three statements and, executed, reads the CSV from that folder
//! and creates nothing; report.md keeps the name inside one code span.

mod common;

use std::process::Command;

use common::{temp_dir, write_comparison};
use fairgrasp_report::{Existing, build_report};

/// A folder name that would end a raw string literal and add a statement.
const HOSTILE: &str = "cmp\")))\nopen(\"PWNED\", \"w\")\nx = ((\"`\n# ";

#[test]
fn a_hostile_folder_name_never_becomes_code_in_the_notebook() {
    let dir = temp_dir("notebook-injection");
    let cmp = dir.join(HOSTILE);
    write_comparison(&cmp, vec![]);
    let out = dir.join("out");
    build_report(std::slice::from_ref(&cmp), &out, Existing::Refuse).unwrap();

    let nb: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.ipynb")).unwrap()).unwrap();
    let code: Vec<String> = nb["cells"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["cell_type"] == "code")
        .map(|c| match &c["source"] {
            serde_json::Value::Array(lines) => lines
                .iter()
                .map(|l| l.as_str().unwrap().to_string())
                .collect::<String>(),
            other => other.as_str().unwrap().to_string(),
        })
        .collect();
    assert_eq!(code.len(), 1, "one code cell: {code:?}");

    // Parse and run the cell in a scratch folder: only import, assignment and loop; it prints
    // the CSV's rows read from the hostile folder, and no file appears.
    let scratch = dir.join("run");
    std::fs::create_dir_all(&scratch).unwrap();
    let check = r#"
import ast, sys
src = sys.stdin.read()
kinds = [type(n).__name__ for n in ast.parse(src).body]
assert kinds == ["Import", "Assign", "For"], kinds
exec(compile(src, "cell", "exec"))
"#;
    let mut child = Command::new("python3")
        .arg("-c")
        .arg(check)
        .current_dir(&scratch)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("python3 runs");
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(code[0].as_bytes())
        .unwrap();
    let run = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "the cell failed:\n{}\n{}",
        code[0],
        String::from_utf8_lossy(&run.stderr)
    );
    let csv = std::fs::read_to_string(cmp.join("compare.csv")).unwrap();
    assert_eq!(
        stdout.lines().count(),
        csv.lines().count() - 1,
        "one printed line per CSV row:\n{stdout}"
    );
    let created: Vec<_> = std::fs::read_dir(&scratch).unwrap().collect();
    assert!(created.is_empty(), "the cell created files: {created:?}");

    // report.md: the name stays inside its code span, no line of it starts a block.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        !md.lines()
            .any(|l| l.starts_with("open(") || l.starts_with("x = ")),
        "{md}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
