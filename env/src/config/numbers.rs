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

/// A TOML error as a message that says where: `line N: `the line` (column C): field: what`, the line
/// counted with LF, CRLF and CR line ends alike and quoted as a bounded excerpt
/// ([`fairgrasp_types::text`]; the parser's own message quoted the whole line, a 1 MB line
/// whole, and a file with old-Mac CR line ends whole as its line 1). For the errors the parser
/// gives without a position (an integer beyond ±9.2·10¹⁸): the first line holding such an
/// integer.
pub fn toml_error_message(text: &str, error: &toml::de::Error) -> String {
    use fairgrasp_types::text::{MAX_QUOTED_CHARS, excerpt, line_and_column};
    let quote = |line: &str| excerpt(line.trim(), MAX_QUOTED_CHARS);
    let message = error.message().trim_end().to_string();
    if let Some(span) = error.span() {
        // A CR not followed by LF (old-Mac line ends, which TOML does not take): cite the
        // line the CR ends, not the one after it.
        let bare_cr = message
            .contains("carriage return")
            .then(|| text[..(span.start + 1).min(text.len())].rfind('\r'))
            .flatten();
        let (line, column, quoted) = line_and_column(text, bare_cr.unwrap_or(span.start));
        let hint = if bare_cr.is_some() {
            " (the file ends its lines with CR alone, as old Macs did: TOML takes LF or CRLF \
             line ends; convert it, e.g. with `tr '\\r' '\\n'`)"
        } else {
            ""
        };
        // The dotted key the line belongs to (`task.stack.base_radius`), when the line ends
        // are ones the key scanner counts as the parser does.
        let field = bare_cr
            .is_none()
            .then(|| crate::config::toml_lines::path_at_line(text, line))
            .flatten()
            .map_or_else(String::new, |f| {
                format!("{}: ", excerpt(&f, MAX_QUOTED_CHARS))
            });
        return format!(
            "line {line}: `{}` (column {column}): {field}{message}{hint}",
            quote(quoted)
        );
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
            quote(line)
        ),
        None => message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(text: &str) -> String {
        let e = toml::from_str::<crate::EnvConfig>(text).expect_err("refused");
        toml_error_message(text, &e)
    }

    #[test]
    fn toml_errors_cite_their_line_for_lf_crlf_and_cr_files_and_quote_an_excerpt() {
        let lines = [
            "[physics]",
            "dt = 0.01",
            "",
            "[scene]",
            "cube_mass = \"heavy\"",
        ];
        for end in ["\n", "\r\n"] {
            let m = message(&(lines.join(end) + end));
            assert!(
                m.starts_with(
                    "line 5: `cube_mass = \"heavy\"` (column 13): scene.cube_mass: invalid type"
                ),
                "{end:?}: {m}"
            );
        }
        // TOML takes no CR-only line ends: the first one is cited on the line it ends, that
        // line alone is quoted (the parser quoted the whole file as its line 1), and why.
        let m = message(&(lines.join("\r") + "\r"));
        assert!(
            m.starts_with("line 1: `[physics]` (column 10): ")
                && m.contains("CR alone")
                && !m.contains("cube_mass"),
            "{m}"
        );
        let ones = vec!["1"; 300_000].join(", ");
        let m = message(&format!("[scene]\ncube_mass = [{ones}]\n"));
        assert!(
            m.starts_with("line 2: `cube_mass = [1, 1") && m.len() < 300,
            "{m}"
        );
    }
}
