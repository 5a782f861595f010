//! URDF loading: the shipped files agree with the model; every bad input gets a named error.

use fairgrasp_kinematics::urdf::JointKind;
use fairgrasp_kinematics::{ArmKind, FR3_URDF, UrdfError, UrdfRobot};

const TWO_LINKS: &str = r#"<?xml version="1.0"?>
<robot name="tiny">
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base_link"/>
    <child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
"#;

fn load(text: &str) -> Result<UrdfRobot, UrdfError> {
    UrdfRobot::from_str_named(text, "bad.urdf")
}

#[test]
fn the_valid_minimal_urdf_loads() {
    let robot = load(TWO_LINKS).unwrap();
    assert_eq!(robot.root, "base_link");
    assert_eq!(robot.chain(None).unwrap().tip, "arm");
}

#[test]
fn fr3_urdf_lists_the_arm_and_gripper_joints_in_tree_order() {
    let robot = UrdfRobot::from_str_named(FR3_URDF, "fr3.urdf").unwrap();
    let names: Vec<&str> = robot.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        &names[..7],
        ["j1", "j2", "j3", "j4", "j5", "j6", "wrist3_tool0"]
    );
    let movable: Vec<&str> = robot.movable_joints().map(|j| j.name.as_str()).collect();
    assert_eq!(
        movable,
        [
            "j1",
            "j2",
            "j3",
            "j4",
            "j5",
            "j6",
            "finger_left_joint",
            "finger_right_joint"
        ]
    );
    let finger = robot
        .joints
        .iter()
        .find(|j| j.name == "finger_left_joint")
        .unwrap();
    assert_eq!(finger.kind, JointKind::Prismatic);
    assert_eq!(finger.limits, Some([0.0, 0.0425]));
}

#[test]
fn fr3_urdf_limits_inertias_and_capsules_equal_the_model() {
    let model = ArmKind::Fr3.model();
    let text = FR3_URDF;
    let robot = urdf_rs::read_from_string(text).unwrap();
    for spec in &model.joints {
        let joint = robot.joints.iter().find(|j| j.name == spec.name).unwrap();
        assert!(
            (joint.limit.lower - spec.lower).abs() < 1e-12,
            "{}",
            spec.name
        );
        assert!(
            (joint.limit.upper - spec.upper).abs() < 1e-12,
            "{}",
            spec.name
        );
        assert!(
            (joint.limit.velocity - spec.max_velocity).abs() < 1e-12,
            "{}",
            spec.name
        );
    }
    for inertial in &model.inertials {
        let link = robot
            .links
            .iter()
            .find(|l| l.name == inertial.link)
            .unwrap();
        assert_eq!(link.inertial.mass.value, inertial.mass, "{}", inertial.link);
        assert_eq!(
            link.inertial.origin.xyz.0, inertial.com,
            "{}",
            inertial.link
        );
        let i = &link.inertial.inertia;
        assert_eq!(
            [i.ixx, i.iyy, i.izz],
            inertial.inertia_diag,
            "{}",
            inertial.link
        );
    }
    for capsule in &model.capsules {
        let link = robot.links.iter().find(|l| l.name == capsule.link).unwrap();
        let collision = &link.collision[0];
        let urdf_rs::Geometry::Capsule { radius, length } = collision.geometry else {
            panic!("{}: not a capsule", capsule.link);
        };
        let axis: Vec<f64> = (0..3).map(|k| capsule.to[k] - capsule.from[k]).collect();
        let expected_length = axis.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!((radius - capsule.radius).abs() < 1e-12, "{}", capsule.link);
        assert!((length - expected_length).abs() < 1e-9, "{}", capsule.link);
        for k in 0..3 {
            let mid = 0.5 * (capsule.from[k] + capsule.to[k]);
            assert!(
                (collision.origin.xyz.0[k] - mid).abs() < 1e-9,
                "{}",
                capsule.link
            );
        }
    }
    let gripper = model.gripper;
    let tcp = robot.joints.iter().find(|j| j.name == "palm_tcp").unwrap();
    assert_eq!(tcp.origin.xyz.0, [0.0, 0.0, gripper.tcp_offset]);
    let finger = robot
        .joints
        .iter()
        .find(|j| j.name == "finger_right_joint")
        .unwrap();
    assert_eq!(finger.limit.upper, gripper.finger_travel);
}

#[test]
fn the_fr3_tree_is_not_serial_without_a_tip_and_the_error_names_the_branching_link() {
    let robot = UrdfRobot::from_str_named(FR3_URDF, "fr3.urdf").unwrap();
    let err = robot.chain(None).unwrap_err();
    assert!(
        matches!(err, UrdfError::NonSerial { ref link, .. } if link == "palm"),
        "{err}"
    );
    let message = err.to_string();
    assert!(
        message.contains("fr3.urdf") && message.contains("finger_left_joint"),
        "{message}"
    );
}

