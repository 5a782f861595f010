//! The burn-free actor (`fairgrasp-eval`) computes the shipped policies' mean actions as burn's
//! forward pass does, to 1e-5, on inputs across the normalised range.

use burn::tensor::{Device, Tensor, TensorData};
use fairgrasp_eval::actor::Actor;
use fairgrasp_eval::burnpack::read_tensors;
use fairgrasp_rl::run::checkpoint::load_model;
use fairgrasp_rl::run::shipped::ShippedPolicy;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[test]
fn every_shipped_policy_acts_the_same_without_burn_to_1e_5() {
    let device = Device::flex();
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for policy in ShippedPolicy::ALL {
        let dir = policy.checkpoint_dir().unwrap();
        let (meta, model) = load_model(&dir, &device).unwrap();
        let bytes = std::fs::read(dir.join("model.bpk")).unwrap();
        let mut sizes = vec![meta.input_dim];
        sizes.extend(&meta.model.hidden);
        sizes.push(meta.act_dim);
        let actor = Actor::from_tensors(&read_tensors(&bytes).unwrap(), &sizes).unwrap();
        let mut worst = 0.0f32;
        for _ in 0..200 {
            // Normalised inputs lie in ±10; most within ±3.
            let x: Vec<f32> = (0..meta.input_dim)
                .map(|_| rng.random_range(-3.0f32..3.0))
                .collect();
            let input = Tensor::<2>::from_data(TensorData::new(x.clone(), [1, x.len()]), &device);
            let burn: Vec<f32> = model.mean(input).into_data().try_to_vec().unwrap();
            let ours = actor.mean(&x);
            assert_eq!(burn.len(), ours.len());
            for (a, b) in burn.iter().zip(&ours) {
                worst = worst.max((a - b).abs());
            }
        }
        eprintln!("{}: largest difference {worst:e}", policy.name());
        assert!(worst <= 1e-5, "{}: {worst}", policy.name());
    }
}
