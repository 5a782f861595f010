//! Live progress on stderr (never on stdout): `train`'s one line every few updates, and
//! `compare`'s progress bar per preset × method (plain lines when stderr is not a terminal).

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use fairgrasp_rl::compare::CompareEvent;
use fairgrasp_rl::run::train::Progress;
use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Seconds between two of `train`'s progress lines (the first update and evaluations always
/// print).
const TRAIN_LINE_EVERY: Duration = Duration::from_secs(5);

/// `1h02m`, `4m05s`, `12s`.
pub fn duration_text(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "?".into();
    }
    let s = seconds.max(0.0).round() as u64;
    match (s / 3600, (s / 60) % 60, s % 60) {
        (0, 0, sec) => format!("{sec}s"),
        (0, m, sec) => format!("{m}m{sec:02}s"),
        (h, m, _) => format!("{h}h{m:02}m"),
    }
}

/// `train`'s progress: one line per call of [`TrainLines::line`] that is due.
pub struct TrainLines {
    last: Option<Instant>,
    /// Smoothed environment steps per second.
    speed: Option<f64>,
    updates: u64,
}

impl TrainLines {
    pub fn new() -> Self {
        TrainLines {
            last: None,
            speed: None,
            updates: 0,
        }
    }

    /// The line for this update if one is due: the first update, an evaluation, the last
    /// update, or [`TRAIN_LINE_EVERY`] since the previous line.
    pub fn line(&mut self, p: &Progress) -> Option<String> {
        self.updates += 1;
        let speed = match self.speed {
            Some(s) => 0.8 * s + 0.2 * p.steps_per_second,
            None => p.steps_per_second,
        };
        self.speed = Some(speed);
        let done = p.timesteps >= p.total;
        let due = self.last.is_none_or(|t| t.elapsed() >= TRAIN_LINE_EVERY);
        if !(due || done || p.eval.is_some()) {
            return None;
        }
        self.last = Some(Instant::now());
        let n = p.stats.episodes.len();
        let success = if n == 0 {
            "–".to_string()
        } else {
            let s = p.stats.episodes.iter().filter(|e| e.success).count();
            format!("{:.0}%", 100.0 * s as f64 / n as f64)
        };
        let eval = p
            .eval
            .map_or(String::new(), |e| format!(" · eval {:.0}%", 100.0 * e));
        let left = p.total.saturating_sub(p.timesteps) as f64 / speed.max(1e-9);
        Some(format!(
            "train: {}/{} steps ({:.0}%) · stage {} · success {success} ({n} episodes){eval} · {:.0} steps/s · {} left",
            p.timesteps,
            p.total,
            100.0 * p.timesteps as f64 / p.total.max(1) as f64,
            p.stage,
            speed,
            duration_text(left),
        ))
    }
}

/// `compare`'s progress: a bar per preset × method in a terminal, else a line per finished
/// preset × method; nothing with `quiet`.
pub struct CompareBars {
    multi: MultiProgress,
    current: Option<ProgressBar>,
    episodes: u64,
    terminal: bool,
    quiet: bool,
    started: Instant,
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
            current: None,
            episodes,
            terminal,
            quiet,
            started: Instant::now(),
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
                self.current = Some(bar);
                self.started = Instant::now();
            }
            CompareEvent::Episode => {
                if let Some(bar) = &self.current {
                    bar.inc(1);
                }
            }
            CompareEvent::MethodDone {
                preset,
                method,
                success_rate,
            } => {
                let text = format!("{:.1} % success", 100.0 * success_rate);
                if let Some(bar) = self.current.take() {
                    bar.finish_with_message(text.clone());
                }
                if !self.terminal && !self.quiet {
                    eprintln!(
                        "compare: {preset} · {method}: {} episodes, {text}, {:.1} s",
                        self.episodes,
                        self.started.elapsed().as_secs_f64()
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
