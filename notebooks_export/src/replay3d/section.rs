//! The report's section for a comparison's 3D replay: `replay.html` with every episode the
//! comparison recorded for it (`compare.json`'s `replay`, or its `recorded` episodes in older
//! folders), and the text that links it.

use std::path::Path;

use crate::comparison_table::Comparison;
use crate::document::Document;
use crate::error::ReportError;
use crate::replay3d::{ReplayEpisode, write_replay};
use crate::trajectory::{self, Trajectory};

/// Writes `<prefix>replay.html` into `out` for the comparison `c` read from `dir`
/// (`recorded`: the trajectories of `c.recorded`, already loaded) and links it from `doc`.
pub fn replay_section(
    doc: &mut Document,
    (dir, c, recorded): (&Path, &Comparison, &[Trajectory]),
    out: &Path,
    prefix: &str,
    written: &mut Vec<String>,
) -> Result<(), ReportError> {
    let entries = if c.replay.is_empty() {
        &c.recorded
    } else {
        &c.replay
    };
    if entries.is_empty() {
        return Ok(());
    }
    let file = format!("{prefix}replay.html");
    let loaded: Vec<Trajectory> = if c.replay.is_empty() {
        recorded.to_vec()
    } else {
        entries
            .iter()
            .map(|e| trajectory::load(&dir.join(&e.trajectory)))
            .collect::<Result<_, _>>()?
    };
    let episodes: Vec<ReplayEpisode<'_>> = entries
        .iter()
        .zip(&loaded)
        .map(|(e, t)| ReplayEpisode {
            method: e.method.clone(),
            preset: e.preset.clone(),
            episode: e.episode,
            outcome: Some(e.outcome),
            trajectory: t,
        })
        .collect();
    let title = format!(
        "fairgrasp replay: {} on {}",
        c.methods.join(", "),
        entries[0].preset
    );
    write_replay(&out.join(&file), &title, &episodes)?;
    written.push(file.clone());
    let scenarios = {
        let mut k: Vec<usize> = entries.iter().map(|e| e.episode).collect();
        k.sort_unstable();
        k.dedup();
        k.len()
    };
    doc.markdown(format!(
        "### Watch it in 3D\n\n[{file}]({file}) replays every method on {scenarios} scenario(s) \
         of `{}` in 3D: open it in a browser (it needs no network). Pick a method and episode \
         at the top, and the same scenario by a second method beside it; play, step or scrub \
         the timeline, which shows the script's phase, the reward, the gripper command, the \
         pad contacts and what happened (collisions, pushes). A link opens one moment: \
         `{file}#episode=3&t=2.5` is entry 3 of the list at 2.5 s.",
        entries[0].preset
    ));
    Ok(())
}
