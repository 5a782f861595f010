//! The environment's scene diagnostics as library calls.

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets;
use fairgrasp_env::env::diagnostics::{ContactVerdict, capsule_overlaps, diagnose_scene};
use fairgrasp_kinematics::ArmKind;

#[test]
fn the_seed_preset_starts_clean_with_the_cube_resting_on_the_table() {
    let config = presets::load("sector").unwrap();
    let d = diagnose_scene(&config, 3, 8).unwrap();
    assert!(!d.start_is_bad(), "{d:?}");
    assert!(d.refused.is_none() && d.bad_starts.is_empty(), "{d:?}");
    assert_eq!(d.seeds_checked, 8);
    assert!(d.object_pushed_m < 1e-3, "{d:?}");
    assert!(
        d.contacts
            .iter()
            .any(|c| c.verdict == ContactVerdict::RestingContact
                && [c.a.as_str(), c.b.as_str()].contains(&"cube")),
        "{d:?}"
    );
    assert!(d.contacts.iter().all(|c| !c.verdict.is_bad()), "{d:?}");
    // Neighbouring capsules overlap at home, and every such pair is one the model ignores.
    assert!(!d.capsule_overlaps_at_home.is_empty());
    assert!(
        d.capsule_overlaps_at_home
            .iter()
            .all(|o| o.ignored && o.overlap_m > 0.0)
    );
}

#[test]
fn a_cube_spawned_inside_the_base_is_refused_and_every_seed_starts_broken() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/configs/pitfall1_spawn_touching.toml"
    );
    let config = EnvConfig::from_toml_file(path).unwrap();
    let d = diagnose_scene(&config, 0, 3).unwrap();
    assert!(d.start_is_bad());
    assert!(
        d.refused.as_deref().unwrap_or("").contains("cube_xy"),
        "{d:?}"
    );
    assert!(d.object_pushed_m > 0.01, "{d:?}");
    assert!(
        d.contacts
            .iter()
            .any(|c| c.verdict == ContactVerdict::ObjectTouchesRobot),
        "{d:?}"
    );
    assert_eq!(d.bad_starts, vec![0, 1, 2], "the cube is not randomised");
}

#[test]
fn counted_capsule_overlaps_are_the_kinematics_self_collisions() {
    let model = ArmKind::Fr3.model();
    // A deterministic sweep over the joint ranges, some configurations self-colliding.
    let mut found = 0;
    for k in 0..400 {
        let t = k as f64 * 0.61803;
        let q = std::array::from_fn(|i| ((t * (i as f64 + 1.3)).sin()) * 2.6);
        let hits = model.self_collisions(&q, 0.0);
        let overlaps = capsule_overlaps(&model, &q);
        let counted: Vec<_> = overlaps.iter().filter(|o| !o.ignored).collect();
        assert_eq!(counted.len(), hits.len(), "q {q:?}");
        for (o, (a, b, clearance)) in counted.iter().zip(&hits) {
            assert_eq!((o.a, o.b, o.overlap_m), (*a, *b, -clearance));
        }
        assert!(
            overlaps
                .iter()
                .filter(|o| o.ignored)
                .all(|o| model.collision_ignored(o.a, o.b))
        );
        found += usize::from(!hits.is_empty());
    }
    assert!(
        found > 0,
        "no self-colliding configuration among the 400 tried"
    );
}
