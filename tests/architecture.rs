//! No import loop between the files of any crate: every path in a file (in `use` items and
//! inline) that starts at `crate::`, `super::`, `self::` or a child module of the file's own
//! (`schedule::evaluate_all` in `compare/mod.rs`) is resolved to the file that defines what it
//! names — through a module's `pub use child::…` re-exports to the child's file — and the graph
//! of those imports must have no cycle. A `mod.rs`' or crate root's own `pub use` (and
//! `pub(crate) use`) re-exports and `mod` declarations are the module's public face, not
//! imports. A cycle fails naming its files; a parent and its child that import each other (a
//! `mod.rs` used as a toolbox by the children it calls) are named as such.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates whose `src/` is checked (the workspace's members and the root package).
const CRATES: [&str; 11] = [
    "types",
    "kinematics",
    "env",
    "planner",
    "policy",
    "evaluate",
    "rl",
    "bench",
    "notebooks_export",
    "python",
    ".",
];

/// Children that still import their parent back (a parent used as a toolbox), as (crate, child,
/// parent): issue 48's remaining debts. The loop search leaves these imports out; each must
/// still be there, so one that is moved away must leave this list too.
const KNOWN_BACK_IMPORTS: [(&str, &str, &str); 0] = [];

/// Leaves out of `graph` the known back-imports of `krate`; names each one that is gone.
fn without_known_back_imports(
    krate: &str,
    graph: &mut BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
) -> Vec<String> {
    let module = |m: &str| -> Vec<String> { m.split("::").map(String::from).collect() };
    let mut gone = Vec::new();
    for (_, child, parent) in KNOWN_BACK_IMPORTS.iter().filter(|(k, ..)| *k == krate) {
        let removed = graph
            .get_mut(&module(child))
            .is_some_and(|to| to.remove(&module(parent)));
        if !removed {
            gone.push(format!(
                "{krate}: {child} no longer imports {parent}: remove it from KNOWN_BACK_IMPORTS"
            ));
        }
    }
    gone
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, with its module path (`lib.rs`/`main.rs` = [], `a.rs` and
/// `a/mod.rs` = [a], `a/b.rs` = [a, b]).
fn modules(src: &Path) -> BTreeMap<Vec<String>, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let rel = path.strip_prefix(src).unwrap();
            let mut segments: Vec<String> = rel
                .iter()
                .map(|s| s.to_string_lossy().trim_end_matches(".rs").to_string())
                .collect();
            let last = segments.last().unwrap().clone();
            if last == "mod" || (segments.len() == 1 && (last == "lib" || last == "main")) {
                segments.pop();
            }
            // A crate with both lib.rs and main.rs (the root package): the library is the root.
            if segments.is_empty() && out.contains_key(&segments) && last == "main" {
                continue;
            }
            out.insert(segments, path);
        }
    }
    out
}

/// The text without comments (line comments and block comments) and string literals' content.
fn code_of(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            '/' if chars.peek() == Some(&'*') => {
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
            }
            '"' => {
                let mut escaped = false;
                for c in chars.by_ref() {
                    if escaped {
                        escaped = false;
                    } else if c == '\\' {
                        escaped = true;
                    } else if c == '"' {
                        break;
                    }
                }
                out.push_str("\"\"");
            }
            _ => out.push(c),
        }
    }
    out
}

