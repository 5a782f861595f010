//! Policies are verified before they act: every number of `meta.json` is checked against its
//! range (naming the field), one checksum covers the folder's files together (an edit of
//! `meta.json` within every range, a missing checksum, or a model from another save is refused),
//! and the shipped policies carry the checksum and load.

use std::path::{Path, PathBuf};

use fairgrasp_policy::checkpoint::{load_actor, load_meta};
use fairgrasp_policy::shipped::ShippedPolicy;

const SHIPPED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/policies");

/// A copy of the shipped policy `name`'s checkpoint in a fresh folder.
fn copy_of(name: &str, tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-verify-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let from = Path::new(SHIPPED).join(name).join("checkpoint");
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap();
    }
    dir
}

fn edit_meta(dir: &Path, edit: impl Fn(&mut serde_json::Value)) {
    let path = dir.join("meta.json");
    let mut meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    edit(&mut meta);
    std::fs::write(&path, serde_json::to_vec_pretty(&meta).unwrap()).unwrap();
}

#[test]
fn every_shipped_policy_carries_its_folder_checksum_and_loads() {
    for policy in ShippedPolicy::ALL {
        let dir = policy.checkpoint_dir().unwrap();
        assert!(dir.join("checksum").is_file(), "{policy:?}");
        let (meta, _) = load_actor(&dir).unwrap_or_else(|e| panic!("{policy:?}: {e}"));
        assert_eq!(meta.version, 2, "{policy:?}");
    }
}

#[test]
fn numbers_out_of_range_are_refused_naming_the_field() {
    type Edit = fn(&mut serde_json::Value);
    let cases: [(&str, Edit); 9] = [
        ("obs_norm.count", |m| m["obs_norm"]["count"] = 1e300.into()),
        ("obs_norm.count", |m| m["obs_norm"]["count"] = (-1.0).into()),
        ("obs_norm.var[3]", |m| {
            m["obs_norm"]["var"][3] = (-0.5).into()
        }),
        ("obs_norm.mean[0]", |m| {
            m["obs_norm"]["mean"][0] = 1e9.into()
        }),
        ("agent.residual_scale", |m| {
            m["agent"]["residual_scale"] = 1e30.into()
        }),
        ("updates", |m| m["updates"] = u64::MAX.into()),
        ("timesteps", |m| m["timesteps"] = u64::MAX.into()),
        ("eval_success_rate", |m| m["eval_success_rate"] = 7.0.into()),
        ("wall_time_s", |m| m["wall_time_s"] = (-3.0).into()),
    ];
    for (i, (field, edit)) in cases.iter().enumerate() {
        let dir = copy_of("residual_nudged", &format!("range{i}"));
        edit_meta(&dir, edit);
        let e = load_meta(&dir).unwrap_err().to_string();
        assert!(e.contains(&format!("{field} = ")), "{field}: {e}");
        assert!(e.len() < 300, "the message quotes the value whole: {e}");
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn the_folder_checksum_refuses_edits_missing_sums_and_mixed_saves() {
    // An edit that keeps every number in range: only the checksum can tell.
    let dir = copy_of("residual_nudged", "edit");
    edit_meta(&dir, |m| {
        let v = m["obs_norm"]["mean"][0].as_f64().unwrap();
        m["obs_norm"]["mean"][0] = (v + 0.01).into();
    });
    let e = load_actor(&dir).unwrap_err().to_string();
    assert!(e.contains("differ from their checksum"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
    // The weights of another policy of the same shape.
    let dir = copy_of("residual_nudged", "mixed");
    let other = Path::new(SHIPPED).join("residual_miscalibrated/checkpoint/model.bpk");
    std::fs::copy(other, dir.join("model.bpk")).unwrap();
    let e = load_actor(&dir).unwrap_err().to_string();
    assert!(e.contains("differ from their checksum"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
    // A version-2 folder without its checksum.
    let dir = copy_of("residual_nudged", "missing");
    std::fs::remove_file(dir.join("checksum")).unwrap();
    let e = load_actor(&dir).unwrap_err().to_string();
    assert!(e.contains("checksum: missing"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
