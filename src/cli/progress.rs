//! Live progress on stderr (never on stdout): `compare`'s progress bar per preset × method
//! (plain lines when stderr is not a terminal). `train`'s lines are in [`super::train`].

use std::collections::HashMap;
use std::io::IsTerminal;
use std::time::Instant;

use fairgrasp_evaluate::compare::CompareEvent;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};

/// `compare`'s progress: a bar per preset × method in a terminal, else a line per finished
/// preset × method; nothing with `quiet`. Two methods can be running at once (the workers share
/// one queue of episodes), so each bar is found by its preset and method.
pub struct CompareBars {
    multi: MultiProgress,
    /// The running bars and when each started, by (preset, method).
    running: HashMap<(String, String), (ProgressBar, Instant)>,
    episodes: u64,
    terminal: bool,
    quiet: bool,
}

impl CompareBars {
    /// Bars of `episodes` episodes each.
    pub fn new(episodes: u64, quiet: bool) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let target = if terminal && !quiet {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        CompareBars {
            multi: MultiProgress::with_draw_target(target),
            running: HashMap::new(),
            episodes,
            terminal,
            quiet,
        }
    }

    /// Shows one event of the comparison.
    pub fn event(&mut self, e: CompareEvent<'_>) {
        match e {
            CompareEvent::Method { preset, method } => {
                let bar = self.multi.add(ProgressBar::new(self.episodes));
                bar.set_style(
                    ProgressStyle::with_template("{prefix:<48} [{bar:25}] {pos}/{len} {msg}")
                        .expect("valid template")
                        .progress_chars("=> "),
                );
                bar.set_prefix(format!("{preset} · {method}"));
                self.running
                    .insert((preset.into(), method.into()), (bar, Instant::now()));
            }
            CompareEvent::Episode { preset, method } => {
                if let Some((bar, _)) = self.running.get(&(preset.into(), method.into())) {
                    bar.inc(1);
                }
            }
            CompareEvent::MethodDone {
                preset,
                method,
                success_rate,
            } => {
                let text = format!("{:.1} % success", 100.0 * success_rate);
                let Some((bar, started)) = self.running.remove(&(preset.into(), method.into()))
                else {
                    return;
                };
                bar.finish_with_message(text.clone());
                if !self.terminal && !self.quiet {
                    eprintln!(
                        "compare: {preset} · {method}: {} episodes, {text}, {:.1} s",
                        self.episodes,
                        started.elapsed().as_secs_f64()
                    );
                }
            }
            CompareEvent::Recording { episodes } => {
                if !self.quiet {
                    let _ = self.multi.println(format!(
                        "recording {episodes} episodes for the charts and replay.html"
                    ));
                    if !self.terminal {
                        eprintln!(
                            "compare: recording {episodes} episodes for the charts and replay.html"
                        );
                    }
                }
            }
        }
    }
}
