//! The place task (`task.kind = "place"`): carry the cube into the fixture's pocket, seat it,
//! release it and clear the arm. Its rules are in [`rules`]; its settings (`[task.place]`,
//! [`PlaceConfig`](settings::PlaceConfig)) and their checks in [`settings`]; the facts it is judged on are
//! [`PlaceFacts`], measured by the env from the simulation.

pub mod rules;
pub mod settings;

pub use crate::task::state::PlaceFacts;
pub use rules::{distance_to_go, is_clear, is_placed, is_seated};
