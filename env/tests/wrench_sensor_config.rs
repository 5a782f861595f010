//! `[sensor.wrench]`: its numbers are checked naming the field, and a wrist sensor is only had
//! on a task with a fixture.

use fairgrasp_env::config::{EnvConfig, TaskKind, WrenchSensorConfig};

fn place_with(sensor: WrenchSensorConfig) -> EnvConfig {
    let mut c = EnvConfig::default();
    c.task.kind = TaskKind::Place;
    c.sensor.wrench = Some(sensor);
    c
}

#[test]
fn a_noise_that_is_negative_not_finite_or_too_large_is_refused_naming_the_field() {
    let cases = [
        (-0.1, "force_noise"),
        (f64::NAN, "torque_noise"),
        (f64::INFINITY, "force_resolution"),
        (50.0, "force_noise"),
        (2.0, "torque_resolution"),
    ];
    for (value, field) in cases {
        let mut s = WrenchSensorConfig::default();
        match field {
            "force_noise" => s.force_noise = value,
            "torque_noise" => s.torque_noise = value,
            "force_resolution" => s.force_resolution = value,
            _ => s.torque_resolution = value,
        }
        let err = place_with(s).validate().unwrap_err().to_string();
        assert!(err.contains(&format!("sensor.wrench.{field}")), "{err}");
    }
    assert!(place_with(WrenchSensorConfig::default()).validate().is_ok());
}

#[test]
fn a_wrench_sensor_on_a_task_without_a_fixture_is_refused() {
    let mut lift = EnvConfig::default();
    lift.sensor.wrench = Some(WrenchSensorConfig::default());
    let err = lift.validate().unwrap_err().to_string();
    assert!(
        err.contains("sensor.wrench") && err.contains("lift"),
        "{err}"
    );
    assert_eq!(EnvConfig::default().wrench_sensor(), None);
    let mut place = EnvConfig::default();
    place.task.kind = TaskKind::Place;
    assert_eq!(place.wrench_sensor(), Some(WrenchSensorConfig::default()));
}

#[test]
fn a_sensor_table_in_a_preset_file_is_read_and_checked() {
    let text = "[task]\nkind = \"place\"\n[sensor.wrench]\nforce_noise = 0.1\n";
    let config: EnvConfig = toml::from_str(text).unwrap();
    assert_eq!(config.wrench_sensor().unwrap().force_noise, 0.1);
    assert_eq!(config.wrench_sensor().unwrap().torque_noise, 0.002);
    let bad = "[task]\nkind = \"place\"\n[sensor.wrench]\nforce_nois = 0.1\n";
    assert!(toml::from_str::<EnvConfig>(bad).is_err());
}
