//! Numbers on the command line: exponent forms with a sign parse, non-finite and absurd values
//! are refused naming the flag (they used to give `null` in JSON), and the reported wrist
//! singularity round-trips through `fk` and `ik`.

use std::process::Output;

mod common;
use common::fairgrasp;

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn a_negative_number_in_exponent_form_is_a_number_not_a_flag() {
    let out = fairgrasp(&[
        "fk", "--joints", "0", "-1e-12", "0", "0", "0", "0", "--json",
    ]);
    let v = json(&out);
    assert!(v["flange"]["xyz"][0].is_f64(), "{v}");
}

#[test]
fn non_finite_or_absurd_numbers_are_refused_naming_the_flag() {
    for args in [
        &["frames", "--point", "1e308", "0", "0", "--json"][..],
        &["frames", "--point", "nan", "0", "0", "--json"][..],
        &["fk", "--joints", "inf", "0", "0", "0", "0", "0"][..],
        &["ik", "--pose", "0.3", "0", "0.3", "0", "-1e400", "0"][..],
    ] {
        let out = fairgrasp(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("'{}", args[1])) && stderr.contains("finite"),
            "{args:?}: {stderr}"
        );
        assert!(out.stdout.is_empty(), "{args:?} printed a result");
    }
}

#[test]
fn ik_reaches_the_fk_pose_of_the_reported_wrist_singularity() {
    let fk = json(&fairgrasp(&[
        "fk", "--joints", "1", "-1", "0.3", "-1", "0", "1", "--json",
    ]));
    let xyz = &fk["flange"]["xyz"];
    let rpy = &fk["flange"]["rpy"];
    let pose: Vec<String> = (0..3)
        .map(|i| xyz[i].to_string())
        .chain((0..3).map(|i| rpy[i].to_string()))
        .collect();
    let mut args = vec!["ik", "--json", "--pose"];
    args.extend(pose.iter().map(String::as_str));
    let out = fairgrasp(&args);
    let v = json(&out);
    let text = v.to_string();
    assert!(!text.contains("out of reach"), "{text}");
    let solutions = v["solutions"].as_array().map_or(0, Vec::len);
    assert!(solutions >= 1, "{text}");
}

/// A negative number after a flag is a number, refused by the flag's range with a message naming
/// the flag and the range (it used to be "unexpected argument '-0' found"), and a count too large
/// to finish is refused where it is parsed (`compare --episodes 4294967295` used to run for hours,
/// `scene --seeds 18446744073709551615` never returned). The preset does not exist, so a command
/// that took the number fails on the preset, fast, with the wrong message.
#[test]
fn negative_numbers_and_endless_counts_are_refused_by_range_naming_the_flag() {
    for (args, range) in [
        (&["bench", "soak", "--noise", "-0.5"][..], "[0, 1]"),
        (
            &["baseline", "--script", "tuned_grip", "--grip-force", "-3"][..],
            "(0, 100]",
        ),
        (&["baseline", "--episodes", "-5"][..], "1..=1000000"),
        (&["compare", "--episodes", "4294967295"][..], "1..=1000000"),
        (
            &["scene", "--seeds", "18446744073709551615"][..],
            "0..=1000000",
        ),
        (&["scene", "--seed", "-1"][..], "0..=9007199254740991"),
    ] {
        let mut argv = args.to_vec();
        argv.extend(["--preset", "no_such_preset"]);
        let out = fairgrasp(&argv);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let flag = args.iter().rev().nth(1).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("'{flag} ")) && stderr.contains(range),
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn a_search_flag_out_of_range_is_refused_by_the_presets_rule_naming_the_setting() {
    for (flag, value, setting, rule) in [
        (
            "--search-force",
            "50",
            "task.place.search.contact_force",
            "[0.1, 30] N",
        ),
        (
            "--search-floor-band",
            "0.02",
            "task.place.search.floor_band",
            "wall_height",
        ),
        (
            "--search-max-radius",
            "0.2",
            "--search-max-radius",
            "[0.001, 0.05]",
        ),
    ] {
        let out = fairgrasp(&[
            "baseline",
            "--preset",
            "place",
            "--script",
            "force_search",
            "--episodes",
            "1",
            flag,
            value,
        ]);
        let err = common::stderr(&out);
        assert!(!out.status.success(), "{flag} {value} accepted");
        assert!(
            err.contains(&format!("{flag} {value}")) && err.contains(setting) && err.contains(rule),
            "{flag}: {err}"
        );
    }
}
