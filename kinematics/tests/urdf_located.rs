//! What urdf-rs refuses after the pre-check is named with its line and element (urdf-rs names
//! neither), and the pre-check's rules for what urdf-rs would read silently differently.

use fairgrasp_kinematics::urdf::urdf_rs;
use fairgrasp_kinematics::{FR3_URDF, UrdfError, UrdfRobot};

/// Line 3 the link, 4 its visual; line 9 the joint, 12 its axis, 13 its limit; line 15 the
/// material, 16 its color.
const ARM: &str = r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link">
    <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
    <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
  </link>
  <link name="arm"/>

  <joint name="j1" type="revolute">
    <parent link="base_link"/>
    <child link="arm"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <material name="grey">
    <color rgba="0.5 0.5 0.5 1"/>
  </material>
</robot>
"#;

fn load(text: &str) -> Result<UrdfRobot, UrdfError> {
    UrdfRobot::from_str_named(text, "arm.urdf")
}

/// `ARM` with `from` replaced by `to` (which must occur).
fn with(from: &str, to: &str) -> String {
    assert!(ARM.contains(from), "{from}");
    ARM.replacen(from, to, 1)
}

fn refusal(text: &str) -> String {
    load(text).unwrap_err().to_string()
}

#[test]
fn the_example_loads() {
    let robot = load(ARM).unwrap();
    assert_eq!(robot.links, ["base_link", "arm"]);
    assert_eq!(robot.joints[0].axis, [0.0, 0.0, 1.0]);
}

#[test]
fn what_urdf_rs_refuses_is_named_with_the_line_and_element_it_concerns() {
    let cases = [
        (
            with(
                "<geometry><box size=\"0.1 0.1 0.1\"/></geometry>",
                "<origin xyz=\"0 0 0\"/>",
            ),
            "line 4: link 'base_link' <visual>: urdf-rs: missing field `geometry`",
        ),
        (
            with("<mass value=\"1\"/>", ""),
            "line 5: link 'base_link' <inertial>: urdf-rs: missing field `mass`",
        ),
        (
            with("<box size=\"0.1 0.1 0.1\"/>", "<mesh/>"),
            "line 4: link 'base_link' <visual>: urdf-rs: missing field `filename`",
        ),
        (
            with("<axis xyz=\"0 0 1\"/>", "<axis/>"),
            "line 12: joint 'j1' <axis>: urdf-rs: missing field `xyz`",
        ),
        (
            with("<color rgba=\"0.5 0.5 0.5 1\"/>", "<color/>"),
            "line 16: material 'grey' <color>: urdf-rs: missing field `rgba`",
        ),
    ];
    for (text, expected) in cases {
        let message = refusal(&text);
        assert!(
            message.starts_with("arm.urdf: ") && message.contains(expected),
            "expected {expected:?} in {message}"
        );
    }
}

#[test]
fn xml_that_only_urdf_rs_refuses_is_named_with_its_line_column_and_element() {
    // An attribute without a value (as HTML writes them) is not XML: the pre-check's reader
    // skips it, urdf-rs's refuses it.
    let message = refusal(&with(
        "<axis xyz=\"0 0 1\"/>",
        "<axis xyz=\"0 0 1\" checked />",
    ));
    assert!(
        message.contains("line 12: joint 'j1' <axis>: urdf-rs's XML reader, column")
            && message.contains("Space occured in attribute name"),
        "{message}"
    );
}

#[test]
fn entity_declarations_are_refused_naming_the_line() {
    let doctype = "<!DOCTYPE robot [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;\">]>\n";
    let text = ARM.replacen("<robot", &format!("{doctype}<robot"), 1);
    let message = refusal(&text);
    assert!(
        message.contains("line 2: the <!DOCTYPE> declares entities"),
        "{message}"
    );
    // A DOCTYPE without entities is harmless and read.
    let text = ARM.replacen("<robot", "<!DOCTYPE robot>\n<robot", 1);
    assert!(load(&text).is_ok());
}

#[test]
fn a_quaternion_origin_needs_urdf_1_1_and_a_non_zero_quaternion() {
    let quaternion = with("<axis xyz", "<origin quat_xyzw=\"0 0 0.6 0.8\"/><axis xyz");
    // urdf-rs reads a URDF 1.0 file's quat_xyzw as no rotation at all: refused, not misread.
    let message = refusal(&quaternion);
    assert!(
        message.contains("line 12: joint 'j1' <origin>: quat_xyzw is URDF 1.1"),
        "{message}"
    );
    let version_1_1 = quaternion.replace(
        "<robot name=\"arm\">",
        "<robot name=\"arm\" version=\"1.1\">",
    );
    let robot = load(&version_1_1).unwrap();
    let yaw = robot.joints[0].origin.rpy()[2];
    assert!((yaw - 2.0 * 0.6f64.atan2(0.8)).abs() < 1e-12, "yaw {yaw}");
    let zero = version_1_1.replace("0 0 0.6 0.8", "0 0 0 0");
    let message = refusal(&zero);
    assert!(message.contains("quat_xyzw is zero"), "{message}");
}

#[test]
fn a_link_without_a_name_is_named_by_its_line() {
    let message = refusal(&with("<link name=\"arm\"/>", "<link/>"));
    assert!(
        message.contains("line 7: a <link> has no name attribute"),
        "{message}"
    );
}

#[test]
fn a_robot_urdf_rs_read_maps_to_the_same_model_as_the_text() {
    let theirs = urdf_rs::read_from_string(FR3_URDF).unwrap();
    let from_robot = UrdfRobot::from_urdf_rs(&theirs, "fr3.urdf").unwrap();
    let from_text = UrdfRobot::from_str_named(FR3_URDF, "fr3.urdf").unwrap();
    assert_eq!(from_robot, from_text);
}

#[test]
fn a_robot_built_in_code_with_a_non_finite_origin_is_refused_naming_the_joint() {
    let mut robot = urdf_rs::read_from_string(ARM).unwrap();
    robot.joints[0].origin.xyz.0[1] = f64::NAN;
    let message = UrdfRobot::from_urdf_rs(&robot, "built")
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("built: joint 'j1': <origin> xyz holds a non-finite number"),
        "{message}"
    );
}
