//! The trained policies shipped in `assets/policies/`, built into every binary that links this
//! crate, so `fairgrasp eval` and `fairgrasp compare` find them from any folder and after
//! `cargo install` (no path from the build machine is kept).
//!
//! A checkpoint is a folder (`meta.json`, `model.bpk`) beside its run files (`metrics.csv`,
//! `config.toml`, `train.toml`); the first use unpacks each policy's files into a folder of the
//! system's temporary directory named after this version and the files' content hash, and every
//! use checks that the files there are byte for byte the built-in ones (rewriting any that are
//! not).

use std::path::{Path, PathBuf};

use fairgrasp_types::write_atomic;

/// A policy shipped with fairgrasp.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShippedPolicy {
    /// The first residual (joint-space corrections of the baseline's action) on `hard`: the
    /// documented negative result (the perception error it would have to fix is unobservable).
    ResidualHard,
    /// Pure PPO with the seed recipe's reward on `hard`: the guide's pitfall 2 (it hovers).
    PureHard,
    /// Pure PPO that grasps: task-space action, staged reward, curriculum, trained on `full`.
    PureFull,
    /// The residual with authority (task-space correction) in the miscalibrated cell A.
    ResidualMiscalibrated,
    /// The same recipe in cell B (`miscalibrated_b`).
    ResidualMiscalibratedB,
    /// The same recipe on `nudged` (the cube pushed during the approach).
    ResidualNudged,
    /// The same recipe on `wrist_camera` (a coarse fixed camera and an exact wrist camera).
    ResidualWristCamera,
    /// The residual with the squeeze on `heavy_slippery` (cubes the script's grip cannot lift).
    ResidualHeavySlippery,
    /// One residual with the squeeze for `full`, `nudged`, `wrist_camera` and `heavy_slippery`,
    /// kickstarted from the three specialists above.
    ResidualGeneralist,
}

/// A file of a shipped policy: its path inside the policy folder, and its bytes.
type File = (&'static str, &'static [u8]);

/// Every file of the policy folder `assets/policies/<name>/`.
macro_rules! policy_files {
    ($name:literal) => {
        &[
            (
                "checkpoint/meta.json",
                include_bytes!(concat!(
                    "../../assets/policies/",
                    $name,
                    "/checkpoint/meta.json"
                )) as &[u8],
            ),
            (
                "checkpoint/model.bpk",
                include_bytes!(concat!(
                    "../../assets/policies/",
                    $name,
                    "/checkpoint/model.bpk"
                )),
            ),
            (
                "checkpoint/checksum",
                include_bytes!(concat!(
                    "../../assets/policies/",
                    $name,
                    "/checkpoint/checksum"
                )),
            ),
            (
                "metrics.csv",
                include_bytes!(concat!("../../assets/policies/", $name, "/metrics.csv")),
            ),
            (
                "config.toml",
                include_bytes!(concat!("../../assets/policies/", $name, "/config.toml")),
            ),
            (
                "train.toml",
                include_bytes!(concat!("../../assets/policies/", $name, "/train.toml")),
            ),
        ]
    };
}

const RESIDUAL_HARD: &[File] = policy_files!("residual_hard");
const PURE_HARD: &[File] = policy_files!("pure_hard");
const PURE_FULL: &[File] = policy_files!("pure_full");
const RESIDUAL_MISCALIBRATED: &[File] = policy_files!("residual_miscalibrated");
const RESIDUAL_MISCALIBRATED_B: &[File] = policy_files!("residual_miscalibrated_b");
const RESIDUAL_NUDGED: &[File] = policy_files!("residual_nudged");
const RESIDUAL_WRIST_CAMERA: &[File] = policy_files!("residual_wrist_camera");
const RESIDUAL_HEAVY_SLIPPERY: &[File] = policy_files!("residual_heavy_slippery");
const RESIDUAL_GENERALIST: &[File] = policy_files!("residual_generalist");

/// A shipped policy that could not be unpacked.
#[derive(Debug, thiserror::Error)]
#[error("unpacking the shipped policy `{policy}` to {path}: {source}")]
pub struct ShippedError {
    pub policy: &'static str,
    pub path: PathBuf,
    pub source: std::io::Error,
}

