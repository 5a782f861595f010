//! `metrics.csv`: one row per PPO update — progress, the episodes that finished in the update
//! (return, success, length, and the share of each outcome), the update's diagnostics, the
//! curriculum stage, the evaluation's success rate when one ran, and the update's speed. The
//! TensorBoard events ([`crate::run::tensorboard`]) carry the same cells.

use fairgrasp_types::Outcome;

use crate::ppo::UpdateStats;
use crate::ppo::vec_api::EpisodeStats;

/// The columns before the outcome shares.
const LEADING_COLUMNS: &str = "update,timesteps,wall_time_s,episodes,episode_return,success_rate,episode_length,policy_loss,value_loss,entropy,approx_kl,clip_fraction,explained_variance,learning_rate,stage,eval_success_rate";

/// The header line: `LEADING_COLUMNS`, then `outcome_<name>` for every [`Outcome`] (the share
/// of the update's finished episodes that ended so), then `steps_per_second` (environment steps
/// per second of the update's rollout and learning) and `kickstart_loss` (the teachers' term,
/// [`crate::ppo::teacher`]; 0 without teachers). Files written before the later columns
/// existed have a prefix of them (a resume pads their rows).
pub fn metrics_header() -> String {
    let mut header = LEADING_COLUMNS.to_string();
    for o in Outcome::ALL {
        header.push_str(",outcome_");
        header.push_str(o.as_str());
    }
    header.push_str(",steps_per_second,kickstart_loss");
    header
}

/// The row of update `update` at `timesteps`, `wall` seconds of training \[s\], `speed`
/// environment steps per second, curriculum `stage` and evaluation success rate `eval`.
pub fn metrics_row(
    update: u64,
    timesteps: u64,
    (wall, speed): (f64, f64),
    s: &UpdateStats,
    stage: usize,
    eval: Option<f64>,
) -> String {
    let n = s.episodes.len().max(1) as f64;
    let mean = |f: &dyn Fn(&EpisodeStats) -> f64| s.episodes.iter().map(f).sum::<f64>() / n;
    let mut row = format!(
        "{update},{timesteps},{wall:.2},{},{:.4},{:.4},{:.2},{:.6},{:.6},{:.5},{:.6},{:.4},{:.4},{:.3e},{stage},{}",
        s.episodes.len(),
        mean(&|e| e.episode_return as f64),
        mean(&|e| e.success as u8 as f64),
        mean(&|e| e.length as f64),
        s.policy_loss,
        s.value_loss,
        s.entropy,
        s.approx_kl,
        s.clip_fraction,
        s.explained_variance,
        s.learning_rate,
        eval.map_or(String::new(), |e| format!("{e:.4}")),
    );
    for &o in Outcome::ALL {
        let share = mean(&|e| f64::from(u8::from(e.outcome == Some(o))));
        row.push_str(&format!(",{share:.4}"));
    }
    row.push_str(&format!(",{speed:.1},{:.6}", s.kickstart_loss));
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    fn episode(outcome: Option<Outcome>) -> EpisodeStats {
        EpisodeStats {
            success: outcome == Some(Outcome::Success),
            outcome,
            episode_return: 1.0,
            length: 10,
            object_xy: None,
        }
    }

    #[test]
    fn a_row_has_a_cell_per_header_column_and_the_outcome_shares_of_its_episodes() {
        let stats = UpdateStats {
            episodes: vec![
                episode(Some(Outcome::Success)),
                episode(Some(Outcome::Success)),
                episode(Some(Outcome::Collision)),
                episode(Some(Outcome::Timeout)),
            ],
            ..UpdateStats::default()
        };
        let header = metrics_header();
        let row = metrics_row(3, 96, (1.5, 64.25), &stats, 0, None);
        let columns: Vec<&str> = header.split(',').collect();
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(columns.len(), cells.len());
        let cell = |name: &str| cells[columns.iter().position(|c| *c == name).unwrap()];
        assert_eq!(cell("success_rate"), "0.5000");
        assert_eq!(cell("outcome_success"), "0.5000");
        assert_eq!(cell("outcome_collision"), "0.2500");
        assert_eq!(cell("outcome_timeout"), "0.2500");
        assert_eq!(cell("outcome_missed_grasp"), "0.0000");
        assert_eq!(cell("steps_per_second"), "64.2");
        assert!(header.starts_with(LEADING_COLUMNS));
    }
}