/// `code` with the paths inside its inline modules (`mod tests { use super::*; }`, `mod trainer
/// { use super::Args; }`) written as the file's own: there `super::` is the file's module, not
/// its parent, so a leading `super::` becomes `self::` and `super::super::` becomes `super::`.
fn inline_modules_resolved(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut depth = 0usize;
    // The brace depths at which the inline modules entered so far opened.
    let mut inline: Vec<usize> = Vec::new();
    let mut i = 0;
    while i < code.len() {
        let rest = &code[i..];
        let boundary = code[..i]
            .chars()
            .last()
            .is_none_or(|c| !(c.is_alphanumeric() || c == '_' || c == ':'));
        if boundary && rest.starts_with("mod ") {
            let name_end = rest[4..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .map_or(rest.len(), |e| 4 + e);
            if rest[name_end..].trim_start().starts_with('{') {
                inline.push(depth + 1);
            }
        }
        if boundary && !inline.is_empty() && rest.starts_with("super::") {
            let mut k = 0;
            while code[i + 7 * k..].starts_with("super::") {
                k += 1;
            }
            out.push_str(if k == 1 { "self::" } else { "" });
            out.push_str(&"super::".repeat(k.saturating_sub(1)));
            i += 7 * k;
            continue;
        }
        let c = rest.chars().next().unwrap();
        match c {
            '{' => depth += 1,
            '}' => {
                if inline.last() == Some(&depth) {
                    inline.pop();
                }
                depth = depth.saturating_sub(1);
            }
            _ => {}
        }
        out.push(c);
        i += c.len_utf8();
    }
    out
}

/// Whether a statement (its text up to a path) is a re-export: a module root's public face.
fn is_reexport(statement: &str) -> bool {
    ["pub use", "pub(crate) use", "pub(super) use"]
        .iter()
        .any(|p| statement.starts_with(p))
}

/// The module paths a piece of code names: `crate::a::b`, `super::a`, `self::a`, `child::a`
/// (`child` one of `children`, the file's own child modules) and groups
/// (`crate::a::{b, c::d}`), each as the path from the crate root (`super`, `self` and a child
/// resolved against `here`, the module of the file).
fn named_paths(
    code: &str,
    here: &[String],
    children: &[String],
    is_module_root: bool,
) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let text = code;
    let relative: Vec<String> = children.iter().map(|c| format!("{c}::")).collect();
    let starts = ["crate::", "super::", "self::"]
        .into_iter()
        .chain(relative.iter().map(String::as_str));
    for start in starts {
        let mut from = 0;
        while let Some(pos) = text[from..].find(start) {
            let at = from + pos;
            from = at + start.len();
            let before = text[..at].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            // The statement this path is in: a module root's own `pub use` re-exports are skipped.
            let line_start = text[..at].rfind(['\n', ';', '{', '}']).map_or(0, |i| i + 1);
            let statement = text[line_start..at].trim();
            if is_module_root && is_reexport(statement) {
                continue;
            }
            let mut base: Vec<String> = Vec::new();
            let mut rest = &text[at..];
            if start == "crate::" {
                rest = &rest["crate::".len()..];
            } else if start == "self::" {
                base = here.to_vec();
                rest = &rest["self::".len()..];
            } else if start != "super::" {
                // A child module of the file's own, named relatively.
                base = here.to_vec();
            } else {
                // `super` is the parent of the file's module (a/b.rs is a::b, a/mod.rs is a).
                base = here.to_vec();
                while let Some(r) = rest.strip_prefix("super::") {
                    base.pop();
                    rest = r;
                }
            }
            expand(rest, &base, &mut out);
        }
    }
    out
}

/// Appends the paths of `rest` (what follows `crate::` or the `super::`s) under `base`.
fn expand(rest: &str, base: &[String], out: &mut Vec<Vec<String>>) {
    let mut path = base.to_vec();
    let mut chars = rest.char_indices().peekable();
    let mut ident = String::new();
    while let Some((i, c)) = chars.next() {
        if c.is_alphanumeric() || c == '_' {
            ident.push(c);
        } else if c == ':' && rest[i..].starts_with("::") {
            chars.next();
            if !ident.is_empty() {
                path.push(std::mem::take(&mut ident));
            }
            if rest[i + 2..].starts_with('{') {
                // A group: each top-level entry under the path so far.
                let inner = &rest[i + 3..];
                let mut depth = 0;
                let mut entry_start = 0;
                for (j, d) in inner.char_indices() {
                    match d {
                        '{' => depth += 1,
                        '}' if depth == 0 => {
                            expand(inner[entry_start..j].trim(), &path, out);
                            return;
                        }
                        '}' => depth -= 1,
                        ',' if depth == 0 => {
                            expand(inner[entry_start..j].trim(), &path, out);
                            entry_start = j + 1;
                        }
                        _ => {}
                    }
                }
                return;
            }
        } else {
            break;
        }
    }
    if !ident.is_empty() && ident != "self" {
        path.push(ident);
    }
    out.push(path);
}

/// The file that defines what `path` names: the deepest module on it, and, when the next
/// segment is an item a module root re-exports from a child (`pub use child::…`), the child.
fn resolve(
    path: &[String],
    modules: &BTreeMap<Vec<String>, PathBuf>,
    texts: &BTreeMap<Vec<String>, String>,
) -> Option<Vec<String>> {
    let mut depth = path.len();
    while !modules.contains_key(&path[..depth]) {
        depth = depth.checked_sub(1)?;
    }
    let mut module = path[..depth].to_vec();
    // Follow re-exports of the next segment (an item) into children, as far as they go.
    if let Some(item) = path.get(depth) {
        for _ in 0..4 {
            let Some(text) = texts.get(&module) else {
                break;
            };
            let Some(child) = reexporting_child(text, item, &module, modules, texts) else {
                break;
            };
            module = child;
        }
    }
    Some(module)
}

