//! Where a key is in a TOML text: the dotted path of every key and table header with its line,
//! so a message about a field can cite the line it was written on, in the file the user wrote
//! (a training config's `[env]` table is merged into its preset and checked as another text).
//!
//! A line scanner, not a parser: the text has already parsed when it is asked. It knows table
//! headers (`[a.b]`, `[[a]]`), keys (`k = v`, dotted `a.b = v`, quoted `"k" = v`) and comments;
//! a line inside a multi-line string or array belongs to the key it started on.

/// Every key and table header of `text`, as (line number from 1, dotted path).
pub fn keys(text: &str) -> Vec<(usize, String)> {
    let mut table = String::new();
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = without_comment(raw).trim();
        if let Some(inner) = line.strip_prefix('[') {
            let inner = inner.trim_start_matches('[');
            let name = inner.split(']').next().unwrap_or_default();
            table = dotted(name);
            out.push((i + 1, table.clone()));
        } else if let Some((key, _)) = line.split_once('=')
            && !key.trim().is_empty()
            && !key.contains(['"', '\'']) | key.trim().starts_with(['"', '\''])
        {
            let key = dotted(key);
            let full = if table.is_empty() {
                key
            } else {
                format!("{table}.{key}")
            };
            out.push((i + 1, full));
        }
    }
    out
}

/// `a . "b" .c` → `a.b.c`.
fn dotted(key: &str) -> String {
    key.split('.')
        .map(|p| p.trim().trim_matches(['"', '\'']))
        .collect::<Vec<_>>()
        .join(".")
}

/// The line up to a `#` that is not inside a string.
fn without_comment(line: &str) -> &str {
    let mut quote: Option<char> = None;
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '#') => return &line[..i],
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            _ => {}
        }
    }
    line
}

/// The dotted path of the key (or table) written on `line` (from 1), or on the nearest line
/// above it (a value continued over several lines).
pub fn path_at_line(text: &str, line: usize) -> Option<String> {
    keys(text)
        .into_iter()
        .take_while(|(l, _)| *l <= line)
        .last()
        .map(|(_, p)| p)
}

/// The line (from 1) where `path` is written: the key itself, else the nearest enclosing key
/// or table that is written (an inline table, or the table whose key is missing).
pub fn line_of_path(text: &str, path: &str) -> Option<usize> {
    let keys = keys(text);
    if let Some((line, _)) = keys.iter().find(|(_, p)| p == path) {
        return Some(*line);
    }
    keys.iter()
        .filter(|(_, p)| path.starts_with(&format!("{p}.")))
        .max_by_key(|(_, p)| p.len())
        .map(|(line, _)| *line)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "preset = \"seed\" # a = b\n\n[env.task]\nreward = \"staged\"\n\n[env.task.staged]\nlift = 2.0\n\n[env]\nphysics.substeps = 4\nscene = { cube_mass = 0.1 }\nrandomization.yaw = [\n  0.0,\n  1.0,\n]\n";

    #[test]
    fn keys_tables_dotted_and_inline_keys_are_found_on_their_lines() {
        assert_eq!(line_of_path(TEXT, "preset"), Some(1));
        assert_eq!(line_of_path(TEXT, "env.task.reward"), Some(4));
        assert_eq!(line_of_path(TEXT, "env.task.staged.lift"), Some(7));
        assert_eq!(line_of_path(TEXT, "env.physics.substeps"), Some(10));
        // Inside an inline table: the line of the table's key.
        assert_eq!(line_of_path(TEXT, "env.scene.cube_mass"), Some(11));
        // A key that is not written: the table it would be in.
        assert_eq!(line_of_path(TEXT, "env.task.staged.grasp"), Some(6));
        assert_eq!(line_of_path(TEXT, "model.hidden"), None);
        assert_eq!(
            path_at_line(TEXT, 13).as_deref(),
            Some("env.randomization.yaw")
        );
        assert_eq!(
            path_at_line(TEXT, 7).as_deref(),
            Some("env.task.staged.lift")
        );
    }
}
