//! The stack task (`task.kind = "stack"`): carry the cube onto a second cube standing on the
//! table, set it down squarely on its top, release it and clear the arm (the classic of
//! panda-gym's and ManiSkill's stacking tasks). Its rules are in [`rules`]; its settings
//! (`[task.stack]`, [`StackConfig`](settings::StackConfig)) and their checks in [`settings`].
//!
//! The second cube is the task's fixture: a fixed body (bolted to the table, as a part held in
//! a nest is; it does not slide or topple), drawn per scenario where `[task.stack]` says and seen
//! through the camera's errors (`observed_position_noise`); the facts a step is judged on are
//! the fixture's ([`PlaceFacts`](crate::task::state::PlaceFacts)).

pub mod rules;
pub mod settings;

pub use rules::{distance_to_go, is_stacked, is_success};