/// The child module of `module` that `text` (its code) re-exports `item` from, if any.
fn reexporting_child(
    text: &str,
    item: &str,
    module: &[String],
    modules: &BTreeMap<Vec<String>, PathBuf>,
    texts: &BTreeMap<Vec<String>, String>,
) -> Option<Vec<String>> {
    for statement in text.split(';') {
        let s = statement.trim();
        let Some(rest) = ["pub use ", "pub(crate) use ", "pub(super) use "]
            .iter()
            .find_map(|p| s.strip_prefix(p))
        else {
            continue;
        };
        let rest = rest.trim_start_matches("self::");
        let child_name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let mut child = module.to_vec();
        child.push(child_name);
        let Some(child_text) = texts.get(&child) else {
            continue;
        };
        let named = rest.contains(&format!("{{{item}"))
            || rest.contains(&format!(" {item},"))
            || rest.contains(&format!(" {item}}}"))
            || rest.contains(&format!(", {item}"))
            || rest.ends_with(&format!("::{item}"));
        let glob = rest.ends_with("::*") && defines(child_text, item);
        if (named || glob) && modules.contains_key(&child) {
            return Some(child);
        }
    }
    None
}

/// Whether `code` declares `item` after the keyword `kw` (`fn `, `struct `, …).
fn declares(code: &str, kw: &str, item: &str) -> bool {
    code.match_indices(&format!("{kw}{item}")).any(|(i, _)| {
        code[i + kw.len() + item.len()..]
            .chars()
            .next()
            .is_none_or(|c| !(c.is_alphanumeric() || c == '_'))
    })
}

/// Whether `code` defines `item` itself (a fn, type, trait, const or static; not a module or
/// a re-export).
fn defines_item(code: &str, item: &str) -> bool {
    [
        "fn ", "struct ", "enum ", "trait ", "type ", "const ", "static ",
    ]
    .iter()
    .any(|kw| declares(code, kw, item))
}

/// Whether `code` defines `item` at some level (an item, a module or a re-export of it).
fn defines(code: &str, item: &str) -> bool {
    defines_item(code, item)
        || declares(code, "mod ", item)
        || code.contains(&format!("pub use {item}"))
}

