//! Where the planner registers each task: the residual interface a task-space residual policy
//! corrects on a preset of that task. A task's hand-written controls are its rows of
//! [`crate::controls::CONTROLS`], in its folder (`planner/src/lift/controls.rs`, …).

use fairgrasp_env::{EnvConfig, TaskKind};

use crate::task_residual::TaskResidual;
use crate::{PlaceResidual, ResidualScript};

/// The residual interface of `env`'s task: the lift script (with the squeeze if `squeeze`), or
/// the place task's force-guided search, the stack task's force lower (neither has a squeeze;
/// `squeeze` is ignored there).
pub fn task_residual(env: &EnvConfig, squeeze: bool) -> Box<dyn TaskResidual> {
    match env.task.kind {
        TaskKind::Lift => {
            let r = ResidualScript::new(env);
            Box::new(if squeeze { r.squeezing(env) } else { r })
        }
        TaskKind::Place => Box::new(PlaceResidual::new(env)),
        TaskKind::Stack => Box::new(crate::stack::residual(env)),
    }
}
