//! Carrying out a scenario's turn of the cube in the grip (`task.place.grip_tilt`, drawn per
//! scenario in [`crate::scenario::fixture::FixturePose::grip_tilt`]): once, before the first env
//! step that finds both pads on the cube and its bottom [`GRIP_TILT_LIFT`] above the table. The
//! cube turns about the TCP's x (the axis between the pads) through the TCP, so the faces the
//! pads hold stay in the pads' planes: the grip is kept, the cube hangs tilted in it.

use nalgebra::Vector3;
use serde::Serialize;

use crate::scenario::Scenario;
use crate::scenario::grip_tilt::settings::GRIP_TILT_LIFT;
use crate::sim::Sim;

/// What became of this episode's turn in the grip.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GripTiltEvent {
    /// Before the action of env step `step` (0-based).
    pub step: usize,
    /// By this angle about the TCP's x \[rad\].
    pub angle: f64,
}

/// The per-episode state of the turn.
#[derive(Clone, Debug, Default)]
pub struct GripTiltHook {
    event: Option<GripTiltEvent>,
}

/// Where the hand and the cube are before a step, in `world` \[m\].
pub struct HandState {
    /// The TCP's position and its x axis (the fingers' closing axis, a unit vector).
    pub tcp: [f64; 3],
    pub tcp_x: [f64; 3],
    /// Both pads touch the cube.
    pub held: bool,
    /// The cube's lowest point above the table top \[m\].
    pub cube_bottom_above_table: f64,
}

impl GripTiltHook {
    /// Forgets the previous episode's turn.
    pub fn reset(&mut self) {
        self.event = None;
    }

    /// This episode's turn, once it has happened.
    pub fn event(&self) -> Option<GripTiltEvent> {
        self.event
    }

    /// Before env step `step`'s action: turns the cube in the grip if the scenario draws a turn,
    /// it has not happened yet, and the cube is held clear of the table.
    pub fn before_step(
        &mut self,
        step: usize,
        scenario: Option<&Scenario>,
        hand: &HandState,
        sim: &mut Sim,
    ) {
        let angle = scenario
            .and_then(|s| s.fixture)
            .map_or(0.0, |f| f.grip_tilt);
        let due = hand.held && hand.cube_bottom_above_table >= GRIP_TILT_LIFT;
        if angle == 0.0 || self.event.is_some() || !due {
            return;
        }
        let axis = Vector3::from(hand.tcp_x).normalize();
        sim.turn_object_about(hand.tcp, axis.into(), angle);
        self.event = Some(GripTiltEvent { step, angle });
    }
}
