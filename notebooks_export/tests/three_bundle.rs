//! The three.js bundle every replay.html inlines is the committed one in `web/vendor/`, and it
//! agrees with what it was built from: the version pinned in `web/package-lock.json`, and every
//! name `web/src/three-subset.js` exports. (`scripts/check-three-bundle.sh` rebuilds it byte for
//! byte with npm; these checks need no node and catch an edit to either file without a rebuild.)

use std::path::PathBuf;

use fairgrasp_report::replay3d::three_version;

fn web() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("web")
}

fn read(path: &str) -> String {
    std::fs::read_to_string(web().join(path)).unwrap_or_else(|e| panic!("web/{path}: {e}"))
}

/// The version of three.js that `web/package-lock.json` pins.
fn pinned_three() -> String {
    let lock: serde_json::Value = serde_json::from_str(&read("package-lock.json")).unwrap();
    lock["packages"]["node_modules/three"]["version"]
        .as_str()
        .expect("package-lock.json pins three")
        .to_string()
}

#[test]
fn every_build_inlines_the_three_version_the_lock_file_pins() {
    let pinned = pinned_three();
    assert_eq!(three_version(), pinned.as_str());
    assert_eq!(read("vendor/three-version.txt").trim(), pinned);
    // three.js names its release by the minor version: 0.187.0 is r187, which the bundle
    // announces to the page as `window.__THREE__`.
    let revision = pinned.split('.').nth(1).unwrap();
    let bundle = read("vendor/three.min.js");
    assert!(
        bundle.contains(&format!("window.__THREE__=\"{revision}\"")),
        "vendor/three.min.js is not three.js r{revision} (package-lock.json pins {pinned}): \
         run scripts/check-three-bundle.sh --write"
    );
    assert!(read("vendor/three-LICENSE.txt").starts_with("The MIT License"));
}

#[test]
fn the_committed_bundle_exports_every_name_three_subset_asks_for() {
    let subset = read("src/three-subset.js");
    let list = subset
        .split("export {")
        .nth(1)
        .and_then(|rest| rest.split('}').next())
        .expect("three-subset.js has one `export { … }` list");
    let names: Vec<&str> = list
        .split(',')
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .collect();
    assert!(names.len() > 20, "{names:?}");
    let bundle = read("vendor/three.min.js");
    assert!(
        bundle.starts_with("var THREE=("),
        "the bundle defines the global THREE"
    );
    // esbuild's minified IIFE exports each name as `Name:()=>local`.
    let missing: Vec<&&str> = names
        .iter()
        .filter(|n| !bundle.contains(&format!("{n}:()=>")))
        .collect();
    assert!(
        missing.is_empty(),
        "three-subset.js exports {missing:?}, which vendor/three.min.js lacks: run \
         scripts/check-three-bundle.sh --write"
    );
}
