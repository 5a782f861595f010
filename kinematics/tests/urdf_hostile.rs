//! URDF text a user may type or generate: deep nesting, huge files, duplicate names, a joint
//! without limits, non-finite numbers. Each is refused with a message naming it, never a crash
//! or a hang.

use fairgrasp_kinematics::urdf::{MAX_NESTING_DEPTH, MAX_URDF_BYTES};
use fairgrasp_kinematics::{UrdfError, UrdfRobot};

const TWO_JOINTS: &str = r#"<?xml version="1.0"?>
<robot name="tiny">
  <link name="base_link"/>
  <link name="arm"/>
  <link name="hand"/>
  <joint name="j1" type="revolute">
    <parent link="base_link"/>
    <child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="prismatic">
    <parent link="arm"/>
    <child link="hand"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
    <axis xyz="1 0 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/>
  </joint>
</robot>
"#;

fn load(text: &str) -> Result<UrdfRobot, UrdfError> {
    UrdfRobot::from_str_named(text, "user.urdf")
}

/// A chain `l0 → l1 → … → l{joints}` of revolute joints, each 0.1 m along z of its parent.
fn long_chain(joints: usize) -> String {
    let mut text = String::from("<?xml version=\"1.0\"?>\n<robot name=\"long\">\n");
    for i in 0..=joints {
        text += &format!("  <link name=\"l{i}\"/>\n");
    }
    // Joints listed from the tip down, so that nothing is found by reading in order.
    for i in (0..joints).rev() {
        text += &format!(
            "  <joint name=\"j{i}\" type=\"revolute\">\n    <parent link=\"l{i}\"/>\n    \
             <child link=\"l{}\"/>\n    <origin xyz=\"0 0 0.1\" rpy=\"0 0 0\"/>\n    \
             <axis xyz=\"0 0 1\"/>\n    \
             <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n  </joint>\n",
            i + 1
        );
    }
    text + "</robot>\n"
}

#[test]
fn forty_thousand_nested_tags_are_refused_naming_the_depth_limit_not_a_stack_overflow() {
    let depth = 40_000;
    let mut text = String::from("<?xml version=\"1.0\"?>\n<robot name=\"deep\">\n");
    text += &"<link>".repeat(depth);
    text += &"</link>".repeat(depth);
    text += "\n</robot>\n";
    let err = load(&text).unwrap_err();
    let message = err.to_string();
    assert!(
        matches!(err, UrdfError::TooDeep { line: 3, limit, .. } if limit == MAX_NESTING_DEPTH),
        "{message}"
    );
    assert!(
        message.starts_with("user.urdf: line 3:")
            && message.contains("nesting depth")
            && message.contains(&format!("limit of {MAX_NESTING_DEPTH} levels")),
        "{message}"
    );
}

#[test]
fn a_truncated_file_names_the_element_left_open_and_its_line() {
    let cut = TWO_JOINTS.find("<axis").unwrap();
    let err = load(&TWO_JOINTS[..cut]).unwrap_err();
    let message = err.to_string();
    assert!(matches!(err, UrdfError::Xml { line: 6, .. }), "{message}");
    assert!(
        message.contains("<joint> opened on this line is never closed"),
        "{message}"
    );
}

#[test]
fn a_chain_of_16000_joints_loads_in_linear_time_and_its_fk_adds_up_the_offsets() {
    // 4 MB. Reading it took time quadratic in its length (9 s for 4 000 joints on 2026-11-23,
    // so about 2.5 minutes for this one); it now takes about a second in the dev profile.
    let joints = 16_000;
    let text = long_chain(joints);
    assert!(text.len() > 3_900_000 && text.len() < MAX_URDF_BYTES);
    let robot = load(&text).unwrap();
    assert_eq!(robot.joints.len(), joints);
    assert_eq!(robot.joints[0].name, "j0");
    assert_eq!(robot.joints[joints - 1].name, format!("j{}", joints - 1));
    let chain = robot.chain(None).unwrap();
    assert_eq!(chain.tip, format!("l{joints}"));
    assert_eq!(chain.dof(), joints);
    let tip = chain.fk(&vec![0.3; joints]);
    let z = tip.xyz()[2];
    assert!((z - 0.1 * joints as f64).abs() < 1e-6, "tip at z = {z} m");
}

#[test]
fn text_over_the_size_limit_is_refused_naming_the_limit() {
    let padding = format!("<!--{}-->", " ".repeat(MAX_URDF_BYTES));
    let text = TWO_JOINTS.replace("</robot>", &format!("{padding}</robot>"));
    let err = load(&text).unwrap_err();
    let message = err.to_string();
    assert!(matches!(err, UrdfError::TooLarge { .. }), "{message}");
    assert!(
        message.contains(&format!("{} bytes", text.len()))
            && message.contains(&format!("{MAX_URDF_BYTES} bytes")),
        "{message}"
    );
}

#[test]
fn a_file_over_the_size_limit_is_refused_without_reading_it() {
    let path = std::env::temp_dir().join(format!("fairgrasp-huge-{}.urdf", std::process::id()));
    let file = std::fs::File::create(&path).unwrap();
    file.set_len(MAX_URDF_BYTES as u64 + 1).unwrap(); // sparse: nothing is written
    let result = UrdfRobot::from_file(&path);
    std::fs::remove_file(&path).unwrap();
    let message = result.unwrap_err().to_string();
    assert!(
        message.starts_with(&path.display().to_string())
            && message.contains(&format!("{} bytes is more than", MAX_URDF_BYTES + 1)),
        "{message}"
    );
}