/// The first cycle in `edges` (as module paths), if any.
fn find_cycle(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Option<Vec<Vec<String>>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit(
        node: &Vec<String>,
        edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        marks: &mut BTreeMap<Vec<String>, Mark>,
        stack: &mut Vec<Vec<String>>,
    ) -> Option<Vec<Vec<String>>> {
        marks.insert(node.clone(), Mark::Open);
        stack.push(node.clone());
        for next in edges.get(node).into_iter().flatten() {
            match marks.get(next).copied().unwrap_or(Mark::New) {
                Mark::Open => {
                    let from = stack.iter().position(|n| n == next).unwrap();
                    let mut cycle = stack[from..].to_vec();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                Mark::New => {
                    if let Some(c) = visit(next, edges, marks, stack) {
                        return Some(c);
                    }
                }
                Mark::Done => {}
            }
        }
        stack.pop();
        marks.insert(node.clone(), Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for node in edges.keys() {
        if marks.get(node).copied().unwrap_or(Mark::New) == Mark::New {
            let mut stack = Vec::new();
            if let Some(c) = visit(node, edges, &mut marks, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

/// The import graph of one crate's files.
fn import_graph(src: &Path) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let modules = modules(src);
    let texts: BTreeMap<Vec<String>, String> = modules
        .iter()
        .map(|(m, p)| {
            let code = code_of(&std::fs::read_to_string(p).unwrap());
            (m.clone(), inline_modules_resolved(&code))
        })
        .collect();
    let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    for (module, path) in &modules {
        let name = path.file_name().unwrap().to_string_lossy();
        let is_module_root = name == "mod.rs" || name == "lib.rs" || name == "main.rs";
        let code = &texts[module];
        let children: Vec<String> = modules
            .keys()
            .filter(|m| m.len() == module.len() + 1 && m.starts_with(module))
            .map(|m| m[module.len()].clone())
            .collect();
        for named in named_paths(code, module, &children, is_module_root) {
            if let Some(target) = resolve(&named, &modules, &texts)
                && &target != module
                // A module's own ancestors are where it is declared; naming them is not a loop
                // unless they import it back, which their own edges show. An item the crate
                // root defines itself (a helper in lib.rs) is an import of the root.
                && !(target.is_empty()
                    && named.len() <= 1
                    && !named.first().is_some_and(|item| defines_item(&texts[&target], item)))
            {
                edges.entry(module.clone()).or_default().insert(target);
            }
        }
        edges.entry(module.clone()).or_default();
    }
    edges
}

/// A module path as the report names it.
fn module_name(m: &[String]) -> String {
    if m.is_empty() {
        "(crate root)".to_string()
    } else {
        m.join("::")
    }
}

/// A cycle as the report says it: its files in order, and for a parent and its child that
/// import each other, that the parent is used as a toolbox.
fn describe(cycle: &[Vec<String>]) -> String {
    let names: Vec<String> = cycle.iter().map(|m| module_name(m)).collect();
    let path = names.join(" → ");
    if let [a, b, _] = cycle {
        let (parent, child) = if a.len() < b.len() { (a, b) } else { (b, a) };
        if child.len() == parent.len() + 1 && child.starts_with(parent) {
            return format!(
                "{path} (parent ↔ child: {} uses its child {}, which imports from it back; move what the child needs into a named module)",
                module_name(parent),
                module_name(child)
            );
        }
    }
    path
}

#[test]
fn no_two_files_of_a_crate_import_each_other_directly_or_through_a_loop() {
    let mut report = Vec::new();
    let mut files = 0;
    let mut imports = 0;
    for krate in CRATES {
        let src = repo().join(krate).join("src");
        let mut graph = import_graph(&src);
        report.extend(without_known_back_imports(krate, &mut graph));
        files += graph.len();
        imports += graph.values().map(BTreeSet::len).sum::<usize>();
        if let Some(cycle) = find_cycle(&graph) {
            report.push(format!("{krate}: {}", describe(&cycle)));
        }
    }
    eprintln!("{files} files, {imports} imports between files");
    assert!(files > 150, "only {files} files found: the scan is broken");
    assert!(
        imports > 300,
        "only {imports} imports resolved: the scan is broken"
    );
    assert!(report.is_empty(), "import loops:\n{}", report.join("\n"));
}

/// A crate's `src/` of `files` (path, text) in a fresh temporary folder named after `name`.
fn scratch_crate(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-arch-{name}-{}", std::process::id()));
    for (path, text) in files {
        let file = dir.join(path);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(file, text).unwrap();
    }
    dir
}

#[test]
fn the_loop_finder_finds_a_loop_between_two_files() {
    let dir = scratch_crate(
        "two",
        &[
            ("lib.rs", "pub mod a;\npub mod b;\n"),
            ("a/mod.rs", "mod inner;\npub use inner::*;\n"),
            ("a/inner.rs", "use crate::b::Thing;\npub struct Other;\n"),
            ("b.rs", "use crate::a::Other;\npub struct Thing;\n"),
        ],
    );
    let cycle = find_cycle(&import_graph(&dir));
    std::fs::remove_dir_all(&dir).ok();
    let cycle = cycle.expect("b → a::inner → b is a loop (through a's re-export)");
    let names: BTreeSet<String> = cycle.iter().map(|m| m.join("::")).collect();
    assert!(
        names.contains("b") && names.contains("a::inner"),
        "{names:?}"
    );
}

#[test]
fn a_parent_and_its_child_importing_each_other_through_relative_paths_is_a_loop() {
    // The parent calls its child by a relative path, the child imports the parent's helper.
    let dir = scratch_crate(
        "relative",
        &[
            ("lib.rs", "pub mod a;\n"),
            (
                "a/mod.rs",
                "mod child;\npub fn helper() {}\npub fn run() { child::work() }\n",
            ),
            (
                "a/child.rs",
                "use super::helper;\npub fn work() { helper() }\n",
            ),
        ],
    );
    let graph = import_graph(&dir);
    let cycle = find_cycle(&graph);
    // The same through `self::` and `crate::` from the mod.rs.
    for call in ["self::child::work()", "crate::a::child::work()"] {
        std::fs::write(
            dir.join("a/mod.rs"),
            format!("mod child;\npub fn helper() {{}}\npub fn run() {{ {call} }}\n"),
        )
        .unwrap();
        assert!(
            find_cycle(&import_graph(&dir)).is_some(),
            "{call} then super::helper back is a loop"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
    let cycle = cycle.expect("a → a::child → a is a loop");
    let said = describe(&cycle);
    assert!(
        said.contains("parent ↔ child: a uses its child a::child"),
        "{said}"
    );
}

#[test]
fn super_inside_an_inline_module_is_the_file_itself_not_its_parent() {
    // The child's inline test module says `use super::*`: the child, not the parent. Only the
    // same words outside an inline module import the parent.
    let dir = scratch_crate(
        "inline",
        &[
            ("lib.rs", "pub mod a;\n"),
            (
                "a/mod.rs",
                "mod child;\npub fn helper() {}\npub fn run() { child::work() }\n",
            ),
            (
                "a/child.rs",
                "pub fn work() {}\nmod tests { use super::*; fn t() { work() } }\n",
            ),
        ],
    );
    assert!(
        find_cycle(&import_graph(&dir)).is_none(),
        "inline super:: is the file"
    );
    std::fs::write(
        dir.join("a/child.rs"),
        "use super::helper;\npub fn work() { helper() }\nmod tests { use super::*; }\n",
    )
    .unwrap();
    assert!(
        find_cycle(&import_graph(&dir)).is_some(),
        "super:: at file level is the parent"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Whether `m` is in env's configuration layer: the `config` folder, or a task's or a scenario
/// family's `settings.rs` (each keeps its settings in its own folder, `task/<task>/`,
/// `scenario/<family>/`).
fn in_config_layer(m: &[String]) -> bool {
    matches!(m, [first, ..] if first == "config")
        || matches!(m, [room, _, settings]
            if (room == "scenario" || room == "task") && settings == "settings")
}

/// The imports that leave a layer: (from, to) for each file of the layer that imports a file
/// outside it.
fn imports_leaving(
    graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
    in_layer: fn(&[String]) -> bool,
) -> Vec<String> {
    graph
        .iter()
        .filter(|(from, _)| in_layer(from))
        .flat_map(|(from, to)| {
            to.iter()
                .filter(|t| !in_layer(t))
                .map(move |t| format!("{} imports {}", module_name(from), module_name(t)))
        })
        .collect()
}

#[test]
fn env_config_with_the_tasks_and_families_settings_is_a_leaf_that_imports_no_behaviour() {
    // Why a layer and not the folder alone: `EnvConfig` names each task's and family's settings
    // type, which lives in its folder, so `config` imports those `settings.rs` files and they
    // import `config`'s checks. Neither may import the env's behaviour (cell, sim, robot, a
    // task's rules, a family's draw or hook), so every other room can import the configuration.
    let graph = import_graph(&repo().join("env").join("src"));
    let settings_in = |room: &str| {
        graph
            .keys()
            .filter(|m| in_config_layer(m) && m[0] == room)
            .count()
    };
    assert!(
        settings_in("scenario") >= 5,
        "the scenario families' settings.rs files were not found"
    );
    assert!(
        settings_in("task") >= 1,
        "the place task's settings.rs was not found"
    );
    let leaving = imports_leaving(&graph, in_config_layer);
    assert!(
        leaving.is_empty(),
        "the config layer imports behaviour:\n{}",
        leaving.join("\n")
    );
}

#[test]
fn an_import_from_config_into_a_familys_behaviour_leaves_the_layer() {
    let dir = scratch_crate(
        "layer",
        &[
            ("lib.rs", "pub mod config;\npub mod scenario;\n"),
            ("config/mod.rs", "pub mod env_config;\n"),
            (
                "config/env_config.rs",
                "use crate::scenario::nudge::settings::Nudge;\npub struct EnvConfig;\n",
            ),
            ("scenario/mod.rs", "pub mod nudge;\n"),
            (
                "scenario/nudge/mod.rs",
                "pub mod settings;\npub mod draw;\n",
            ),
            ("scenario/nudge/settings.rs", "pub struct Nudge;\n"),
            ("scenario/nudge/draw.rs", "pub fn draw() {}\n"),
        ],
    );
    let within = imports_leaving(&import_graph(&dir), in_config_layer);
    std::fs::write(
        dir.join("config/env_config.rs"),
        "use crate::scenario::nudge::draw::draw;\npub struct EnvConfig;\n",
    )
    .unwrap();
    let leaving = imports_leaving(&import_graph(&dir), in_config_layer);
    std::fs::remove_dir_all(&dir).ok();
    assert!(within.is_empty(), "{within:?}");
    assert_eq!(
        leaving,
        vec!["config::env_config imports scenario::nudge::draw".to_string()]
    );
}

/// The files that register the tasks and may name each one: the list of tasks and what the
/// shared code reads of each (`TaskSpec`), the rules' arms and the planner's residual
/// interfaces. (The table of every task's controls, `planner/src/controls/mod.rs`, names none:
/// each task's rows are in its folder.) ARCHITECTURE.md's "Where to add things" lists them.
const TASK_REGISTRATION: [&str; 3] = [
    "env/src/config/task.rs",
    "env/src/task/tasks.rs",
    "planner/src/tasks.rs",
];

/// Whether `path` (relative to a crate's `src/`) is inside a task's own folder: a folder named
/// after the task (`task/place/`, `place/`).
fn in_a_task_folder(path: &Path, tasks: &[&str]) -> bool {
    let mut folders = path.iter().rev().skip(1);
    folders.any(|f| tasks.iter().any(|t| f == *t))
}

/// The places in the `src/` files of `crates` (under `root`) outside a task's folder and the
/// registration files that ask which task it is: that name a task of `TaskKind` (`TaskKind::
/// Place`; `TaskKind::ALL` names none). Unit-test modules (from `#[cfg(test)]` on) are left out.
fn task_checks_outside_task_folders(root: &Path, crates: &[&str], tasks: &[&str]) -> Vec<String> {
    let mut found = Vec::new();
    for krate in crates {
        let src = root.join(krate).join("src");
        for path in modules(&src).into_values() {
            let rel = path.strip_prefix(&src).unwrap();
            let shown = Path::new(krate).join("src").join(rel);
            let shown = shown.strip_prefix("./").unwrap_or(&shown);
            if in_a_task_folder(rel, tasks)
                || TASK_REGISTRATION.iter().any(|r| shown == Path::new(r))
            {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let code = code_of(&text);
            let code = code.split("#[cfg(test)]").next().unwrap_or_default();
            for (n, line) in code.lines().enumerate() {
                let names_a_task = line.match_indices("TaskKind::").any(|(i, m)| {
                    line[i + m.len()..].starts_with(|c: char| c.is_ascii_uppercase())
                        && !line[i + m.len()..].starts_with("ALL")
                });
                if names_a_task {
                    found.push(format!("{}:{}: {}", shown.display(), n + 1, line.trim()));
                }
            }
        }
    }
    found
}

#[test]
fn no_code_outside_a_tasks_folder_asks_which_task_it_is() {
    let tasks: Vec<&str> = fairgrasp_env::TaskKind::ALL.map(|t| t.name()).to_vec();
    let found = task_checks_outside_task_folders(repo(), &CRATES, &tasks);
    assert!(
        found.is_empty(),
        "code outside a task's folder asks which task it is (read what the task registers \
         instead — its TaskSpec, its controls' rows, its residual interface — or move the code \
         into the task's folder; see ARCHITECTURE.md, \"Where to add things\"):\n{}",
        found.join("\n")
    );
}

#[test]
fn a_task_named_outside_its_folder_is_found_with_its_file_and_line() {
    let dir = scratch_crate(
        "task-check",
        &[
            ("env/src/lib.rs", "pub mod sim;\npub mod task;\n"),
            (
                "env/src/sim/scene.rs",
                "// TaskKind::Place in a comment is no check\nfn f(k: TaskKind) -> bool {\n    \
                 k == TaskKind::Place\n}\nconst A: [TaskKind; 2] = TaskKind::ALL;\n",
            ),
            (
                "env/src/task/place/rules.rs",
                "fn g() -> TaskKind { TaskKind::Place }\n",
            ),
            (
                "env/src/sim/world.rs",
                "fn h() {}\n#[cfg(test)]\nmod tests { fn t() { let _ = TaskKind::Lift; } }\n",
            ),
        ],
    );
    let found = task_checks_outside_task_folders(&dir, &["env"], &["lift", "place"]);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(
        found,
        vec!["env/src/sim/scene.rs:3: k == TaskKind::Place".to_string()]
    );
}
