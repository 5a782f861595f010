//! A joint stream as a file: JSON (whose `period_sec` and `joints_deg` are the goal of the
//! FAIRINO ROS 2 driver's `stream_servo_j` action, one to one), CSV, or NumPy `.npy` (an N×6
//! float64 array in degrees, as the PyBullet recipe saves its joint angles). Encoding returns
//! bytes (the caller writes them atomically); decoding reads JSON and CSV back for playback.

use fairgrasp_kinematics::ArmModel;
use serde_json::{Value, json};

use crate::stream::check::peaks;
use crate::stream::limits::PERIOD_RANGE_SEC;
use crate::stream::servo::{GripperEvent, ServoStream};

/// The `format` field of a stream's JSON.
pub const JSON_FORMAT: &str = "fairgrasp servo stream 1";
/// The most samples a stream file may hold (about 22 hours at 8 ms).
pub const MAX_SAMPLES: usize = 10_000_000;

/// The stream's file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Json,
    Csv,
    Npy,
}

impl Format {
    /// The format a file name's extension names, if any.
    pub fn of(path: &std::path::Path) -> Option<Format> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "json" => Some(Format::Json),
            "csv" => Some(Format::Csv),
            "npy" => Some(Format::Npy),
            _ => None,
        }
    }
}

/// Why a stream file cannot be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct StreamFileError(pub String);

fn fail<T>(message: impl Into<String>) -> Result<T, StreamFileError> {
    Err(StreamFileError(message.into()))
}

/// The stream as JSON (keys in alphabetical order): `period_sec` and `joints_deg` (N×6, flat,
/// row by row), and beside them what a person or a script needs: the joint order, the sample
/// count, the hold, the gripper events (command and commanded opening \[m\], when the stream has
/// any), the peaks, and `source` (where it came from, as the caller describes it).
pub fn to_json(stream: &ServoStream, model: &ArmModel, source: &Value) -> Vec<u8> {
    let period = stream.period_sec;
    let joints_deg: Vec<f64> = stream
        .joints
        .iter()
        .flat_map(|q| q.map(f64::to_degrees))
        .collect();
    let mut doc = json!({
        "period_sec": period,
        "joints_deg": joints_deg,
        "format": JSON_FORMAT,
        "joint_order": model.joints.map(|j| j.name),
        "samples": stream.joints.len(),
        "hold_samples": stream.hold_samples,
        "duration_sec": stream.duration_sec(),
        "peaks": peaks(&stream.joints, period),
        "source": source,
    });
    if !stream.gripper.is_empty() {
        let travel = model.gripper.finger_travel;
        doc["gripper"] = stream
            .gripper
            .iter()
            .map(|e| {
                let opening = model.gripper.opening((e.command + 1.0) / 2.0 * travel);
                json!({"sample": e.sample, "time_sec": e.sample as f64 * period,
                       "command": e.command, "opening_m": opening})
            })
            .collect();
    }
    let mut bytes = serde_json::to_vec_pretty(&doc).expect("a stream serialises");
    bytes.push(b'\n');
    bytes
}

/// The stream as CSV: `sample,time_sec,j1_deg,…,j6_deg`, plus `gripper_command` (the command in
/// effect at that sample) when the stream has gripper events.
pub fn to_csv(stream: &ServoStream) -> Vec<u8> {
    let with_gripper = !stream.gripper.is_empty();
    let mut out = String::from("sample,time_sec,j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg");
    out.push_str(if with_gripper {
        ",gripper_command\n"
    } else {
        "\n"
    });
    for (n, q) in stream.joints.iter().enumerate() {
        out.push_str(&format!("{n},{:.6}", n as f64 * stream.period_sec));
        for v in q {
            out.push_str(&format!(",{:.9}", v.to_degrees()));
        }
        if let Some(g) = stream.gripper_at(n).filter(|_| with_gripper) {
            out.push_str(&format!(",{g}"));
        }
        out.push('\n');
    }
    out.into_bytes()
}

/// `values` as a NumPy `.npy` file (format 1.0, little-endian float64, C order) of `shape`.
pub fn to_npy(values: &[f64], shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let mut header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    // Magic (6) + version (2) + length (2) + header + '\n' is a multiple of 64 bytes.
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    for v in values {
        bytes.extend_from_slice(&v.to_le_bytes());
    }
    bytes
}

/// The joints as an N×6 `.npy` array \[deg\].
pub fn joints_npy(stream: &ServoStream) -> Vec<u8> {
    let flat: Vec<f64> = stream
        .joints
        .iter()
        .flat_map(|q| q.map(f64::to_degrees))
        .collect();
    to_npy(&flat, &[stream.joints.len(), 6])
}

/// The gripper command in effect at each sample as an N-vector `.npy` array.
pub fn gripper_npy(stream: &ServoStream) -> Vec<u8> {
    let commands: Vec<f64> = (0..stream.joints.len())
        .map(|n| stream.gripper_at(n).unwrap_or(-1.0))
        .collect();
    to_npy(&commands, &[commands.len()])
}

/// A stream read from `text` in `format` (JSON or CSV), and the JSON's `source` (`Null` for
/// CSV). Checks the shape and the period, not the limits.
pub fn parse(text: &str, format: Format) -> Result<(ServoStream, Value), StreamFileError> {
    match format {
        Format::Json => parse_json(text),
        Format::Csv => parse_csv(text).map(|s| (s, Value::Null)),
        Format::Npy => fail(
            "a .npy file holds the joints only (no period, no gripper): play the .json or .csv \
             exported beside it",
        ),
    }
}

