//! A joint stream for a real FR3 controller: an episode's joints resampled to the controller's
//! servo period with Ruckig ([`mod@resample`]), checked against the FR3's limits before anything is
//! written ([`check`]), encoded as JSON, CSV or NumPy `.npy` ([`mod@file`]), and played back in the
//! env ([`playback`]) so that what leaves the simulator is what was evaluated.
//!
//! Joints are in FAIRINO's order j1 … j6, radians in memory, degrees in files. The stream starts
//! where the arm must be brought first (a blocking `MoveJ` on a real arm), then runs one sample
//! per period (`ServoJ`), then repeats its final sample `hold_samples` times so that the arm
//! settles before the servo mode ends.
//!
//! - [`servo`]: the stream ([`ServoStream`]); [`limits`]: what it must respect ([`StreamLimits`]).

pub mod check;
pub mod file;
pub mod limits;
pub mod playback;
pub mod resample;
pub mod servo;

pub use check::{Quantity, StreamViolation, check_stream};
pub use limits::{
    DEFAULT_PERIOD_SEC, MAX_ACCELERATION, MAX_STEP_DEG, PERIOD_RANGE_SEC, StreamLimits,
};
pub use playback::{PlaybackError, PlaybackReport, play};
pub use resample::{EpisodeJoints, Resampled, resample};
pub use servo::{GripperEvent, ServoStream};
