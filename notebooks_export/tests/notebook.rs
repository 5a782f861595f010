//! `build_report`: report.md and a notebook that nbformat accepts, with the images inside.

mod common;

use std::path::Path;
use std::process::Command;

use base64::Engine;
use common::{temp_dir, write_comparison, write_run};
use fairgrasp_report::{Existing, build_report};

/// The Python interpreter of the project's test venv (created by scripts/python-env.sh).
fn python_with_nbformat() -> String {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/python-env.sh");
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-venv");
    let out = Command::new("bash")
        .arg(&script)
        .arg(&venv)
        .output()
        .expect("bash runs scripts/python-env.sh");
    assert!(
        out.status.success(),
        "scripts/python-env.sh failed (python3 with venv and PyPI access needed):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap().trim().to_string()
}

#[test]
fn report_from_a_comparison_and_a_run_passes_nbformat_validation() {
    let dir = temp_dir("notebook");
    write_run(&dir.join("run_a"), 30, 3);
    let run = dir.join("run_a").display().to_string();
    write_comparison(&dir.join("cmp"), vec![run]);
    let out = dir.join("out");
    let written = build_report(&[dir.join("cmp")], &out, Existing::Refuse).unwrap();
    for f in [
        "success_rate.png",
        "workspace_sector.png",
        "workspace_hard.png",
        "learning_curves.png",
        "episode_scripted_baseline_hard_ep0.png",
        "replay_scripted_baseline_hard_ep0.gif",
        "report.md",
        "report.ipynb",
    ] {
        assert!(
            written.contains(&out.join(f)),
            "{f} not reported as written"
        );
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // report.md links only files that exist, and quotes the config of the run.
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let links: Vec<&str> = md
        .split("](")
        .skip(1)
        .map(|s| s.split(')').next().unwrap())
        .collect();
    assert!(links.len() >= 6);
    for l in &links {
        assert!(out.join(l).is_file(), "report.md links missing {l}");
    }
    assert!(md.contains("total_timesteps = 100000"));
    assert!(md.contains("| hard | residual PPO: test |"));

    // The notebook embeds every image as an attachment with the file's exact bytes.
    let nb: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.ipynb")).unwrap()).unwrap();
    let mut embedded = 0;
    for cell in nb["cells"].as_array().unwrap() {
        let Some(att) = cell["attachments"].as_object() else {
            continue;
        };
        for (name, data) in att {
            let (mime, b64) = data.as_object().unwrap().iter().next().unwrap();
            let bytes = base64::engine::general_purpose::STANDARD
                .decode(b64.as_str().unwrap())
                .unwrap();
            assert_eq!(bytes, std::fs::read(out.join(name)).unwrap(), "{name}");
            assert_eq!(mime == "image/gif", name.ends_with(".gif"));
            embedded += 1;
        }
    }
    // Every image is embedded; the 3D replay (replay.html) is linked, not embedded.
    let images = links
        .iter()
        .filter(|l| l.ends_with(".png") || l.ends_with(".gif"))
        .count();
    assert_eq!(embedded, images);

    let python = python_with_nbformat();
    let check = Command::new(&python)
        .arg("-c")
        .arg(
            "import sys, nbformat\n\
             nb = nbformat.read(sys.argv[1], as_version=4)\n\
             nbformat.validate(nb)\n\
             assert nb.nbformat == 4\n\
             print(len(nb.cells))",
        )
        .arg(out.join("report.ipynb"))
        .output()
        .unwrap();
    assert!(
        check.status.success(),
        "nbformat rejected the notebook:\n{}",
        String::from_utf8_lossy(&check.stderr)
    );
    let cells: usize = String::from_utf8_lossy(&check.stdout)
        .trim()
        .parse()
        .unwrap();
    assert_eq!(cells, nb["cells"].as_array().unwrap().len());
}

#[test]
fn a_broken_input_writes_nothing() {
    let dir = temp_dir("notebook-broken");
    write_comparison(&dir.join("cmp"), Vec::new());
    let out = dir.join("out");
    let e = build_report(
        &[dir.join("cmp"), dir.join("missing_run")],
        &out,
        Existing::Refuse,
    )
    .unwrap_err();
    assert!(e.to_string().contains("missing_run: no such folder"), "{e}");
    assert!(
        !out.exists(),
        "files written before the inputs were checked"
    );
}

#[test]
fn a_broken_recorded_episode_stops_the_report_before_any_chart() {
    let dir = temp_dir("notebook-broken-episode");
    write_comparison(&dir.join("cmp"), Vec::new());
    std::fs::write(
        dir.join("cmp/episodes/baseline_hard_ep0.json"),
        "{\"rows\": 3}",
    )
    .unwrap();
    let out = dir.join("out");
    let e = build_report(&[dir.join("cmp")], &out, Existing::Refuse).unwrap_err();
    assert!(
        e.to_string()
            .contains("baseline_hard_ep0.json: not a fairgrasp trajectory JSON"),
        "{e}"
    );
    assert!(
        !out.exists(),
        "charts written before the episode was checked"
    );
}