fn check_period(period: f64, field: &str) -> Result<f64, StreamFileError> {
    if !PERIOD_RANGE_SEC.contains(&period) {
        return fail(format!(
            "{field} = {period}: a servo period is 0.001–0.016 s (FAIRINO's driver)"
        ));
    }
    Ok(period)
}

fn parse_json(text: &str) -> Result<(ServoStream, Value), StreamFileError> {
    let doc: Value = serde_json::from_str(text).or_else(|e| fail(format!("not JSON: {e}")))?;
    let period = doc["period_sec"].as_f64().ok_or_else(|| {
        StreamFileError("no `period_sec` number (a fairgrasp export has one)".into())
    })?;
    let period = check_period(period, "period_sec")?;
    let Some(flat) = doc["joints_deg"].as_array() else {
        return fail("no `joints_deg` array (N×6 numbers, row by row)");
    };
    if flat.is_empty() || flat.len() % 6 != 0 || flat.len() / 6 > MAX_SAMPLES {
        return fail(format!(
            "joints_deg has {} numbers: a stream has 6 per sample, 1 to {MAX_SAMPLES} samples",
            flat.len()
        ));
    }
    let mut joints = Vec::with_capacity(flat.len() / 6);
    for (n, row) in flat.chunks(6).enumerate() {
        let mut q = [0.0; 6];
        for (i, v) in row.iter().enumerate() {
            q[i] = v.as_f64().ok_or_else(|| {
                StreamFileError(format!(
                    "joints_deg: sample {n}, j{}: {v} is not a number",
                    i + 1
                ))
            })?;
        }
        joints.push(q.map(f64::to_radians));
    }
    let mut gripper = Vec::new();
    if let Some(events) = doc.get("gripper") {
        let Some(events) = events.as_array() else {
            return fail("gripper is not an array of {sample, command} events");
        };
        for (k, e) in events.iter().enumerate() {
            let (Some(sample), Some(command)) = (e["sample"].as_u64(), e["command"].as_f64())
            else {
                return fail(format!(
                    "gripper[{k}] needs `sample` (an index) and `command`"
                ));
            };
            let sample = sample as usize;
            if sample >= joints.len() || !(-1.0..=1.0).contains(&command) {
                return fail(format!(
                    "gripper[{k}]: sample {sample} (the stream has {}), command {command} \
                     (−1 open … +1 closed)",
                    joints.len()
                ));
            }
            if gripper
                .last()
                .is_some_and(|p: &GripperEvent| p.sample > sample)
            {
                return fail(format!("gripper[{k}]: events must be in sample order"));
            }
            gripper.push(GripperEvent { sample, command });
        }
    }
    let hold_samples = doc["hold_samples"].as_u64().unwrap_or(0) as usize;
    let stream = ServoStream {
        period_sec: period,
        hold_samples: hold_samples.min(joints.len()),
        joints,
        gripper,
    };
    Ok((stream, doc["source"].clone()))
}

fn parse_csv(text: &str) -> Result<ServoStream, StreamFileError> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .unwrap_or("")
        .split(',')
        .map(str::trim)
        .collect();
    let expected = [
        "sample", "time_sec", "j1_deg", "j2_deg", "j3_deg", "j4_deg", "j5_deg",
    ];
    if header.len() < 8 || header[..7] != expected || header[7] != "j6_deg" {
        return fail("the header is not `sample,time_sec,j1_deg,…,j6_deg[,gripper_command]`");
    }
    let with_gripper = header.get(8) == Some(&"gripper_command");
    let (mut joints, mut times, mut gripper) = (Vec::new(), Vec::new(), Vec::new());
    for (row, line) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let number = |c: usize| -> Result<f64, StreamFileError> {
            let cell = cells.get(c).copied().unwrap_or("");
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    let column = header.get(c).copied().unwrap_or("?");
                    StreamFileError(format!(
                        "row {}: {column} = {cell:?} is not a number",
                        row + 1
                    ))
                })
        };
        if joints.len() >= MAX_SAMPLES {
            return fail(format!("more than {MAX_SAMPLES} samples"));
        }
        times.push(number(1)?);
        joints.push(std::array::from_fn::<_, 6, _>(|i| i).map(|i| number(2 + i)));
        if with_gripper {
            let command = number(8)?;
            if !(-1.0..=1.0).contains(&command) {
                return fail(format!(
                    "row {}: gripper_command {command} is not in −1 … +1",
                    row + 1
                ));
            }
            if gripper
                .last()
                .is_none_or(|e: &GripperEvent| e.command != command)
            {
                gripper.push(GripperEvent {
                    sample: joints.len() - 1,
                    command,
                });
            }
        }
    }
    let joints: Vec<[f64; 6]> = joints
        .into_iter()
        .map(|q| -> Result<[f64; 6], StreamFileError> {
            let mut out = [0.0; 6];
            for (o, v) in out.iter_mut().zip(q) {
                *o = v?.to_radians();
            }
            Ok(out)
        })
        .collect::<Result<_, _>>()?;
    if times.len() < 2 {
        return fail("fewer than 2 rows: no period can be read from time_sec");
    }
    let period = check_period(times[1] - times[0], "time_sec of row 2 − row 1")?;
    if let Some(n) = (0..times.len()).find(|&n| (times[n] - n as f64 * period).abs() > 1e-5) {
        return fail(format!(
            "row {}: time_sec {} is not {n} × {period} s: the samples must be evenly spaced",
            n + 1,
            times[n]
        ));
    }
    Ok(ServoStream {
        period_sec: period,
        joints,
        hold_samples: 0,
        gripper,
    })
}
