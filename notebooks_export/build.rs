//! Bundles the part of three.js the 3D replay uses (`web/src/three-subset.js`: tree-shaken and
//! minified by esbuild into a script that defines the global `THREE`) into `OUT_DIR`, with
//! three.js's licence and version, for `src/replay3d/` to inline into every replay.html.
//!
//! Both come from the npm registry at the versions pinned in `web/package-lock.json`
//! (`scripts/install-browser.sh` runs `npm ci` in `web/`). Without them the crate still builds:
//! the bundle is left empty and writing a replay fails with an error that says how to install
//! them. Nothing here uses the network.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets it"));
    let web = manifest.join("web");
    let three = web.join("node_modules/three");
    let esbuild = web.join("node_modules/.bin/esbuild");
    for watched in [
        web.join("src/three-subset.js"),
        web.join("package-lock.json"),
        // npm writes this after every install: a later `npm ci` rebuilds the bundle.
        web.join("node_modules/.package-lock.json"),
    ] {
        println!("cargo::rerun-if-changed={}", watched.display());
    }
    let (bundle, licence, version) = match bundle(&web, &three, &esbuild, &out) {
        Ok(found) => found,
        Err(why) => {
            println!(
                "cargo::warning=replay.html will be unavailable: {why} (run scripts/install-browser.sh, then build again)"
            );
            (String::new(), String::new(), String::new())
        }
    };
    for (name, text) in [
        ("three.min.js", bundle),
        ("three-LICENSE.txt", licence),
        ("three-version.txt", version),
    ] {
        std::fs::write(out.join(name), text).expect("OUT_DIR is writable");
    }
}

/// The bundle, three.js's licence text and its version, or why they are missing.
fn bundle(
    web: &Path,
    three: &Path,
    esbuild: &Path,
    out: &Path,
) -> Result<(String, String, String), String> {
    let package = std::fs::read_to_string(three.join("package.json"))
        .map_err(|_| format!("three.js is not installed in {}", web.display()))?;
    let version = package
        .split("\"version\"")
        .nth(1)
        .and_then(|rest| rest.split('"').nth(1))
        .ok_or("three.js's package.json names no version")?
        .to_string();
    let licence = std::fs::read_to_string(three.join("LICENSE"))
        .map_err(|e| format!("three.js's LICENSE: {e}"))?;
    if !esbuild.exists() {
        return Err(format!("esbuild is not installed in {}", web.display()));
    }
    let target = out.join("three.bundle.js");
    let status = Command::new(esbuild)
        .current_dir(web)
        .args([
            "src/three-subset.js",
            "--bundle",
            "--minify",
            "--format=iife",
            "--global-name=THREE",
            "--legal-comments=none",
            "--log-level=warning",
        ])
        .arg(format!("--outfile={}", target.display()))
        .status()
        .map_err(|e| format!("running esbuild: {e}"))?;
    if !status.success() {
        return Err(format!("esbuild failed ({status})"));
    }
    let bundle = std::fs::read_to_string(&target).map_err(|e| format!("esbuild's output: {e}"))?;
    Ok((bundle, licence, version))
}
