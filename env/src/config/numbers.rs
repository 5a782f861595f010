//! Numbers no config field accepts, found by walking a serialised config (so every field,
//! present and future, is covered), and TOML errors that say where.

/// The first non-finite number (inf, −inf, NaN) anywhere in `value`, with its dotted field path
/// (`physics.dt`, `scene.table_size[1]`). TOML accepts `inf` and `nan` literals, and no field of
/// any fairgrasp config means anything with them, so one walk refuses them all.
pub fn first_non_finite(value: &toml::Value) -> Option<(String, f64)> {
    fn walk(v: &toml::Value, path: &mut String) -> Option<(String, f64)> {
        match v {
            toml::Value::Float(f) if !f.is_finite() => Some((path.clone(), *f)),
            toml::Value::Table(t) => t.iter().find_map(|(k, v)| {
                let len = path.len();
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(k);
                let found = walk(v, path);
                path.truncate(len);
                found
            }),
            toml::Value::Array(a) => a.iter().enumerate().find_map(|(i, v)| {
                let len = path.len();
                path.push_str(&format!("[{i}]"));
                let found = walk(v, path);
                path.truncate(len);
                found
            }),
            _ => None,
        }
    }
    walk(value, &mut String::new())
}

/// The first whole number beyond TOML's range (above 9 223 372 036 854 775 807, which serde
/// still reads into a `u64` or `usize` field) anywhere in `value`, with its dotted path.
fn first_huge_integer(value: &serde_json::Value, path: &str) -> Option<(String, String)> {
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        }
    };
    match value {
        serde_json::Value::Number(n) if n.as_u64().is_some_and(|u| u > i64::MAX as u64) => {
            Some((path.to_string(), n.to_string()))
        }
        serde_json::Value::Object(o) => o.iter().find_map(|(k, v)| first_huge_integer(v, &join(k))),
        serde_json::Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, v)| first_huge_integer(v, &format!("{path}[{i}]"))),
        _ => None,
    }
}

/// The first number of a configuration that no field accepts, with its dotted path and why:
/// a non-finite float, or an integer beyond ±9.2·10¹⁸.
pub fn first_bad_number(config: &impl serde::Serialize) -> Option<(String, String, &'static str)> {
    if let Ok(json) = serde_json::to_value(config)
        && let Some((field, value)) = first_huge_integer(&json, "")
    {
        return Some((
            field,
            value,
            "must be at most 9223372036854775807 (and within the field's range)",
        ));
    }
    let value = toml::Value::try_from(config).ok()?;
    first_non_finite(&value).map(|(field, v)| (field, v.to_string(), "must be a finite number"))
}

/// A TOML error as a message that says where: the parser's own (line, column, the line itself)
/// or, for the errors it gives without a position (an integer beyond ±9.2·10¹⁸), the first line
/// holding such an integer.
pub fn toml_error_message(text: &str, error: &toml::de::Error) -> String {
    let message = error.to_string();
    if message.contains("line") {
        return message;
    }
    let too_big = |word: &str| {
        let digits = word.trim_start_matches(['+', '-']).replace('_', "");
        !digits.is_empty()
            && digits.bytes().all(|b| b.is_ascii_digit())
            && word.replace('_', "").parse::<i64>().is_err()
    };
    let found = text.lines().enumerate().find(|(_, line)| {
        line.split(|c: char| c.is_whitespace() || "=[],{}".contains(c))
            .any(too_big)
    });
    match found {
        Some((i, line)) => format!(
            "line {}: `{}`: {message} (integers must lie within ±9223372036854775807)",
            i + 1,
            line.trim()
        ),
        None => message,
    }
}
