//! A method named on the command line resolves as every other name of a policy does: a script,
//! a shipped policy, a checkpoint folder or a run folder (its `checkpoints/best`); anything else
//! is refused with what it could have been.

use std::path::PathBuf;

use fairgrasp_evaluate::compare::methods::Method;
use fairgrasp_policy::shipped::ShippedPolicy;

#[test]
fn a_method_is_a_script_a_shipped_policy_a_checkpoint_or_a_run_folder() {
    assert!(matches!(
        Method::resolve("closed_loop").unwrap(),
        Method::Script(1)
    ));
    let shipped = Method::resolve("residual_nudged").unwrap();
    assert!(matches!(shipped, Method::Learned(_)));
    // A run folder: the shipped checkpoint copied to RUN/checkpoints/best.
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("methods-run-folder");
    let _ = std::fs::remove_dir_all(&root);
    let best = root.join("my_run/checkpoints/best");
    std::fs::create_dir_all(&best).unwrap();
    let source = ShippedPolicy::ResidualNudged.checkpoint_dir().unwrap();
    for f in ["meta.json", "model.bpk", "checksum"] {
        std::fs::copy(source.join(f), best.join(f)).unwrap();
    }
    let run = root.join("my_run");
    let Method::Learned(from_run) = Method::resolve(run.to_str().unwrap()).unwrap() else {
        panic!("a run folder is a learned policy");
    };
    assert_eq!(from_run.dir, best);
    let Method::Learned(from_checkpoint) = Method::resolve(best.to_str().unwrap()).unwrap() else {
        panic!("a checkpoint folder is a learned policy");
    };
    assert_eq!(from_checkpoint.meta, from_run.meta);
    // A folder that is neither is refused naming the scripts and the shipped policies.
    let e = match Method::resolve(root.to_str().unwrap()) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a folder without a checkpoint resolved"),
    };
    assert!(
        e.contains("not a script (open_loop, closed_loop, oracle, calibrated, tuned_grip)")
            && e.contains("residual_generalist")
            && e.contains("run folder"),
        "{e}"
    );
}

#[test]
fn on_a_place_preset_only_the_open_loop_script_is_a_script() {
    let place = fairgrasp_env::config::presets::load("place").unwrap();
    let lift = fairgrasp_env::config::presets::load("sector").unwrap();
    let closed = Method::resolve("closed_loop").unwrap();
    let e = closed.check_task(&place).unwrap_err().to_string();
    assert!(e.contains("closed_loop") && e.contains("open_loop"), "{e}");
    assert!(closed.check_task(&lift).is_ok());
    assert!(
        Method::resolve("open_loop")
            .unwrap()
            .check_task(&place)
            .is_ok()
    );
}
