//! fairgrasp-report: turns run folders (`fairgrasp train`) and comparison folders
//! (`fairgrasp compare`) into PNG charts, GIF replays, `report.md` and a Jupyter notebook.
//!
//! It reads files only (CSV, JSON, TOML text) and of the fairgrasp crates depends only on the
//! result schema (`fairgrasp-types`), so the charts can be redrawn from a colleague's folders
//! without the simulator.
//!
//! - [`comparison_table`]: the comparison's data (`compare.json`), `compare.csv`, text and
//!   Markdown tables.
//! - [`runs`]: a training run folder and its `metrics.csv`.
//! - [`trajectory`]: a recorded episode (`episode_NNNN.json`).
//! - [`charts`]: success bars, learning curves, workspace maps, episode charts, GIF replays.
//! - [`replay3d`]: the interactive 3D replay, one self-contained `replay.html`.
//! - [`document`], [`notebook`]: the report as Markdown and as nbformat 4.5.
//! - [`report`]: all of it from a list of folders; [`comparison_folder`]: a comparison's folder
//!   (its data, episodes and report) written whole.
//! - [`output_folder`], [`folder_marker`]: the output folder, written whole or not at all, and
//!   never over files fairgrasp did not write.
//!
//! - [`raster`]: the RGB buffer charts are drawn in, encoded to PNG or GIF frames; [`error`]:
//!   the crate's one error type, naming the file.
//!
//! Text is drawn with the embedded DejaVu Sans ([`raster::register_fonts`]): no system font is
//! needed.

pub mod charts;
pub mod comparison_folder;
pub mod comparison_table;
pub mod document;
pub mod error;
pub mod folder_marker;
pub mod notebook;
pub mod output_folder;
pub mod raster;
pub mod replay3d;
pub mod report;
pub mod runs;
pub mod trajectory;

pub use comparison_table::{Comparison, EpisodeRecord, MethodResult, Outcome, RecordedEpisode};
pub use error::ReportError;
pub use output_folder::{Existing, StagedFolder};
pub use report::{Input, build_report, load_inputs, write_report};
pub use runs::RunFolder;
