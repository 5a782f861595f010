//! The 3D replay in a real browser: `fairgrasp replay` writes one HTML file for two methods on
//! one scenario; Debian's chromium-headless-shell (software WebGL) opens it from disk through
//! playwright-core (`notebooks_export/web/test/replay-browser.mjs` prints what it saw). The
//! page draws (not blank), two moments of the timeline (the second opened by the URL fragment)
//! draw the arm in different places, the selector switches episodes, the second selector puts
//! another method beside it, playing advances time, and the page makes no network request.
//!
//! Skipped, with a message, only where no Chromium is installed; `scripts/install-browser.sh`
//! installs it (and the npm packages, whose absence fails the test).

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The installed headless Chromium, if any.
fn chromium() -> Option<PathBuf> {
    ["chromium-headless-shell", "chromium"]
        .iter()
        .flat_map(|name| {
            std::env::var_os("PATH")
                .map(|p| {
                    std::env::split_paths(&p)
                        .map(|d| d.join(name))
                        .collect::<Vec<_>>()
                })
                .unwrap_or_default()
        })
        .find(|p| p.is_file())
}

fn distance(a: &Value, b: &Value) -> f64 {
    (0..3)
        .map(|k| (a[k].as_f64().unwrap() - b[k].as_f64().unwrap()).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn the_replay_draws_moves_switches_and_stays_offline_in_chromium() {
    let Some(browser) = chromium() else {
        eprintln!(
            "SKIPPED: no Chromium installed (chromium-headless-shell or chromium on PATH); \
             scripts/install-browser.sh installs it"
        );
        return;
    };
    let web = repo().join("notebooks_export/web");
    assert!(
        web.join("node_modules/playwright-core").is_dir(),
        "playwright-core is not installed in {}: run scripts/install-browser.sh",
        web.display()
    );
    let dir = std::env::temp_dir().join(format!("fairgrasp-replay-browser-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let html = dir.join("replay.html");
    write_two_method_replay(&html);
    let shot = dir.join("replay.png");
    let seen = open_in_browser(&web, &browser, &html, &shot);
    assert_page_drew_without_errors(&seen, &shot);
    assert_the_end_moment_differs_from_the_start(&seen);
    assert_selectors_switch_the_episode(&seen);
    assert_no_network_request(&seen);
    std::fs::remove_dir_all(&dir).ok();
}

/// `fairgrasp replay` of the open-loop script and the oracle on one `sector` scenario into
/// `html`, under 2 MB.
fn write_two_method_replay(html: &Path) {
    let out = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
        .args(["replay", "--policy", "open_loop", "--policy", "oracle"])
        .args(["--preset", "sector", "--episode", "1", "--out"])
        .arg(html)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "fairgrasp replay failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let size = std::fs::metadata(html).unwrap().len();
    assert!(size < 2_000_000, "a two-episode replay is {size} bytes");
}

/// Runs the browser script (`web/test/replay-browser.mjs`) on `html` in `browser`, with a
/// screenshot to `shot`, and returns what it printed (JSON).
fn open_in_browser(web: &Path, browser: &Path, html: &Path, shot: &Path) -> Value {
    let run = Command::new("node")
        .arg(web.join("test/replay-browser.mjs"))
        .arg(browser)
        .arg(html)
        .arg(shot)
        .current_dir(web)
        .output()
        .expect("node runs the browser script");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "the browser script failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

/// The page loaded both episodes without errors and is not blank: many colours, much of the
/// canvas not background; the screenshot `shot` was written.
fn assert_page_drew_without_errors(seen: &Value, shot: &Path) {
    assert!(seen["failure"].is_null(), "{}", seen["failure"]);
    assert_eq!(seen["errors"], serde_json::json!([]), "page errors");
    assert_eq!(seen["ready"], true);
    assert_eq!(seen["count"], 2);
    let pixels = &seen["start"]["pixels"];
    assert!(pixels["colours"].as_u64().unwrap() > 200, "{pixels}");
    assert!(pixels["notBackground"].as_f64().unwrap() > 0.1, "{pixels}");
    assert!(shot.is_file());
}

/// Two moments: the fragment opened the end; the TCP (more than 5 cm) and the image moved, the
/// outcome shows.
fn assert_the_end_moment_differs_from_the_start(seen: &Value) {
    let (start, end) = (&seen["start"], &seen["end"]);
    assert_eq!(start["state"]["time"], 0.0);
    assert_eq!(end["state"]["time"], start["state"]["duration"]);
    let moved = distance(&start["state"]["tcp"], &end["state"]["tcp"]);
    assert!(
        moved > 0.05,
        "the TCP moved {moved} m between the two moments"
    );
    assert_ne!(
        start["pixels"]["hash"], end["pixels"]["hash"],
        "the same image at both moments"
    );
    assert!(
        end["state"]["banner"]
            .as_str()
            .unwrap()
            .contains("outcome: "),
        "{}",
        end["state"]["banner"]
    );
    assert!(
        end["state"]["fragment"]
            .as_str()
            .unwrap()
            .starts_with("#episode=0&t=")
    );
}

/// The selector switched to the other method (another label, another image), the second
/// selector put the first method beside it on the same scenario, and playing advanced time.
fn assert_selectors_switch_the_episode(seen: &Value) {
    let (start, switched) = (&seen["start"], &seen["switched"]);
    assert_eq!(switched["state"]["episode"], 1);
    assert_ne!(switched["state"]["label"], start["state"]["label"]);
    assert!(
        switched["state"]["label"]
            .as_str()
            .unwrap()
            .contains("oracle script")
    );
    assert_ne!(switched["pixels"]["hash"], start["pixels"]["hash"]);
    assert_eq!(seen["sideBySide"]["partner"], 0, "{}", seen["sideBySide"]);
    assert!(
        seen["played"].as_f64().unwrap() > 0.0,
        "playing did not advance"
    );
}

/// No network: the only request is the page's own file (blob: and data: URLs aside).
fn assert_no_network_request(seen: &Value) {
    let url = seen["url"].as_str().unwrap();
    let requests = seen["requests"].as_array().unwrap();
    assert!(!requests.is_empty());
    for r in requests {
        let r = r.as_str().unwrap();
        assert!(
            r.split('#').next() == Some(url) || r.starts_with("blob:") || r.starts_with("data:"),
            "the page requested {r}"
        );
    }
}