impl ShippedPolicy {
    /// Every shipped policy.
    pub const ALL: [ShippedPolicy; 9] = [
        ShippedPolicy::ResidualMiscalibrated,
        ShippedPolicy::ResidualMiscalibratedB,
        ShippedPolicy::ResidualNudged,
        ShippedPolicy::ResidualWristCamera,
        ShippedPolicy::ResidualHeavySlippery,
        ShippedPolicy::ResidualGeneralist,
        ShippedPolicy::PureFull,
        ShippedPolicy::ResidualHard,
        ShippedPolicy::PureHard,
    ];

    /// The shipped policy called `name` ([`ShippedPolicy::name`]), if any.
    pub fn named(name: &str) -> Option<ShippedPolicy> {
        ShippedPolicy::ALL.into_iter().find(|p| p.name() == name)
    }

    /// Whether `fairgrasp compare` compares it by default: the generalist residual and pure PPO
    /// (one learned policy of each kind, on every preset). The specialists join with
    /// `--policy all` ([`ShippedPolicy::compared_with_all`]) or by name.
    pub fn compared_by_default(self) -> bool {
        matches!(
            self,
            ShippedPolicy::ResidualGeneralist | ShippedPolicy::PureFull
        )
    }

    /// Whether `fairgrasp compare --policy all` compares it: every shipped policy but the
    /// pitfall exhibit `pure_hard` (0 % everywhere; the guide's pitfall 2 evaluates it).
    pub fn compared_with_all(self) -> bool {
        self != ShippedPolicy::PureHard
    }

    /// The folder name under `assets/policies/` (also the run-folder label in comparisons).
    pub fn name(self) -> &'static str {
        match self {
            ShippedPolicy::ResidualHard => "residual_hard",
            ShippedPolicy::PureHard => "pure_hard",
            ShippedPolicy::PureFull => "pure_full",
            ShippedPolicy::ResidualMiscalibrated => "residual_miscalibrated",
            ShippedPolicy::ResidualMiscalibratedB => "residual_miscalibrated_b",
            ShippedPolicy::ResidualNudged => "residual_nudged",
            ShippedPolicy::ResidualWristCamera => "residual_wrist_camera",
            ShippedPolicy::ResidualHeavySlippery => "residual_heavy_slippery",
            ShippedPolicy::ResidualGeneralist => "residual_generalist",
        }
    }

    fn files(self) -> &'static [File] {
        match self {
            ShippedPolicy::ResidualHard => RESIDUAL_HARD,
            ShippedPolicy::PureHard => PURE_HARD,
            ShippedPolicy::PureFull => PURE_FULL,
            ShippedPolicy::ResidualMiscalibrated => RESIDUAL_MISCALIBRATED,
            ShippedPolicy::ResidualMiscalibratedB => RESIDUAL_MISCALIBRATED_B,
            ShippedPolicy::ResidualNudged => RESIDUAL_NUDGED,
            ShippedPolicy::ResidualWristCamera => RESIDUAL_WRIST_CAMERA,
            ShippedPolicy::ResidualHeavySlippery => RESIDUAL_HEAVY_SLIPPERY,
            ShippedPolicy::ResidualGeneralist => RESIDUAL_GENERALIST,
        }
    }

    /// The policy's checkpoint folder, unpacked under the system's temporary directory (never
    /// the working directory, whatever `TMPDIR` says).
    pub fn checkpoint_dir(self) -> Result<PathBuf, ShippedError> {
        self.checkpoint_dir_in(&fairgrasp_types::fs::system_temp_dir())
    }

    /// The policy's checkpoint folder, unpacked under `root`
    /// (`<root>/fairgrasp-<version>-<hash>/<name>/checkpoint`).
    pub fn checkpoint_dir_in(self, root: &Path) -> Result<PathBuf, ShippedError> {
        let folder = unpack_root(root).join(self.name());
        for (relative, bytes) in self.files() {
            let path = folder.join(relative);
            // Only a regular file is compared (a FIFO put in its place is not opened).
            let current =
                fairgrasp_types::fs::read_bounded(&path, fairgrasp_types::fs::MAX_DATA_BYTES).ok();
            if current.as_deref() != Some(*bytes) {
                write_atomic(&path, bytes).map_err(|source| ShippedError {
                    policy: self.name(),
                    path: path.clone(),
                    source,
                })?;
            }
        }
        Ok(folder.join("checkpoint"))
    }
}

