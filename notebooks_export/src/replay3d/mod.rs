//! The interactive 3D replay: one self-contained HTML file (`replay.html`) that opens from disk
//! with no network. three.js (the bundle committed in `web/vendor/`, built from the npm package
//! at the version pinned in `web/package-lock.json`, its licence kept in the file) is inlined;
//! so are the viewer (`scene.js`: data and 3D scene; `viewer.js`: controls, timeline, URL
//! fragment, the state a test reads; `viewer.css`) and the episodes ([`pack`]).
//!
//! The viewer draws the FR3 from the simulation's shapes on the recorded bodies (capsules for
//! the links, boxes for the palm, finger struts and pads), the table, the cube and the base's
//! mount in the world frame; a timeline with play/pause, speed, step and scrub shows the
//! policy's phase, the reward, the gripper command, the pad contacts and events, and the
//! outcome at the end; a selector picks any recorded method and episode, and a second one shows
//! another method on the same scenario side by side. `replay.html#episode=3&t=2.5` opens
//! entry 3 (as numbered in the selector) at 2.5 s; `&with=5` adds entry 5 beside it.

pub mod episode;
pub mod pack;
pub mod section;

pub use episode::ReplayEpisode;

use std::path::Path;

use serde_json::json;

use crate::error::{ReportError, write_file};

/// The parts of three.js the viewer uses (`web/src/three-subset.js`), bundled and minified by
/// esbuild into a script that defines the global `THREE`. Committed in `web/vendor/` with
/// three.js's licence and version, so every build has it without node;
/// `scripts/check-three-bundle.sh` rebuilds it from the npm packages pinned in
/// `web/package-lock.json` and fails if it differs.
const THREE_JS: &str = include_str!("../../web/vendor/three.min.js");
const THREE_LICENSE: &str = include_str!("../../web/vendor/three-LICENSE.txt");
const THREE_VERSION: &str = include_str!("../../web/vendor/three-version.txt");
const SCENE_JS: &str = include_str!("scene.js");
const VIEWER_JS: &str = include_str!("viewer.js");
const VIEWER_CSS: &str = include_str!("viewer.css");

/// Marks a file as a fairgrasp replay (what `fairgrasp replay` may overwrite).
pub const GENERATOR: &str = "fairgrasp replay";

/// The three.js version inlined into replays (`0.187.0`): every build has the committed bundle.
pub fn three_version() -> &'static str {
    THREE_VERSION.trim()
}

/// Is `path` a replay that fairgrasp wrote (so it may be replaced)?
pub fn is_replay_file(path: &Path) -> bool {
    // Only the start of a regular file is read (a device or a pipe is not a replay).
    fairgrasp_types::output::head(path).is_some_and(|bytes| {
        let head = &bytes[..bytes.len().min(2_000)];
        String::from_utf8_lossy(head).contains(&format!("content=\"{GENERATOR}\""))
    })
}

/// JSON text safe inside a `<script>` element: no `</` can close it early (`<\/` is the same
/// string in JSON).
fn json_in_script(text: &str) -> String {
    text.replace("</", "<\\/")
}

/// JavaScript safe inside a `<script>` element: the two sequences the HTML parser acts on
/// there (`</script` and `<!--`) are escaped; in the code they can only occur in string or
/// regular-expression literals, where the escaped forms mean the same.
fn js_in_script(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find('<') {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        if tail
            .get(..8)
            .is_some_and(|t| t.eq_ignore_ascii_case("</script"))
        {
            out.push_str("<\\/");
            rest = &tail[2..];
        } else if let Some(after) = tail.strip_prefix("<!--") {
            out.push_str("<\\!--");
            rest = after;
        } else {
            out.push('<');
            rest = &tail[1..];
        }
    }
    out.push_str(rest);
    out
}

/// Escapes text for HTML element content.
fn html_text(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The replay page for `episodes` under `title`.
pub fn replay_html(title: &str, episodes: &[ReplayEpisode<'_>]) -> Result<String, ReportError> {
    let version = THREE_VERSION.trim();
    if episodes.is_empty() {
        return Err(ReportError::ReplayUnavailable(
            "no recorded episode to replay".into(),
        ));
    }
    if let Some(e) = episodes.iter().find(|e| e.trajectory.rows.is_empty()) {
        return Err(ReportError::ReplayUnavailable(format!(
            "{} on {} episode {}: the trajectory has no rows",
            e.method, e.preset, e.episode
        )));
    }
    let packed = pack::pack(episodes).map_err(|e| ReportError::ReplayUnavailable(e.to_string()))?;
    let mut index = packed.index;
    index["title"] = json!(title);
    index["values"] = json!(packed.values);
    index["three"] = json!(version);
    use base64::Engine;
    let poses = base64::engine::general_purpose::STANDARD.encode(&packed.poses_gz);
    let licence = THREE_LICENSE.replace("*/", "* /");
    Ok(format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"generator\" content=\"{GENERATOR}\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>\n{VIEWER_CSS}</style>\n</head>\n<body>\n\
         <div id=\"app\"></div>\n\
         <script type=\"application/json\" id=\"replay-index\">{}</script>\n\
         <script type=\"text/plain\" id=\"replay-poses\">{poses}</script>\n\
         <script>\n/*! three.js {version} (npm package `three`), bundled with esbuild: only the \
         parts the viewer uses.\n{licence}*/\n{}\n</script>\n\
         <script>\n(function () {{\n\"use strict\";\n{}\n{}\n}})();\n</script>\n</body>\n</html>\n",
        html_text(title),
        json_in_script(&index.to_string()),
        js_in_script(THREE_JS),
        js_in_script(SCENE_JS),
        js_in_script(VIEWER_JS),
    ))
}

/// Writes the replay page for `episodes` to `path` (atomically).
pub fn write_replay(
    path: &Path,
    title: &str,
    episodes: &[ReplayEpisode<'_>],
) -> Result<(), ReportError> {
    let html = replay_html(title, episodes)?;
    write_file(path, html.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn script_text_cannot_end_its_element_early() {
        assert_eq!(
            js_in_script(r#"a="</SCRIPT>";b="<!--";c=d<e"#),
            r#"a="<\/SCRIPT>";b="<\!--";c=d<e"#
        );
        assert_eq!(json_in_script(r#"{"t":"</b>"}"#), r#"{"t":"<\/b>"}"#);
    }
}
