//! Carrying out a scenario's push of the cube ([`crate::scenario::nudge::Nudge`]): once, before the
//! action of the drawn env step, and only if the TCP is far enough from the cube before and
//! after the push. The cube is moved across the table (height and yaw kept) and left at rest;
//! the env reads the cube's pose from the simulator every step, so nothing holds a stale pose.

use nalgebra::{Isometry3, Translation3};
use serde::Serialize;

use crate::cell::mount::Mount;
use crate::scenario::Scenario;
use crate::sim::Sim;

/// What became of this episode's push.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum NudgeEvent {
    /// The cube was pushed before the action of env step `step` (0-based), from `from` to `to`
    /// (cube centre in `world` \[m\]), with the TCP `tcp_distance` \[m\] from the cube centre (the
    /// nearer of before and after).
    Pushed {
        step: usize,
        from: [f64; 3],
        to: [f64; 3],
        tcp_distance: f64,
    },
    /// The TCP was nearer than `min_tcp_distance` at the drawn step: no push this episode.
    Skipped { step: usize, tcp_distance: f64 },
}

/// The per-episode state of the push.
#[derive(Clone, Debug, Default)]
pub struct NudgeHook {
    event: Option<NudgeEvent>,
}

impl NudgeHook {
    /// Forgets the previous episode's push.
    pub fn reset(&mut self) {
        self.event = None;
    }

    /// What happened to this episode's push so far.
    pub fn event(&self) -> Option<NudgeEvent> {
        self.event
    }

    /// Before env step `step`'s action: pushes the cube if the scenario draws a push for this
    /// step. `tcp` is the TCP position in `world` \[m\].
    pub fn before_step(
        &mut self,
        step: usize,
        scenario: Option<&Scenario>,
        mount: &Mount,
        sim: &mut Sim,
        tcp: [f64; 3],
    ) {
        let Some(s) = scenario else { return };
        let Some(nudge) = s.nudge else { return };
        if self.event.is_some() || step != nudge.step {
            return;
        }
        let from = sim.object_pose();
        // The push is drawn in the table frame, whose z is the world's: turn it into the world.
        let d =
            mount
                .table_in_world
                .transform_vector([nudge.offset_xy[0], nudge.offset_xy[1], 0.0]);
        let to = Translation3::new(d[0], d[1], 0.0) * from;
        let distance = |p: &Isometry3<f64>| {
            let c = p.translation.vector;
            ((c.x - tcp[0]).powi(2) + (c.y - tcp[1]).powi(2) + (c.z - tcp[2]).powi(2)).sqrt()
        };
        let tcp_distance = distance(&from).min(distance(&to));
        let [a, b] = [from, to].map(|p| {
            let c = p.translation.vector;
            [c.x, c.y, c.z]
        });
        self.event = Some(if tcp_distance >= nudge.min_tcp_distance {
            sim.place_object(&to, s.friction, s.mass);
            NudgeEvent::Pushed {
                step,
                from: a,
                to: b,
                tcp_distance,
            }
        } else {
            NudgeEvent::Skipped { step, tcp_distance }
        });
    }
}
