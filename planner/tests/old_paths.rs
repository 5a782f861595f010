//! The planner's module paths from before its folder per task (`baseline`, `place_search`,
//! `residual`, `place_residual`, …) still name the same items, for one release: a user's
//! `use fairgrasp_planner::place_search::DROP_HEIGHT` keeps compiling, and names the type the
//! task's folder defines, not a copy of it.

use std::any::TypeId;

use fairgrasp_planner as planner;

/// Whether `A` and `B` are one type.
fn same<A: 'static, B: 'static>() -> bool {
    TypeId::of::<A>() == TypeId::of::<B>()
}

#[test]
fn the_lift_modules_old_paths_name_the_lift_folders_types() {
    assert!(same::<
        planner::baseline::ScriptedGrasp,
        planner::lift::script::ScriptedGrasp,
    >());
    assert!(same::<planner::baseline::Phase, planner::phase::Phase>());
    assert!(same::<
        planner::closed_loop::ClosedLoopGrasp,
        planner::lift::closed_loop::ClosedLoopGrasp,
    >());
    assert!(same::<
        planner::calibrated::CalibratedScript,
        planner::lift::calibrated::CalibratedScript,
    >());
    assert!(same::<
        planner::tuned_grip::TunedGripScript,
        planner::lift::tuned_grip::TunedGripScript,
    >());
    assert!(same::<
        planner::residual::ResidualScript,
        planner::lift::residual::ResidualScript,
    >());
    assert_eq!(
        planner::calibrated::TOUCH_ERROR,
        planner::lift::calibrated::TOUCH_ERROR
    );
    assert_eq!(
        planner::residual::FEATURE_DIM,
        planner::task_residual::FEATURE_DIM
    );
}

#[test]
fn the_place_modules_old_paths_name_the_place_folders_types() {
    assert!(same::<
        planner::place::ScriptedPlace,
        planner::place::script::ScriptedPlace,
    >());
    assert!(same::<
        planner::place::PlacePhase,
        planner::place::script::PlacePhase,
    >());
    assert!(same::<
        planner::place_search::ForceSearch,
        planner::place::search::ForceSearch,
    >());
    assert!(same::<
        planner::place_square::Squaring,
        planner::place::square::Squaring,
    >());
    assert!(same::<
        planner::place_residual::PlaceResidual,
        planner::place::residual::PlaceResidual,
    >());
    assert!(same::<
        planner::oracle_switch::OracleSwitch,
        planner::place::oracle_switch::OracleSwitch,
    >());
    assert_eq!(
        planner::place_search::DROP_HEIGHT,
        planner::place::search::DROP_HEIGHT
    );
    assert_eq!(
        planner::place::DROP_HEIGHT,
        planner::place::search::DROP_HEIGHT
    );
    let old: Vec<&str> = planner::controls::SEARCH.iter().map(|p| p.name).collect();
    let new: Vec<&str> = planner::place::search_params::SEARCH
        .iter()
        .map(|p| p.name)
        .collect();
    assert_eq!(old, new);
}
