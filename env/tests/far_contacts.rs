//! The palm's and the finger struts' far speculative contacts never reach rapier's solver
//! (`sim::world::FAR_CONTACT`), while the pads keep rapier's full prediction margin.

mod common;

use fairgrasp_env::sim::scene::Part;
use fairgrasp_env::sim::world::FAR_CONTACT;
use fairgrasp_env::{ArmSimulation, TaskEnv};

/// The signed distances \[m\] of every solver contact of the narrow phase now, with the pair's
/// parts.
fn solver_contacts(env: &mut TaskEnv) -> Vec<(Part, Part, f32)> {
    let (world, handles) = env.world_mut();
    let mut out = Vec::new();
    for pair in world.narrow_phase.contact_pairs() {
        let (Some(a), Some(b)) = (
            handles.parts.get(&pair.collider1),
            handles.parts.get(&pair.collider2),
        ) else {
            continue;
        };
        for m in pair.manifolds() {
            out.extend(m.data.solver_contacts.iter().map(|c| (a, b, c.dist)));
        }
    }
    out
}

#[test]
fn palm_and_struts_reach_the_solver_only_within_5_mm_and_the_pads_from_farther() {
    for arm in [ArmSimulation::Servo, ArmSimulation::Multibody] {
        let mut config = common::config(arm);
        config.physics.free_space = false;
        let mut env = TaskEnv::new(config).unwrap();
        env.reset(5).unwrap();
        let (grasp, above) = common::grasp_targets(&env);
        let (mut far_pad, mut near_palm_or_strut) = (false, 0);
        for (target, grip, n) in [(above, -1.0, 40), (grasp, -1.0, 30), (grasp, 1.0, 12)] {
            for _ in 0..n {
                let action = common::toward(&env, target, grip);
                env.step(&action).unwrap();
                for (a, b, dist) in solver_contacts(&mut env) {
                    let hooked = |p: Part| matches!(p, Part::Palm | Part::Finger(_));
                    if hooked(a) || hooked(b) {
                        assert!(dist < FAR_CONTACT, "{arm:?}: {a:?}-{b:?} at {dist} m");
                        near_palm_or_strut += 1;
                    }
                    far_pad |= matches!((a, b), (Part::Pad(_), _) | (_, Part::Pad(_)))
                        && dist >= FAR_CONTACT;
                }
            }
        }
        assert!(far_pad, "{arm:?}: no pad contact beyond {FAR_CONTACT} m");
        eprintln!("{arm:?}: {near_palm_or_strut} palm or strut solver contacts within 5 mm");
    }
}
