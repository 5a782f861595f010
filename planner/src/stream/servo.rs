//! The joint stream itself ([`ServoStream`]): samples at a fixed period and the gripper events
//! that go with them.

/// A gripper command that takes effect at a sample and holds until the next event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GripperEvent {
    /// Index of the sample at which it takes effect.
    pub sample: usize,
    /// The env's gripper command: −1 open … +1 closed (the fingers' target travel is
    /// `(command + 1)/2` of their 42.5 mm).
    pub command: f64,
}

/// A joint stream at a fixed period.
#[derive(Clone, Debug, PartialEq)]
pub struct ServoStream {
    /// Time between samples \[s\].
    pub period_sec: f64,
    /// The samples \[rad\], j1 … j6; the first is the start (reached by a blocking move), the
    /// last `hold_samples` repeat the final one.
    pub joints: Vec<[f64; 6]>,
    /// How many of the last samples repeat the final position.
    pub hold_samples: usize,
    /// Gripper events in sample order (empty: the stream carries no gripper commands).
    pub gripper: Vec<GripperEvent>,
}

impl ServoStream {
    /// The gripper command in effect at sample `n`, if the stream carries gripper events.
    pub fn gripper_at(&self, n: usize) -> Option<f64> {
        let first = self.gripper.first()?;
        let latest = self.gripper.iter().take_while(|e| e.sample <= n).last();
        Some(latest.unwrap_or(first).command)
    }

    /// The joints \[rad\] at time `t` \[s\] from the first sample: linear between samples (as a
    /// servo controller interpolates), the final sample after the end.
    pub fn joints_at(&self, t: f64) -> [f64; 6] {
        let last = self.joints.len().saturating_sub(1);
        let x = (t / self.period_sec).max(0.0);
        let n = (x.floor() as usize).min(last);
        if n >= last {
            return self.joints[last];
        }
        let f = x - n as f64;
        let (a, b) = (self.joints[n], self.joints[n + 1]);
        std::array::from_fn(|i| a[i] + f * (b[i] - a[i]))
    }

    /// Duration from the first to the last sample \[s\].
    pub fn duration_sec(&self) -> f64 {
        self.joints.len().saturating_sub(1) as f64 * self.period_sec
    }
}