/// The checkpoint folder `name_or_folder` names: a shipped policy's name (unpacked), a
/// checkpoint folder (`meta.json` inside, or in the `.old` copy a kill left) or a run folder
/// (its `checkpoints/best`). The error lists the shipped names.
pub fn checkpoint_folder(name_or_folder: &str) -> Result<PathBuf, String> {
    if let Some(p) = ShippedPolicy::named(name_or_folder) {
        return p.checkpoint_dir().map_err(|e| e.to_string());
    }
    let path = Path::new(name_or_folder);
    if path.join("meta.json").is_file() || path.with_extension("old").join("meta.json").is_file() {
        return Ok(path.to_path_buf());
    }
    if path.join("checkpoints/best/meta.json").is_file() {
        return Ok(path.join("checkpoints/best"));
    }
    // A policy folder as shipped in assets/policies/ (its checkpoint beside its run files).
    if path.join("checkpoint/meta.json").is_file() {
        return Ok(path.join("checkpoint"));
    }
    let names: Vec<&str> = ShippedPolicy::ALL.iter().map(|p| p.name()).collect();
    let shown: String = name_or_folder.chars().take(120).collect();
    Err(format!(
        "{shown:?} is neither a shipped policy ({}) nor a checkpoint folder (meta.json) nor a policy folder (checkpoint/) nor a run folder (checkpoints/best)",
        names.join(", ")
    ))
}

/// The shipped residual policy's checkpoint folder: the default of `fairgrasp eval`.
pub fn default_policy() -> Result<PathBuf, ShippedError> {
    ShippedPolicy::ResidualHard.checkpoint_dir()
}

/// The checkpoint folders of the policies compared by default
/// ([`ShippedPolicy::compared_by_default`], in [`ShippedPolicy::ALL`]'s order): the default of
/// `fairgrasp compare`.
pub fn default_compare_policies() -> Result<Vec<PathBuf>, ShippedError> {
    ShippedPolicy::ALL
        .iter()
        .filter(|p| p.compared_by_default())
        .map(|p| p.checkpoint_dir())
        .collect()
}

/// The checkpoint folders `fairgrasp compare --policy all` compares
/// ([`ShippedPolicy::compared_with_all`], in [`ShippedPolicy::ALL`]'s order).
pub fn all_compare_policies() -> Result<Vec<PathBuf>, ShippedError> {
    ShippedPolicy::ALL
        .iter()
        .filter(|p| p.compared_with_all())
        .map(|p| p.checkpoint_dir())
        .collect()
}

/// The unpack folder under `root`, named after the crate version and a hash (FNV-1a, 64 bit)
/// of every shipped file's name and bytes: another build never reuses these files.
fn unpack_root(root: &Path) -> PathBuf {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for p in ShippedPolicy::ALL {
        for (name, bytes) in p.files() {
            for b in p
                .name()
                .bytes()
                .chain(name.bytes())
                .chain(bytes.iter().copied())
            {
                hash = (hash ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    root.join(format!(
        "fairgrasp-{}-policies-{hash:016x}",
        env!("CARGO_PKG_VERSION")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("fairgrasp-shipped-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        dir
    }

    #[test]
    fn unpacked_policies_are_the_built_in_bytes_and_load_as_checkpoints() {
        let root = scratch("load");
        for p in ShippedPolicy::ALL {
            let dir = p.checkpoint_dir_in(&root).unwrap();
            assert!(dir.starts_with(&root), "{}", dir.display());
            assert_eq!(dir.parent().unwrap().file_name().unwrap(), p.name());
            for (relative, bytes) in p.files() {
                let path = dir.parent().unwrap().join(relative);
                assert_eq!(&std::fs::read(&path).unwrap(), bytes, "{}", path.display());
            }
            let (meta, _) = crate::checkpoint::load_actor(&dir).unwrap();
            let mode = serde_json::to_value(meta.agent.mode).unwrap();
            assert_eq!(p.name().split('_').next(), mode.as_str(), "{}", p.name());
        }
        std::fs::remove_dir_all(&root).ok();
    }

    #[test]
    fn a_tampered_unpacked_file_is_rewritten() {
        let root = scratch("tamper");
        let dir = ShippedPolicy::PureHard.checkpoint_dir_in(&root).unwrap();
        std::fs::write(dir.join("meta.json"), b"{}").unwrap();
        let again = ShippedPolicy::PureHard.checkpoint_dir_in(&root).unwrap();
        assert_eq!(again, dir);
        assert_eq!(
            std::fs::read(dir.join("meta.json")).unwrap(),
            PURE_HARD[0].1,
            "meta.json was not restored"
        );
        std::fs::remove_dir_all(&root).ok();
    }
}
