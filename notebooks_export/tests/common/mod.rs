//! Synthetic comparison, run and episode folders for the report tests, and PNG/GIF readers.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use fairgrasp_report::comparison_table::{
    Comparison, EpisodeRecord, MethodResult, Outcome, RecordedEpisode, to_csv,
};
use fairgrasp_types::{ArmSimulation, EvalReport};

/// A fresh, empty folder under cargo's test temp dir.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("report-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A small deterministic generator (SplitMix64) for test data.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    }
}

/// A method's result with `successes` of `n` episodes, the rest split between two failures.
pub fn method_result(
    method: &str,
    preset: &str,
    n: usize,
    successes: usize,
    seed: u64,
) -> MethodResult {
    let mut rng = Rng::new(seed);
    let results: Vec<EpisodeRecord> = (0..n)
        .map(|i| {
            let angle = (rng.next_f64() - 0.5) * std::f64::consts::PI;
            let r = 0.25 + 0.1 * rng.next_f64();
            let outcome = if i < successes {
                Outcome::Success
            } else if i % 2 == 0 {
                Outcome::MissedGrasp
            } else {
                Outcome::Collision
            };
            EpisodeRecord {
                seed: i as u64,
                outcome,
                steps: 60 + i % 20,
                episode_return: if i < successes { 10.0 } else { -1.0 },
                object_xy: [r * angle.cos(), r * angle.sin()],
                collision_pair: None,
                cycle_time_s: None,
                takt_s: None,
                facts: Default::default(),
            }
            .normalized()
        })
        .collect();
    let mut outcomes = BTreeMap::new();
    for r in &results {
        *outcomes.entry(r.outcome).or_insert(0) += 1;
    }
    let rate = successes as f64 / n as f64;
    MethodResult {
        method: method.into(),
        preset: preset.into(),
        arm: ArmSimulation::Servo,
        seed: 0,
        policy: None,
        report: EvalReport {
            episodes: n,
            successes,
            success_rate: rate,
            ci_low: (rate - 0.08).max(0.0),
            ci_high: (rate + 0.05).min(1.0),
            collision_rate: outcomes.get(&Outcome::Collision).copied().unwrap_or(0) as f64
                / n as f64,
            mean_steps_to_success: (successes > 0).then_some(69.5),
            mean_return: results.iter().map(|r| r.episode_return).sum::<f64>() / n as f64,
            mean_cycle_time_s: None,
            takt_s: None,
            successes_within_takt: successes,
            within_takt_rate: rate,
            within_takt_ci_low: (rate - 0.08).max(0.0),
            within_takt_ci_high: (rate + 0.05).min(1.0),
            outcomes,
            results,
        },
    }
}

/// A recorded episode: an arm of three capsules sweeping over a cube, then lifting it.
pub fn trajectory_json(steps: usize) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = (0..steps)
        .map(|i| {
            let s = i as f64 / (steps - 1) as f64;
            let q = [0.8 * s, -1.0 + 0.5 * s, 1.2, -1.5, -1.57, 0.3 * s];
            let tcp = [0.3 * s.cos(), 0.3 * s.sin(), 0.3 - 0.25 * s.min(0.7) / 0.7];
            let lift = (s - 0.8).max(0.0);
            let object = [0.3 * 1f64.cos(), 0.3 * 1f64.sin(), 0.025 + lift];
            let elbow = [0.15 * s.cos(), 0.15 * s.sin(), 0.45];
            let capsules = vec![
                [0.0, 0.0, 0.0, 0.0, 0.0, 0.15, 0.06],
                [0.0, 0.0, 0.15, elbow[0], elbow[1], elbow[2], 0.05],
                [
                    elbow[0],
                    elbow[1],
                    elbow[2],
                    tcp[0],
                    tcp[1],
                    tcp[2] + 0.1,
                    0.04,
                ],
                [
                    tcp[0] - 0.03,
                    tcp[1],
                    tcp[2] + 0.05,
                    tcp[0] - 0.03,
                    tcp[1],
                    tcp[2],
                    0.01,
                ],
                [
                    tcp[0] + 0.03,
                    tcp[1],
                    tcp[2] + 0.05,
                    tcp[0] + 0.03,
                    tcp[1],
                    tcp[2],
                    0.01,
                ],
            ];
            serde_json::json!({
                "step": i, "time_s": 0.1 * i as f64, "joints": q,
                "gripper_opening_m": if s < 0.7 { 0.085 } else { 0.05 },
                "tcp_xyz": tcp, "tcp_quat_xyzw": [1.0, 0.0, 0.0, 0.0],
                "object_xyz": object, "object_quat_xyzw": [0.0, 0.0, 0.2, 0.98],
                "action": vec![0.0; 7], "reward": 0.0, "capsules": capsules,
            })
        })
        .collect();
    serde_json::json!({
        "scene": {
            "table_corners_xy": [[-0.6, -0.6], [0.6, -0.6], [0.6, 0.6], [-0.6, 0.6]],
            "table_top_z": 0.0, "cube_size": 0.05,
            "capsule_names": ["base_link", "upper_arm_link", "forearm_link", "finger_left", "finger_right"],
        },
        "rows": rows,
    })
}

