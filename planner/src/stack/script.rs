//! The stack task's controls: the place script set down on the second cube's top instead of in
//! a pocket ([`ScriptedPlace::onto`]): grasp, carry above the second cube as the camera sees it,
//! lower, release, retreat ([`open_loop`]); and the same lowering until the wrist feels the cube
//! touch the second cube's top, then releasing there ([`force_lower`], the force search's
//! descent without its spiral: [`FORCE_LOWER`]). [`residual`] is what a residual policy corrects
//! on a stack preset: the force lower, through the place task's interface.

use fairgrasp_env::EnvConfig;

use crate::place::residual::PlaceResidual;
use crate::{ScriptedPlace, SearchParams};

/// The force lower: the search's descent (at the search's default 1 cm/s) until the wrist feels
/// its default 1.5 N up, then the release. A floor band of 1 m counts every touch as the floor's
/// (there is no rim), so the search never spirals; without a touch it stops where the open-loop
/// lower would. The spiral's settings stay the defaults: unused, its radius is only the unit of
/// a residual's spiral features.
pub const FORCE_LOWER: SearchParams = SearchParams {
    floor_band: Some(1.0),
    ..SearchParams::DEFAULT
};

/// The open-loop stack script for `env` (its `[task.stack]`): the cube set down a cube's edge
/// above the table, on the second cube where the camera sees it.
pub fn open_loop(env: &EnvConfig) -> ScriptedPlace {
    ScriptedPlace::onto(env, env.scene.cube_size, env.task.stack.grasp_height, 0.0)
}

/// The stack script that lowers until the wrist feels the second cube ([`FORCE_LOWER`]).
pub fn force_lower(env: &EnvConfig) -> ScriptedPlace {
    open_loop(env).searching(FORCE_LOWER)
}

/// The unit of the residual's depth features \[m\] (the place task's are in wall heights, and
/// the second cube has no walls): 10 mm, the place task's default wall.
pub const DEPTH_FEATURE_UNIT: f64 = 0.01;

/// The residual interface on a stack preset: the force lower, corrected and scaled as the place
/// residual corrects the search, on the stack cell's takt.
pub fn residual(env: &EnvConfig) -> PlaceResidual {
    let takt = env.task.stack.takt;
    PlaceResidual::over(env, force_lower(env), FORCE_LOWER, DEPTH_FEATURE_UNIT, takt)
}
