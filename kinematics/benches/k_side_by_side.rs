//! fairgrasp's URDF chains against the `k` crate's, time per FK and per FK + Jacobian on the
//! FR3 (to `tool0`) and the 7-joint arm, 256 seeded in-limit configurations in turn (their
//! agreement is the test `k_side_by_side`; the figures are in docs/kinematics.md).
//!
//! Run: `cargo bench -p fairgrasp-kinematics --bench k_side_by_side`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use fairgrasp_kinematics::urdf::urdf_rs;
use fairgrasp_kinematics::{FR3_URDF, SerialChain, UrdfRobot};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// fairgrasp's chain to `tip`, k's to the same link, and 256 in-limit configurations.
fn setup(text: &str, tip: Option<&str>) -> (SerialChain, k::SerialChain<f64>, Vec<Vec<f64>>) {
    let ours = UrdfRobot::from_str_named(text, "bench.urdf")
        .unwrap()
        .chain(tip)
        .unwrap();
    let tree = k::Chain::<f64>::from(&urdf_rs::read_from_string(text).unwrap());
    let theirs = k::SerialChain::from_end(tree.find_link(&ours.tip).unwrap());
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let configurations = (0..256)
        .map(|_| {
            ours.joints
                .iter()
                .filter(|j| j.kind.is_single_axis())
                .map(|j| {
                    let [lower, upper] = j.limits.unwrap_or([-3.0, 3.0]);
                    rng.random_range(lower..=upper)
                })
                .collect()
        })
        .collect();
    (ours, theirs, configurations)
}

fn side_by_side(c: &mut Criterion) {
    let seven = include_str!("../../assets/seven_joint_arm.urdf");
    for (arm, text, tip) in [("fr3", FR3_URDF, Some("tool0")), ("seven", seven, None)] {
        let (ours, theirs, qs) = setup(text, tip);
        let mut i = 0;
        let mut next = || {
            i = (i + 1) % qs.len();
            &qs[i]
        };
        c.bench_function(&format!("{arm}/fk/fairgrasp"), |b| {
            b.iter(|| black_box(ours.fk(black_box(next()))))
        });
        c.bench_function(&format!("{arm}/fk/k"), |b| {
            b.iter(|| {
                theirs.set_joint_positions_unchecked(black_box(next()));
                black_box(theirs.end_transform())
            })
        });
        c.bench_function(&format!("{arm}/fk_jacobian/fairgrasp"), |b| {
            b.iter(|| black_box(ours.fk_jacobian(black_box(next()))))
        });
        c.bench_function(&format!("{arm}/fk_jacobian/k"), |b| {
            b.iter(|| {
                theirs.set_joint_positions_unchecked(black_box(next()));
                // k::jacobian walks the chain for the tip's pose too, and does not return it.
                black_box(k::jacobian(&theirs))
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = side_by_side
}
criterion_main!(benches);