/// Writes a comparison folder (compare.json, compare.csv, one recorded episode) into `dir`.
pub fn write_comparison(dir: &Path, run_folders: Vec<String>) -> Comparison {
    let presets = vec!["sector".to_string(), "hard".to_string()];
    let methods = vec![
        "scripted baseline".to_string(),
        "residual PPO: test".to_string(),
    ];
    let mut results = Vec::new();
    for (p, preset) in presets.iter().enumerate() {
        for (m, method) in methods.iter().enumerate() {
            let successes = 40 - 6 * p - 3 * m;
            results.push(method_result(
                method,
                preset,
                40,
                successes,
                (p * 10 + m) as u64,
            ));
        }
    }
    std::fs::create_dir_all(dir.join("episodes")).unwrap();
    std::fs::write(
        dir.join("episodes/baseline_hard_ep0.json"),
        serde_json::to_vec(&trajectory_json(30)).unwrap(),
    )
    .unwrap();
    let c = Comparison {
        command: "fairgrasp compare --episodes 40".into(),
        presets: presets.clone(),
        methods,
        preset_configs: presets
            .iter()
            .map(|p| (p.clone(), format!("[scene]\ncube_size = 0.05 # {p}\n")))
            .collect(),
        run_folders,
        recorded: vec![RecordedEpisode {
            method: "scripted baseline".into(),
            preset: "hard".into(),
            episode: 0,
            outcome: Outcome::Success,
            trajectory: "episodes/baseline_hard_ep0.json".into(),
        }],
        replay: vec![],
        tuning: vec![],
        results,
    };
    std::fs::write(dir.join("compare.json"), c.to_json()).unwrap();
    std::fs::write(dir.join("compare.csv"), to_csv(&c)).unwrap();
    c
}

/// Writes a training run folder with `updates` rows of plausible metrics and two stages.
pub fn write_run(dir: &Path, updates: usize, seed: u64) {
    std::fs::create_dir_all(dir).unwrap();
    let mut rng = Rng::new(seed);
    let mut csv = String::from(
        "update,timesteps,wall_time_s,episodes,episode_return,success_rate,episode_length,\
         policy_loss,value_loss,entropy,approx_kl,clip_fraction,explained_variance,\
         learning_rate,stage,eval_success_rate\n",
    );
    for u in 1..=updates {
        let s = u as f64 / updates as f64;
        let noise = rng.next_f64() - 0.5;
        let eval = if u % 10 == 0 {
            format!("{:.3}", s)
        } else {
            String::new()
        };
        csv += &format!(
            "{u},{},{:.2},20,{:.4},{:.4},80,{:.5},{:.5},{:.4},0.01,0.1,{:.3},3e-4,{},{eval}\n",
            u * 2048,
            0.8 * u as f64,
            10.0 * s + noise,
            (s + 0.1 * noise).clamp(0.0, 1.0),
            -0.03 + 0.01 * noise,
            1.0 / (1.0 + 5.0 * s) + 0.05 * noise,
            3.0 - 2.0 * s,
            0.5 + 0.4 * s,
            usize::from(s > 0.5),
        );
    }
    std::fs::write(dir.join("metrics.csv"), csv).unwrap();
    std::fs::write(
        dir.join("config.toml"),
        "seed = 0\ntotal_timesteps = 100000\n",
    )
    .unwrap();
}

/// A decoded PNG: width, height, RGB(A) bytes and channel count.
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub channels: usize,
    pub pixels: Vec<u8>,
}

impl Image {
    pub fn read_png(path: &Path) -> Self {
        let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
        let mut reader = decoder.read_info().unwrap();
        let mut pixels = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut pixels).unwrap();
        pixels.truncate(info.buffer_size());
        Self {
            width: info.width,
            height: info.height,
            channels: info.color_type.samples(),
            pixels,
        }
    }

    /// Luminance (0–255) of every pixel in rows `y0..y1`.
    pub fn luminance(&self, y0: u32, y1: u32) -> Vec<f64> {
        let row = self.width as usize * self.channels;
        self.pixels[y0 as usize * row..y1.min(self.height) as usize * row]
            .chunks_exact(self.channels)
            .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
            .collect()
    }

    /// Variance of the luminance over the whole image.
    pub fn variance(&self) -> f64 {
        let l = self.luminance(0, self.height);
        let mean = l.iter().sum::<f64>() / l.len() as f64;
        l.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / l.len() as f64
    }

    /// Dark pixels (luminance < 128) in rows `y0..y1`: text in a band that has no lines.
    pub fn dark_pixels(&self, y0: u32, y1: u32) -> usize {
        self.luminance(y0, y1)
            .iter()
            .filter(|l| **l < 128.0)
            .count()
    }
}