#[test]
fn a_missing_parent_link_is_named() {
    let text = TWO_LINKS.replace(
        r#"<parent link="base_link"/>"#,
        r#"<parent link="shoulder"/>"#,
    );
    let err = load(&text).unwrap_err();
    assert_eq!(
        err,
        UrdfError::MissingLink {
            file: "bad.urdf".into(),
            joint: "j1".into(),
            role: "parent",
            link: "shoulder".into()
        }
    );
}

#[test]
fn an_unknown_joint_type_names_the_joint_line_and_value() {
    let text = TWO_LINKS.replace(r#"type="revolute""#, r#"type="hinge""#);
    let err = load(&text).unwrap_err();
    let message = err.to_string();
    assert!(
        matches!(err, UrdfError::UnknownJointType { line: 5, .. }),
        "{message}"
    );
    assert!(
        message.contains("joint 'j1'") && message.contains("\"hinge\""),
        "{message}"
    );
}

#[test]
fn a_bad_number_names_the_element_attribute_and_value() {
    for bad in ["0 0 abc", "0 0", "0 0 nan", "0 0 inf"] {
        let text = TWO_LINKS.replace(r#"xyz="0 0 0.1""#, &format!(r#"xyz="{bad}""#));
        let err = load(&text).unwrap_err();
        let message = err.to_string();
        assert!(
            matches!(err, UrdfError::BadValue { line: 8, .. }),
            "{message}"
        );
        assert!(
            message.contains("joint 'j1' <origin> xyz") && message.contains(bad),
            "{message}"
        );
    }
    let text = TWO_LINKS.replace(r#"upper="1""#, r#"upper="one""#);
    let message = load(&text).unwrap_err().to_string();
    assert!(
        message.contains("<limit> upper=\"one\"") && message.contains("one finite number"),
        "{message}"
    );
}

#[test]
fn inverted_limits_and_a_zero_axis_are_refused() {
    let text = TWO_LINKS.replace(r#"lower="-1" upper="1""#, r#"lower="1" upper="-1""#);
    assert!(load(&text).unwrap_err().to_string().contains("above upper"));
    let text = TWO_LINKS.replace(r#"<axis xyz="0 0 1"/>"#, r#"<axis xyz="0 0 0"/>"#);
    assert!(
        load(&text)
            .unwrap_err()
            .to_string()
            .contains("axis is zero")
    );
}

#[test]
fn two_root_links_are_not_a_tree() {
    let text = TWO_LINKS.replace(
        r#"<link name="arm"/>"#,
        r#"<link name="arm"/><link name="stray"/>"#,
    );
    let message = load(&text).unwrap_err().to_string();
    assert!(
        message.contains("2 root links") && message.contains("stray"),
        "{message}"
    );
}

#[test]
fn a_link_with_two_parents_is_not_a_tree() {
    let second = r#"<joint name="j2" type="fixed"><parent link="base_link"/><child link="arm"/></joint></robot>"#;
    let text = TWO_LINKS.replace("</robot>", second);
    let message = load(&text).unwrap_err().to_string();
    assert!(message.contains("child of two joints"), "{message}");
}

#[test]
fn malformed_xml_reports_the_line() {
    let text = TWO_LINKS.replace("</joint>", "</jont>");
    let message = load(&text).unwrap_err().to_string();
    assert!(
        message.contains("bad.urdf: line") && message.contains("not well-formed"),
        "{message}"
    );
}

#[test]
fn a_missing_file_names_the_path() {
    let message = UrdfRobot::from_file("/nonexistent/robot.urdf")
        .unwrap_err()
        .to_string();
    assert!(
        message.starts_with("/nonexistent/robot.urdf: cannot read"),
        "{message}"
    );
}

#[test]
fn an_unknown_tip_lists_the_links() {
    let message = load(TWO_LINKS)
        .unwrap()
        .chain(Some("hand"))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("no link named 'hand'") && message.contains("base_link, arm"),
        "{message}"
    );
}

#[test]
fn a_floating_joint_in_the_chain_is_unsupported() {
    let text = TWO_LINKS.replace(r#"type="revolute""#, r#"type="floating""#);
    let message = load(&text).unwrap().chain(None).unwrap_err().to_string();
    assert!(message.contains("joint 'j1' is floating"), "{message}");
}

/// urdf-rs reads the text and `map.rs` maps its robot into fairgrasp's model; on every shipped
/// file, and on the test's own, the model holds what urdf-rs read: names, links, joint types,
/// parents, children, origins, axes (normalised) and limits.
#[test]
fn every_shipped_urdf_reads_as_urdf_rs_reads_it() {
    let seven = include_str!("../../assets/seven_joint_arm.urdf");
    // URDF 1.1: a rotation given as a quaternion (urdf-rs turns it into rpy).
    let quaternion = TWO_LINKS
        .replace(
            "<robot name=\"tiny\">",
            "<robot name=\"tiny\" version=\"1.1\">",
        )
        .replace("rpy=\"0 0 0\"", "quat_xyzw=\"0.1 -0.4 0.3 0.8\"");
    for (file, text) in [
        ("quaternion.urdf", quaternion.as_str()),
        ("fr3.urdf", FR3_URDF),
        ("fr5.urdf", fairgrasp_kinematics::FR5_URDF),
        ("seven_joint_arm.urdf", seven),
        ("tiny.urdf", TWO_LINKS),
    ] {
        let ours = UrdfRobot::from_str_named(text, file).unwrap();
        let theirs = urdf_rs::read_from_string(text).unwrap();
        assert_eq!(ours.name, theirs.name, "{file}");
        let links: Vec<&str> = theirs.links.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(ours.links, links, "{file}");
        assert_eq!(ours.joints.len(), theirs.joints.len(), "{file}");
        for t in &theirs.joints {
            let o = ours.joints.iter().find(|j| j.name == t.name).unwrap();
            let what = format!("{file}: joint {}", t.name);
            assert_eq!(
                o.kind.name(),
                format!("{:?}", t.joint_type).to_lowercase(),
                "{what}"
            );
            assert_eq!(
                (&o.parent, &o.child),
                (&t.parent.link, &t.child.link),
                "{what}"
            );
            let expected = fairgrasp_kinematics::Pose::from_xyz_rpy(t.origin.xyz.0, t.origin.rpy.0);
            let error = (o.origin.iso.inverse() * expected.iso).to_homogeneous()
                - nalgebra::Matrix4::identity();
            assert!(error.amax() < 1e-12, "{what}: origin {error}");
            let a = t.axis.xyz.0;
            let norm = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            for (ours, theirs) in o.axis.iter().zip(a) {
                assert!((ours - theirs / norm).abs() < 1e-12, "{what}: axis");
            }
            let limits = o.limits.unwrap_or([t.limit.lower, t.limit.upper]);
            assert_eq!(limits, [t.limit.lower, t.limit.upper], "{what}");
            assert_eq!(
                (o.max_velocity, o.max_effort),
                (t.limit.velocity, t.limit.effort),
                "{what}"
            );
        }
    }
}

#[test]
fn what_the_reader_needs_and_does_not_find_is_named_with_its_line() {
    let no_parent = TWO_LINKS.replace("    <parent link=\"base_link\"/>\n", "");
    let e = load(&no_parent).unwrap_err().to_string();
    assert!(
        e.contains("bad.urdf") && e.contains("line 5") && e.contains("joint 'j1' has no <parent"),
        "{e}"
    );
    let not_robot = "<?xml version=\"1.0\"?>\n<model name=\"m\"><link name=\"a\"/></model>\n";
    let e = load(not_robot).unwrap_err().to_string();
    assert!(
        e.contains("line 2") && e.contains("root element is <model>"),
        "{e}"
    );
    let twice = TWO_LINKS.replace(
        "<axis xyz=\"0 0 1\"/>",
        "<axis xyz=\"0 0 1\"/><axis xyz=\"1 0 0\"/>",
    );
    let e = load(&twice).unwrap_err().to_string();
    assert!(
        e.contains("line 9") && e.contains("joint 'j1' <axis>: given twice"),
        "{e}"
    );
    let no_velocity = TWO_LINKS.replace(" velocity=\"1\"", "");
    let e = load(&no_velocity).unwrap_err().to_string();
    assert!(
        e.contains("joint 'j1' <limit>: no velocity attribute"),
        "{e}"
    );
    let both = TWO_LINKS.replace("rpy=\"0 0 0\"", "rpy=\"0 0 0\" quat_xyzw=\"0 0 0 1\"");
    let e = load(&both).unwrap_err().to_string();
    assert!(e.contains("both rpy and quat_xyzw"), "{e}");
    let second_root = format!("{TWO_LINKS}<robot name=\"other\"/>\n");
    let e = load(&second_root).unwrap_err().to_string();
    assert!(
        e.contains("line 13") && e.contains("a second root element <robot>"),
        "{e}"
    );
    // urdf-rs reads a nameless robot as named ""; so does fairgrasp.
    let unnamed = TWO_LINKS.replace("<robot name=\"tiny\">", "<robot>");
    assert_eq!(load(&unnamed).unwrap().name, "");
    let bad_parent = TWO_LINKS.replace("<parent link=\"base_link\"/>", "<parent/>");
    let e = load(&bad_parent).unwrap_err().to_string();
    assert!(e.contains("joint 'j1' <parent>: no link attribute"), "{e}");
}
