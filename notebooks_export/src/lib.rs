//! fairgrasp-report: turns run folders (`fairgrasp train`) and comparison folders
//! (`fairgrasp compare`) into PNG charts, GIF replays, `report.md` and a Jupyter notebook.
//!
//! It reads files only (CSV, JSON, TOML text) and of the fairgrasp crates depends only on the
//! result schema (`fairgrasp-types`), so the charts can be redrawn from a colleague's folders
//! without the simulator.
//!
//! - [`compare`]: the comparison's data (`compare.json`), `compare.csv`, text and Markdown tables.
//! - [`runs`]: a training run folder and its `metrics.csv`.
//! - [`trajectory`]: a recorded episode (`episode_NNNN.json`).
//! - [`charts`]: success bars, learning curves, workspace maps, episode charts, GIF replays.
//! - [`document`], [`notebook`]: the report as Markdown and as nbformat 4.5.
//! - [`report`]: all of it from a list of folders.
//!
//! Text is drawn with the embedded DejaVu Sans ([`raster::register_fonts`]): no system font is
//! needed.

pub mod charts;
pub mod compare;
pub mod document;
pub mod error;
pub mod notebook;
pub mod raster;
pub mod report;
pub mod runs;
pub mod trajectory;

pub use compare::{Comparison, EpisodeResult, MethodResult, Outcome, RecordedEpisode};
pub use error::ReportError;
pub use report::{Input, build_report};
pub use runs::RunFolder;
