//! Random damage to the shipped URDFs never panics: every result is a robot or a named error,
//! and every fault of one element (found by the pre-check or by urdf-rs) names its line.

mod common;

use std::panic::{AssertUnwindSafe, catch_unwind};

use fairgrasp_kinematics::{FR3_URDF, FR5_URDF, UrdfError, UrdfRobot};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// What a number in the file is replaced with.
const BAD_NUMBERS: [&str; 12] = [
    "inf", "-inf", "nan", "NaN", "1e400", "-1e999", "1e308", "-1e308", "1e-320", "", "0x10", "1,5",
];
/// Fragments inserted at random places.
const FRAGMENTS: [&str; 10] = [
    "<",
    ">",
    "\"",
    "/>",
    "</joint>",
    "<joint name=\"j1\" type=\"revolute\">",
    "<limit/>",
    "<link name=\"tcp\"/>",
    "&amp;",
    "\u{fffd}",
];

/// The byte offset of a random character boundary in `text`, or `text.len()`.
fn char_boundary(text: &str, rng: &mut ChaCha8Rng) -> usize {
    let mut at = rng.random_range(0..=text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The byte ranges of the numbers in `text` (runs of digits, signs, dots and exponents).
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() {
            let mut start = i;
            while start > 0 && matches!(bytes[start - 1], b'-' | b'.') {
                start -= 1;
            }
            let mut end = i;
            while end < bytes.len() && matches!(bytes[end], b'0'..=b'9' | b'.' | b'e' | b'-') {
                end += 1;
            }
            spans.push((start, end));
            i = end;
        } else {
            i += 1;
        }
    }
    spans
}

/// One random mutation of `text`, and what it was (for the failure message).
fn mutate(text: &str, rng: &mut ChaCha8Rng) -> (String, String) {
    let at = char_boundary(text, rng);
    let next = text[at..].chars().next().map_or(0, char::len_utf8);
    match rng.random_range(0..5) {
        0 => (text[..at].to_string(), format!("truncated at byte {at}")),
        1 => (
            format!("{}{}", &text[..at], &text[at + next..]),
            format!("deleted the character at byte {at}"),
        ),
        2 => (
            format!("{}{}", &text[..at + next], &text[at..]),
            format!("duplicated the character at byte {at}"),
        ),
        3 if !number_spans(text).is_empty() => {
            let spans = number_spans(text);
            let (start, end) = spans[rng.random_range(0..spans.len())];
            let bad = BAD_NUMBERS[rng.random_range(0..BAD_NUMBERS.len())];
            (
                format!("{}{bad}{}", &text[..start], &text[end..]),
                format!(
                    "replaced {:?} at byte {start} with {bad:?}",
                    &text[start..end]
                ),
            )
        }
        _ => {
            let fragment = FRAGMENTS[rng.random_range(0..FRAGMENTS.len())];
            (
                format!("{}{fragment}{}", &text[..at], &text[at..]),
                format!("inserted {fragment:?} at byte {at}"),
            )
        }
    }
}

/// Does the refusal of a text name its line? All do but the tree's and the size's faults, which
/// concern several elements or none (and name the joints or links).
fn names_its_line(error: &UrdfError) -> bool {
    let message = error.to_string();
    let tree_or_size = matches!(
        error,
        UrdfError::MissingLink { .. }
            | UrdfError::NotATree { .. }
            | UrdfError::BadJoint { .. }
            | UrdfError::TooLarge { .. }
    );
    let after_line = message
        .split_once(": line ")
        .and_then(|(_, rest)| rest.split_once(": "));
    tree_or_size || after_line.is_some_and(|(n, _)| n.parse::<usize>().is_ok())
}

/// Loads `text`, and when it loads, every chain and its FK at zero: the error messages.
fn load_everything(text: &str) -> Vec<String> {
    let robot = match UrdfRobot::from_str_named(text, "mutated.urdf") {
        Ok(robot) => robot,
        Err(e) => {
            assert!(names_its_line(&e), "no line named: {e}");
            return vec![e.to_string()];
        }
    };
    let mut errors = Vec::new();
    let tips: Vec<Option<&str>> = std::iter::once(None)
        .chain(robot.links.iter().map(|l| Some(l.as_str())))
        .collect();
    for tip in tips {
        match robot.chain(tip) {
            Ok(chain) => {
                let _ = chain.fk(&vec![0.0; chain.dof()]);
                let _ = chain.joint_names();
            }
            Err(e) => errors.push(e.to_string()),
        }
    }
    errors
}

#[test]
fn random_mutations_of_the_shipped_urdfs_never_panic_and_every_error_has_a_message() {
    let mut rng = common::rng(15);
    let (mut refused, mut loaded) = (0, 0);
    for n in 0..600 {
        let original = if n % 4 == 3 { FR5_URDF } else { FR3_URDF };
        let mut text = original.to_string();
        let mut what = Vec::new();
        for _ in 0..rng.random_range(1..=3) {
            let (mutated, description) = mutate(&text, &mut rng);
            text = mutated;
            what.push(description);
        }
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            (
                UrdfRobot::from_str_named(&text, "mutated.urdf").is_ok(),
                load_everything(&text),
            )
        }));
        let Ok((is_ok, errors)) = outcome else {
            panic!("mutation {n} panicked: {}", what.join("; "));
        };
        for message in &errors {
            assert!(
                !message.trim().is_empty(),
                "mutation {n} ({}): empty error",
                what.join("; ")
            );
        }
        if is_ok {
            loaded += 1;
        } else {
            refused += 1;
        }
    }
    eprintln!("{refused} mutations refused, {loaded} loaded");
    // The mutations do damage: most are refused, and some (e.g. a changed digit) still load.
    assert!(
        refused > 100 && loaded > 10,
        "{refused} refused, {loaded} loaded"
    );
}