#[test]
fn a_duplicate_joint_name_is_refused_naming_the_joint_and_both_lines() {
    let text = TWO_JOINTS.replace(r#"<joint name="j2""#, r#"<joint name="j1""#);
    let err = load(&text).unwrap_err();
    let message = err.to_string();
    assert_eq!(
        err,
        UrdfError::Duplicate {
            file: "user.urdf".into(),
            line: 13,
            kind: "joint",
            name: "j1".into(),
            first_line: 6,
        },
        "{message}"
    );
    assert!(
        message.contains("a second joint named 'j1'") && message.contains("line 6"),
        "{message}"
    );
}

#[test]
fn a_duplicate_link_name_is_refused_naming_the_link() {
    let text = TWO_JOINTS.replace(r#"<link name="hand"/>"#, r#"<link name="arm"/>"#);
    let message = load(&text).unwrap_err().to_string();
    assert!(
        message.contains("line 5") && message.contains("a second link named 'arm'"),
        "{message}"
    );
}

#[test]
fn a_revolute_or_prismatic_joint_without_limit_is_refused_naming_it() {
    let without_j1_limit = TWO_JOINTS.replacen(
        r#"    <limit lower="-1" upper="1" effort="1" velocity="1"/>
"#,
        "",
        1,
    );
    let err = load(&without_j1_limit).unwrap_err();
    let message = err.to_string();
    assert!(
        matches!(err, UrdfError::MissingLimit { line: 6, ref joint, ref kind, .. } if joint == "j1" && kind == "revolute"),
        "{message}"
    );
    assert!(
        message.contains("joint 'j1' is revolute but has no <limit>"),
        "{message}"
    );

    let without_j2_limit = TWO_JOINTS.replace(
        r#"<limit lower="0" upper="0.1" effort="1" velocity="1"/>"#,
        "",
    );
    let message = load(&without_j2_limit).unwrap_err().to_string();
    assert!(
        message.contains("joint 'j2' is prismatic but has no <limit>"),
        "{message}"
    );

    // An empty element has no <limit> either.
    let empty = TWO_JOINTS.replace(
        r#"<joint name="j1" type="revolute">"#,
        r#"<joint name="j0" type="revolute"/><joint name="j1" type="revolute">"#,
    );
    let message = load(&empty).unwrap_err().to_string();
    assert!(message.contains("joint 'j0' is revolute"), "{message}");
}

#[test]
fn a_continuous_joint_needs_no_limit() {
    let text = TWO_JOINTS
        .replace(r#"type="revolute""#, r#"type="continuous""#)
        .replacen(
            r#"<limit lower="-1" upper="1" effort="1" velocity="1"/>"#,
            "",
            1,
        );
    let robot = load(&text).unwrap();
    assert_eq!(robot.joints[0].limits, None);
}

#[test]
fn non_finite_numbers_are_refused_naming_the_element_and_attribute() {
    let cases = [
        (
            r#"<origin xyz="0 0 0.1" rpy="0 0 0"/>"#,
            r#"<origin xyz="0 0 0.1" rpy="0 1e400 0"/>"#,
            "joint 'j1' <origin> rpy=\"0 1e400 0\"",
        ),
        (
            r#"<origin xyz="0 0 0.1" rpy="0 0 0"/>"#,
            r#"<origin xyz="inf 0 0.1" rpy="0 0 0"/>"#,
            "joint 'j1' <origin> xyz=\"inf 0 0.1\"",
        ),
        (
            r#"<axis xyz="0 0 1"/>"#,
            r#"<axis xyz="0 NaN 1"/>"#,
            "joint 'j1' <axis> xyz=\"0 NaN 1\"",
        ),
        (
            r#"upper="1""#,
            r#"upper="-inf""#,
            "joint 'j1' <limit> upper=\"-inf\"",
        ),
        (
            r#"velocity="1"/>"#,
            r#"velocity="1e999"/>"#,
            "joint 'j1' <limit> velocity=\"1e999\"",
        ),
    ];
    for (from, to, named) in cases {
        let text = TWO_JOINTS.replacen(from, to, 1);
        let err = load(&text).unwrap_err();
        let message = err.to_string();
        assert!(matches!(err, UrdfError::BadValue { .. }), "{message}");
        assert!(message.contains(named), "{to}: {message}");
    }
}

#[test]
fn a_non_finite_quaternion_origin_of_urdf_1_1_is_refused() {
    // URDF 1.1 allows `quat_xyzw` instead of `rpy` (read as the rotation it gives); a NaN
    // quaternion used to become the identity rotation silently.
    let text = TWO_JOINTS
        .replace(
            r#"<robot name="tiny">"#,
            r#"<robot name="tiny" version="1.1">"#,
        )
        .replacen(
            r#"<origin xyz="0 0 0.1" rpy="0 0 0"/>"#,
            r#"<origin xyz="0 0 0.1" quat_xyzw="nan 0 0 1"/>"#,
            1,
        );
    let message = load(&text).unwrap_err().to_string();
    assert!(
        message.contains("joint 'j1' <origin> quat_xyzw=\"nan 0 0 1\"")
            && message.contains("4 finite numbers"),
        "{message}"
    );
}

#[test]
fn a_huge_but_finite_axis_is_normalised_not_turned_into_zero() {
    let text = TWO_JOINTS.replace(r#"<axis xyz="0 0 1"/>"#, r#"<axis xyz="0 0 1e300"/>"#);
    let robot = load(&text).unwrap();
    assert_eq!(robot.joints[0].axis, [0.0, 0.0, 1.0]);
}
