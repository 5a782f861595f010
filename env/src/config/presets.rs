//! Named configurations: `fixed`, `sector`, `wide`, `full`, `hard` and the scenario families
//! `miscalibrated`, `miscalibrated_b`, `wrist_camera`, `nudged` (`env/src/scenario/<family>/`)
//! the contact family `heavy_slippery` and the place task's `place`, `place_grasp_error`,
//! `place_fixture_error`, `place_tilted` and the mix of the three, `place_cell`, and the stack
//! task's `stack` and `stack_camera_error`, shipped as TOML files in
//! `assets/configs/` and built into the binary, so `--preset NAME` works from any folder.
//!
//! A preset that was renamed keeps its old name as an alias ([`RENAMED_PRESETS`]): every
//! reader resolves it with [`current_name`], and the front ends tell the user with
//! [`rename_note`].

use crate::config::EnvConfig;
use crate::config::validate::ConfigError;

/// Every preset: name, TOML text, one-line description.
pub const PRESETS: [(&str, &str, &str); 17] = [
    (
        "fixed",
        include_str!("../../../assets/configs/fixed.toml"),
        "nothing randomised: the cube 0.35 m in front of the base",
    ),
    (
        "sector",
        include_str!("../../../assets/configs/sector.toml"),
        "the cube anywhere in a sector in front of the base (r 0.25–0.35 m, ±90°) with any yaw",
    ),
    (
        "wide",
        include_str!("../../../assets/configs/wide.toml"),
        "a wider sector (r 0.25–0.45 m, ±135°) and yaw",
    ),
    (
        "full",
        include_str!("../../../assets/configs/full.toml"),
        "wide + friction, mass and joint-noise randomisation",
    ),
    (
        "hard",
        include_str!("../../../assets/configs/hard.toml"),
        "full + perception noise (1 cm, 10°) on the observed cube",
    ),
    (
        "miscalibrated",
        include_str!("../../../assets/configs/miscalibrated.toml"),
        "full seen through a miscalibrated camera (cell A: a fixed 2° and 1.1 cm error, 1.9 cm median)",
    ),
    (
        "miscalibrated_b",
        include_str!("../../../assets/configs/miscalibrated_b.toml"),
        "full seen through a miscalibrated camera (cell B: a fixed -2.5° and 0.9 cm error, 2.2 cm median)",
    ),
    (
        "wrist_camera",
        include_str!("../../../assets/configs/wrist_camera.toml"),
        "full seen by a fixed camera off by N(0, 2 cm) and N(0, 10°) per episode, plus a wrist camera exact within 15 cm",
    ),
    (
        "nudged",
        include_str!("../../../assets/configs/nudged.toml"),
        "full + the cube pushed 1.5–3 cm once during the approach",
    ),
    (
        "heavy_slippery",
        include_str!("../../../assets/configs/heavy_slippery.toml"),
        "full with cubes of 0.3–1.0 kg and friction 0.05–0.3: heavier and more slippery than the script's 5 N grip holds",
    ),
    (
        "place",
        include_str!("../../../assets/configs/place.toml"),
        "the place task: seat the cube in a pocket with 2 mm clearance per side, the fixture drawn per scenario; no perception error",
    ),
    (
        "place_grasp_error",
        include_str!("../../../assets/configs/place_grasp_error.toml"),
        "place with the cube seen off by N(0, 3 mm), N(0, 2°): the grasp is off-centre, unobserved",
    ),
    (
        "place_fixture_error",
        include_str!("../../../assets/configs/place_fixture_error.toml"),
        "place with the fixture known to N(0, 3 mm), N(0, 1.5°) (its layout's tolerance)",
    ),
    (
        "place_tilted",
        include_str!("../../../assets/configs/place_tilted.toml"),
        "place with the cube turning 4–10° in the grip once lifted (about the pads' axis), unobserved: wider than the pocket as it hangs",
    ),
    (
        "place_cell",
        include_str!("../../../assets/configs/place_cell.toml"),
        "a real place cell: each cycle one family's error (fixture pose, grasp, tilt in the grip), unlabelled, a third each; wall friction drawn; 20 s takt",
    ),
    (
        "stack",
        include_str!("../../../assets/configs/stack.toml"),
        "the stack task: set the cube down squarely on a second cube, drawn per scenario; no perception error",
    ),
    (
        "stack_camera_error",
        include_str!("../../../assets/configs/stack_camera_error.toml"),
        "stack with the second cube seen off by N(0, 3 mm), N(0, 1.5°) (the camera's errors)",
    ),
];

/// Presets that were renamed, as (old name, current name). The old names are still accepted
/// everywhere a preset is named (with a note, [`rename_note`]) and resolve to the current one.
pub const RENAMED_PRESETS: [(&str, &str); 1] = [("seed", "sector")];

/// The current name of the preset `name` and whether `name` is an old one
/// ([`RENAMED_PRESETS`]); any other name (a current one, a `.toml` path, an unknown name)
/// comes back as it is.
pub fn current_name(name: &str) -> (&str, bool) {
    match RENAMED_PRESETS.iter().find(|(old, _)| *old == name) {
        Some((_, new)) => (new, true),
        None => (name, false),
    }
}

/// The one line telling the user that `name` is an old preset name, or None if it is not one:
/// `preset "seed" is now called "sector"; the old name still works for now`.
pub fn rename_note(name: &str) -> Option<String> {
    let (new, renamed) = current_name(name);
    renamed.then(|| {
        format!("preset \"{name}\" is now called \"{new}\"; the old name still works for now")
    })
}

/// Serde's reader of a preset name (`deserialize_with`): an old name is read as the current
/// one, so a file written with the old name loads and is written back with the new.
pub fn deserialize_name<'de, D>(d: D) -> Result<String, D::Error>
where
    D: serde::Deserializer<'de>,
{
    let name = <String as serde::Deserialize>::deserialize(d)?;
    Ok(current_name(&name).0.to_string())
}

/// [`deserialize_name`] for a list of preset names.
pub fn deserialize_names<'de, D>(d: D) -> Result<Vec<String>, D::Error>
where
    D: serde::Deserializer<'de>,
{
    let names = <Vec<String> as serde::Deserialize>::deserialize(d)?;
    Ok(names
        .iter()
        .map(|n| current_name(n).0.to_string())
        .collect())
}

/// The preset `name` (an old name, [`RENAMED_PRESETS`], loads its current preset), or the TOML
/// file at `name` if it ends in `.toml`.
pub fn load(name: &str) -> Result<EnvConfig, ConfigError> {
    if name.ends_with(".toml") {
        return EnvConfig::from_toml_file(name);
    }
    let (name, _) = current_name(name);
    match PRESETS.iter().find(|(n, _, _)| *n == name) {
        Some((n, text, _)) => EnvConfig::from_toml_str(text).map_err(|e| ConfigError::File {
            path: format!("assets/configs/{n}.toml"),
            message: e.to_string(),
        }),
        None => Err(ConfigError::File {
            path: name.to_string(),
            message: format!(
                "no such preset; choose one of {} or give a .toml file",
                PRESETS
                    .iter()
                    .map(|(n, _, _)| *n)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }),
    }
}
