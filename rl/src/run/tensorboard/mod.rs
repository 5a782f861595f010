//! TensorBoard event files, written natively by `fairgrasp train` in the run folder beside
//! `metrics.csv`: every column of every metrics row as a scalar at the row's timestep, and the
//! run's config as text. `tensorboard --logdir runs/` shows them.
//!
//! As TensorBoard's own writers do, each `train` invocation writes a new file
//! `events.out.tfevents.<unix seconds, 10 digits>.<host>` whose first event is the
//! `file_version` `brain.Event:2`. The values are the row's own cells, parsed from the text
//! `metrics.csv` holds, so both files say the same. A resumed run never writes a (tag, step)
//! pair an earlier file of the folder holds, and first writes the rows of `metrics.csv` that no
//! file holds yet (a kill between the row and its event): every row is in the events once.
//!
//! - [`proto`]: the protobuf messages (prost, declared by hand).
//! - [`records`]: the TFRecord framing with masked CRC-32C.

pub mod proto;
pub mod records;

use std::collections::HashSet;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use prost::Message;

use crate::run::error::{TrainError, io};
use crate::run::metrics::metrics_header;
use proto::{Event, PluginData, Summary, SummaryMetadata, TensorProto, TensorShapeProto, Value};

/// The tag of the run's config (text).
pub const CONFIG_TAG: &str = "config/config.toml";

/// The file version TensorBoard expects as the first event.
pub const FILE_VERSION: &str = "brain.Event:2";

/// The tag of a `metrics.csv` column: `<group>/<column>`, grouping the dashboard's cards.
pub fn tag_of(column: &str) -> String {
    let group = match column {
        "update" | "timesteps" | "wall_time_s" | "steps_per_second" => "progress",
        "episodes" | "episode_return" | "success_rate" | "episode_length" => "episodes",
        "stage" => "curriculum",
        "eval_success_rate" => "eval",
        c if c.starts_with("outcome_") => "outcomes",
        _ => "ppo",
    };
    format!("{group}/{column}")
}

/// The event files of a run folder, oldest first (their names sort by time).
pub fn event_files(run_dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(run_dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("events.out.tfevents."))
        })
        .collect();
    files.sort();
    files
}

/// Every event of a file, up to a torn tail.
pub fn read_events(path: &Path) -> Result<Vec<Event>, TrainError> {
    let bytes = fairgrasp_types::fs::read_bounded(path, fairgrasp_types::fs::MAX_DATA_BYTES)
        .map_err(io(path))?;
    records::read_records(&bytes)
        .into_iter()
        .map(|r| {
            Event::decode(r).map_err(|e| TrainError::Io {
                path: path.display().to_string(),
                source: std::io::Error::new(std::io::ErrorKind::InvalidData, e),
            })
        })
        .collect()
}

