//! A running comparison's progress, for progress bars ([`CompareEvent`]).

/// Progress of a running comparison, for progress bars.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CompareEvent<'a> {
    /// A method starts on a preset's scenario set.
    Method { preset: &'a str, method: &'a str },
    /// One more episode of this preset and method is done (episodes of two methods may
    /// finish interleaved: the workers share one queue).
    Episode { preset: &'a str, method: &'a str },
    /// A method has finished a preset's scenario set with this success rate.
    MethodDone {
        preset: &'a str,
        method: &'a str,
        success_rate: f64,
    },
    /// The evaluations are done; this many episodes are being recorded for the charts and
    /// the replay.
    Recording { episodes: usize },
}