/// This machine's name for file names (letters, digits, `.`, `-`, `_`), else `localhost`.
fn host_name() -> String {
    let name = ["/proc/sys/kernel/hostname", "/etc/hostname"]
        .iter()
        .find_map(|p| std::fs::read_to_string(p).ok())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .unwrap_or_default();
    let clean: String = name
        .trim()
        .chars()
        .filter(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_'))
        .collect();
    if clean.is_empty() {
        "localhost".into()
    } else {
        clean
    }
}

fn now() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

/// The event file this invocation writes, and what the folder's files hold.
pub struct TensorBoardLog {
    path: PathBuf,
    out: BufWriter<std::fs::File>,
    /// (tag, step) pairs in this folder's event files, this one included.
    written: HashSet<(String, i64)>,
    columns: Vec<String>,
}

impl TensorBoardLog {
    /// Starts a new event file in `run_dir` (its `file_version` first), writes the rows of
    /// `metrics.csv` no earlier file holds, and the config text `config_toml` at `step` unless
    /// a file holds it there.
    pub fn open(run_dir: &Path, config_toml: &str, step: u64) -> Result<Self, TrainError> {
        let mut written = HashSet::new();
        for file in event_files(run_dir) {
            for event in read_events(&file)? {
                if let Some(proto::What::Summary(s)) = event.what {
                    written.extend(s.value.into_iter().map(|v| (v.tag, event.step)));
                }
            }
        }
        let stamp = now();
        let base = format!("events.out.tfevents.{:010}.{}", stamp as u64, host_name());
        let mut path = run_dir.join(&base);
        for n in 1.. {
            if !path.exists() {
                break;
            }
            path = run_dir.join(format!("{base}.{n}"));
        }
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .map_err(io(&path))?;
        let mut log = TensorBoardLog {
            out: BufWriter::new(file),
            written,
            columns: metrics_header().split(',').map(String::from).collect(),
            path,
        };
        log.write(Event {
            wall_time: stamp,
            step: 0,
            what: Some(proto::What::FileVersion(FILE_VERSION.into())),
        })?;
        let metrics = run_dir.join("metrics.csv");
        let text = std::fs::read_to_string(&metrics).unwrap_or_default();
        for row in text.lines().skip(1).filter(|l| !l.is_empty()) {
            log.write_row(row)?;
        }
        let step = i64::try_from(step).unwrap_or(i64::MAX);
        if log.written.insert((CONFIG_TAG.to_string(), step)) {
            log.write(Event {
                wall_time: now(),
                step,
                what: Some(proto::What::Summary(Summary {
                    value: vec![text_value(CONFIG_TAG, config_toml)],
                })),
            })?;
        }
        Ok(log)
    }

    /// The file this log writes.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes one `metrics.csv` row (its text) as scalars at its `timesteps`, leaving out empty
    /// cells and (tag, step) pairs the folder's files already hold.
    pub fn write_row(&mut self, row: &str) -> Result<(), TrainError> {
        let cells: Vec<&str> = row.split(',').collect();
        let cell = |name: &str| {
            self.columns
                .iter()
                .position(|c| c == name)
                .and_then(|i| cells.get(i))
                .and_then(|c| c.trim().parse::<f64>().ok())
        };
        let Some(step) = cell("timesteps") else {
            return Ok(());
        };
        let step = step as i64;
        let mut values = Vec::new();
        for (column, text) in self.columns.iter().zip(&cells) {
            let Ok(v) = text.trim().parse::<f64>() else {
                continue;
            };
            let tag = tag_of(column);
            if self.written.insert((tag.clone(), step)) {
                values.push(Value {
                    tag,
                    metadata: None,
                    value: Some(proto::ValueKind::SimpleValue(v as f32)),
                });
            }
        }
        if values.is_empty() {
            return Ok(());
        }
        self.write(Event {
            wall_time: now(),
            step,
            what: Some(proto::What::Summary(Summary { value: values })),
        })
    }

    fn write(&mut self, event: Event) -> Result<(), TrainError> {
        let path = self.path.clone();
        records::write_record(&mut self.out, &event.encode_to_vec()).map_err(io(&path))?;
        self.out.flush().map_err(io(&path))
    }
}

/// A text summary (TensorBoard's text dashboard renders Markdown: the TOML as a code block).
fn text_value(tag: &str, toml: &str) -> Value {
    let markdown = format!("```toml\n{toml}\n```");
    Value {
        tag: tag.to_string(),
        metadata: Some(SummaryMetadata {
            plugin_data: Some(PluginData {
                plugin_name: "text".into(),
                content: Vec::new(),
            }),
            data_class: proto::DATA_CLASS_TENSOR,
        }),
        value: Some(proto::ValueKind::Tensor(TensorProto {
            dtype: proto::DT_STRING,
            tensor_shape: Some(TensorShapeProto { dim: Vec::new() }),
            string_val: vec![markdown.into_bytes()],
        })),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("fairgrasp-tb-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&d).ok();
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn row(update: u64, timesteps: u64, eval: &str) -> String {
        let header = metrics_header();
        let n = header.split(',').count();
        let mut cells: Vec<String> = (0..n).map(|i| format!("{}.5", i)).collect();
        let col = |name: &str| header.split(',').position(|c| c == name).unwrap();
        cells[col("update")] = update.to_string();
        cells[col("timesteps")] = timesteps.to_string();
        cells[col("eval_success_rate")] = eval.into();
        cells.join(",")
    }

    fn scalars(dir: &Path) -> Vec<(String, i64, f32)> {
        let mut out = Vec::new();
        for f in event_files(dir) {
            for e in read_events(&f).unwrap() {
                if let Some(proto::What::Summary(s)) = e.what {
                    for v in s.value {
                        if let Some(proto::ValueKind::SimpleValue(x)) = v.value {
                            out.push((v.tag, e.step, x));
                        }
                    }
                }
            }
        }
        out
    }

    #[test]
    fn a_resume_writes_a_new_file_backfills_the_missing_row_and_repeats_no_step() {
        let dir = scratch("resume");
        let header = metrics_header();
        let (r1, r2) = (row(1, 64, ""), row(2, 128, "0.25"));
        std::fs::write(dir.join("metrics.csv"), format!("{header}\n{r1}\n")).unwrap();
        let mut first = TensorBoardLog::open(&dir, "seed = 1", 0).unwrap();
        // The first file: version first, then the row already in metrics.csv, then the config.
        let events = read_events(first.path()).unwrap();
        assert_eq!(
            events[0].what,
            Some(proto::What::FileVersion(FILE_VERSION.into()))
        );
        first.write_row(&r1).unwrap(); // nothing new: written at open
        let columns = header.split(',').count();
        assert_eq!(scalars(&dir).len(), columns - 1, "eval is empty in row 1");
        // A kill after row 2 reached metrics.csv but before its event: the resume writes it.
        std::fs::write(dir.join("metrics.csv"), format!("{header}\n{r1}\n{r2}\n")).unwrap();
        drop(first);
        std::thread::sleep(std::time::Duration::from_millis(5));
        let mut second = TensorBoardLog::open(&dir, "seed = 1", 128).unwrap();
        second.write_row(&row(3, 192, "")).unwrap();
        assert_eq!(event_files(&dir).len(), 2);
        let all = scalars(&dir);
        let mut keys: Vec<(String, i64)> = all.iter().map(|(t, s, _)| (t.clone(), *s)).collect();
        let n = keys.len();
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), n, "a (tag, step) pair was written twice");
        let steps: HashSet<i64> = all.iter().map(|(_, s, _)| *s).collect();
        assert_eq!(steps, HashSet::from([64, 128, 192]));
        let eval: Vec<_> = all
            .iter()
            .filter(|(t, ..)| t == "eval/eval_success_rate")
            .collect();
        assert_eq!(
            eval,
            vec![&("eval/eval_success_rate".to_string(), 128, 0.25)]
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn every_column_gets_a_grouped_tag_that_keeps_its_name() {
        let tags: HashSet<String> = metrics_header().split(',').map(tag_of).collect();
        assert_eq!(tags.len(), metrics_header().split(',').count());
        assert_eq!(tag_of("success_rate"), "episodes/success_rate");
        assert_eq!(tag_of("approx_kl"), "ppo/approx_kl");
        assert_eq!(tag_of("outcome_timeout"), "outcomes/outcome_timeout");
    }
}
