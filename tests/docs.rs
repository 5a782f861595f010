//! The docs cite only what exists: every repository path written in backticks in the READMEs and
//! `docs/*.md` (`env/src/task/reward/staged.rs`, `assets/configs/sector.toml`, `assets/policies/<name>/`)
//! and every relative link (with its `#anchor`, a heading of the target page) resolves. Files
//! move; this test names the page and the stale path when they do. Also: the README stays two
//! pages, shows the test command CI runs, and the docs index links every page.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The pages checked: both READMEs and every `docs/*.md`.
fn pages() -> Vec<String> {
    let mut pages = vec!["README.md".to_string(), "README.zh-CN.md".to_string()];
    let mut docs: Vec<String> = std::fs::read_dir(repo().join("docs"))
        .expect("docs/ exists")
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

fn read(page: &str) -> String {
    let path = repo().join(page);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The lines outside fenced code blocks (code is run by tests/guide.rs, not read here), with
/// their line numbers (from 1).
fn prose_lines(text: &str) -> Vec<(usize, &str)> {
    let mut fenced = false;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push((i + 1, line));
        }
    }
    out
}

/// The inline code spans of a line (`` `x` `` and ``` ``x`` ```).
fn code_spans(line: &str) -> Vec<&str> {
    let bytes = line.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] != b'`' {
            i += 1;
            continue;
        }
        let ticks = bytes[i..].iter().take_while(|&&b| b == b'`').count();
        let start = i + ticks;
        let mut j = start;
        let mut end = None;
        while j < bytes.len() {
            if bytes[j] == b'`' {
                let run = bytes[j..].iter().take_while(|&&b| b == b'`').count();
                if run == ticks {
                    end = Some(j);
                    break;
                }
                j += run;
            } else {
                j += 1;
            }
        }
        match end {
            Some(e) => {
                spans.push(line[start..e].trim());
                i = e + ticks;
            }
            None => break,
        }
    }
    spans
}

/// File endings that make a backticked word a file path.
const EXTENSIONS: &[&str] = &[
    "rs", "toml", "md", "urdf", "py", "sh", "txt", "json", "csv", "png", "gif", "ipynb", "bpk",
    "lock", "so",
];

/// Folders the docs name as what a command writes (relative to where it runs), not as sources.
const OUTPUT_ROOTS: &[&str] = &[
    "runs",
    "report",
    "my_report",
    "my_first_report",
    "final_report",
    "first_report",
    "hard_report",
    "cmp",
    "look",
    "plots",
    "episodes",
    "checkpoints",
    "target",
];

/// Whether a backticked word is a path in this repository: it has a `/`, no spaces, ends in a
/// folder's `/` or a file ending, and does not start outside the repository (`../`, `/`) or in a
/// command's output folder.
fn is_repo_path(span: &str) -> bool {
    if span.is_empty()
        || span.contains(char::is_whitespace)
        || !span.contains('/')
        || span.starts_with("../")
        || span.starts_with('/')
        || span.contains("://")
    {
        return false;
    }
    let first = span.split('/').next().unwrap();
    if OUTPUT_ROOTS.contains(&first) {
        return false;
    }
    let last = span.rsplit('/').next().unwrap();
    span.ends_with('/')
        || last
            .rsplit_once('.')
            .is_some_and(|(stem, ext)| !stem.is_empty() && EXTENSIONS.contains(&ext))
}

/// `a/{b,c}.rs` → `a/b.rs`, `a/c.rs`.
fn expand_braces(path: &str) -> Vec<String> {
    match (path.find('{'), path.find('}')) {
        (Some(open), Some(close)) if open < close => path[open + 1..close]
            .split(',')
            .flat_map(|alt| expand_braces(&format!("{}{alt}{}", &path[..open], &path[close + 1..])))
            .collect(),
        _ => vec![path.to_string()],
    }
}

/// Whether `name` matches `pattern`, where one `<…>` or `*` stands for any text.
fn matches(pattern: &str, name: &str) -> bool {
    let (prefix, suffix) = match (pattern.find('<'), pattern.find('>'), pattern.find('*')) {
        (Some(open), Some(close), _) if open < close => (&pattern[..open], &pattern[close + 1..]),
        (_, _, Some(star)) => (&pattern[..star], &pattern[star + 1..]),
        _ => return pattern == name,
    };
    name.len() >= prefix.len() + suffix.len() && name.starts_with(prefix) && name.ends_with(suffix)
}

/// Whether a path (relative to `root`, with `<…>` or `*` standing for any name) exists.
fn exists(root: &Path, path: &str) -> bool {
    let mut candidates = vec![root.to_path_buf()];
    for segment in path.trim_end_matches('/').split('/') {
        let wild = segment.contains('*') || segment.contains('<');
        candidates = candidates
            .iter()
            .flat_map(|dir| -> Vec<PathBuf> {
                if !wild {
                    return vec![dir.join(segment)];
                }
                std::fs::read_dir(dir)
                    .map(|entries| {
                        entries
                            .filter_map(Result::ok)
                            .filter(|e| matches(segment, &e.file_name().to_string_lossy()))
                            .map(|e| e.path())
                            .collect()
                    })
                    .unwrap_or_default()
            })
            .collect();
    }
    candidates.iter().any(|p| p.exists())
}

/// GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a page's headings (a repeated heading gets `-1`, `-2`, … as on GitHub).
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut out = BTreeSet::new();
    for (_, line) in prose_lines(text) {
        let Some(heading) = line.strip_prefix('#') else {
            continue;
        };
        let base = slug(heading.trim_start_matches('#'));
        let n = seen.entry(base.clone()).or_insert(0);
        out.insert(if *n == 0 {
            base.clone()
        } else {
            format!("{base}-{n}")
        });
        *n += 1;
    }
    out
}

/// The targets of a line's Markdown links and images, `[text](target)`.
fn link_targets(line: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let Some(close) = after.find(')') else { break };
        out.push(after[..close].split_whitespace().next().unwrap_or(""));
        rest = &after[close..];
    }
    out
}

/// Every cited path and link of `text` (a page at `page`, relative to `root`) that does not
/// resolve, and how many were checked.
fn stale_citations(root: &Path, page: &str, text: &str) -> (Vec<String>, usize) {
    let mut stale = Vec::new();
    let mut checked = 0;
    let dir = Path::new(page).parent().unwrap_or(Path::new(""));
    for (n, line) in prose_lines(text) {
        for span in code_spans(line) {
            if !is_repo_path(span) {
                continue;
            }
            for path in expand_braces(span) {
                checked += 1;
                if !exists(root, &path) {
                    stale.push(format!("{page}:{n}: `{path}` does not exist"));
                }
            }
        }
        for target in link_targets(line) {
            if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (file, anchor) = target.split_once('#').unwrap_or((target, ""));
            let path = if file.is_empty() {
                root.join(page)
            } else {
                root.join(dir).join(file)
            };
            if !path.exists() {
                stale.push(format!(
                    "{page}:{n}: link `{target}` points at a missing file"
                ));
                continue;
            }
            if !anchor.is_empty() && path.extension().is_some_and(|e| e == "md") {
                let text = std::fs::read_to_string(&path).unwrap();
                if !anchors(&text).contains(anchor) {
                    stale.push(format!(
                        "{page}:{n}: link `{target}`: no heading with that anchor"
                    ));
                }
            }
        }
    }
    (stale, checked)
}

#[test]
fn every_path_and_link_in_the_docs_exists() {
    let mut stale = Vec::new();
    let mut checked = 0;
    for page in pages() {
        let (s, n) = stale_citations(repo(), &page, &read(&page));
        stale.extend(s);
        checked += n;
    }
    assert!(
        checked >= 150,
        "only {checked} citations found: is the detector broken?"
    );
    assert!(stale.is_empty(), "stale citations:\n{}", stale.join("\n"));
}

#[test]
fn a_moved_file_and_a_broken_link_are_caught() {
    let text = "Rewards in `env/src/reward.rs`, presets in `assets/configs/sector.toml`, \
                policies in `assets/policies/<name>/`, the guide [here](GUIDE.md#2-the-scene-friction-mass-and-the-physics-step), \
                a page [gone](nowhere.md), an anchor [gone](GUIDE.md#no-such-heading), \
                output `runs/x/metrics.csv`, a phrase `fk/ik`.\n\
                ```\n`env/src/in_a_fence.rs`\n```\n";
    let (stale, checked) = stale_citations(repo(), "docs/example.md", text);
    assert_eq!(checked, 6, "{stale:?}");
    assert_eq!(stale.len(), 3, "{stale:?}");
    assert!(stale[0].contains("`env/src/reward.rs`"), "{stale:?}");
    assert!(stale[1].contains("nowhere.md"), "{stale:?}");
    assert!(stale[2].contains("no-such-heading"), "{stale:?}");
}

#[test]
fn headings_give_githubs_anchors() {
    let text = "# Title\n## API, observation, action, reward\n### 1. Collisions before the arm moves\n\
                ## `fairgrasp compare`\n## Notes\n## Notes\n";
    let a = anchors(text);
    for expected in [
        "title",
        "api-observation-action-reward",
        "1-collisions-before-the-arm-moves",
        "fairgrasp-compare",
        "notes",
        "notes-1",
    ] {
        assert!(a.contains(expected), "{expected} not in {a:?}");
    }
}

#[test]
fn both_readmes_are_two_pages() {
    for page in ["README.md", "README.zh-CN.md"] {
        let lines = read(page).lines().count();
        assert!(
            lines <= 200,
            "{page} has {lines} lines; the rest belongs in docs/"
        );
    }
}

#[test]
fn ci_runs_the_readmes_test_command() {
    let command = "cargo test --workspace --locked --features fairgrasp/train";
    for page in ["README.md", "README.zh-CN.md"] {
        assert!(
            read(page).lines().any(|l| l.starts_with(command)),
            "{page} does not show `{command}`"
        );
    }
    assert!(
        read(".ci/run").lines().any(|l| l.trim() == command),
        ".ci/run does not run the README's `{command}`"
    );
}

#[test]
fn the_docs_index_links_every_page() {
    let index = read("docs/index.md");
    let linked: BTreeSet<&str> = prose_lines(&index)
        .into_iter()
        .flat_map(|(_, line)| link_targets(line))
        .map(|t| t.split('#').next().unwrap())
        .collect();
    for page in pages() {
        let Some(name) = page.strip_prefix("docs/") else {
            continue;
        };
        if name != "index.md" {
            assert!(linked.contains(name), "docs/index.md does not link {name}");
        }
    }
    for page in ["README.md", "README.zh-CN.md"] {
        assert!(
            read(page).contains("(docs/index.md)"),
            "{page} does not link docs/index.md"
        );
    }
}

/// Each page of docs/ written for one concern opens by saying what a reader can do after it.
#[test]
fn every_concern_page_opens_with_what_a_reader_can_do() {
    let older = ["GUIDE.md", "GUIDE.zh-CN.md", "ARCHITECTURE.md", "FR3.md"];
    for page in pages() {
        let Some(name) = page.strip_prefix("docs/") else {
            continue;
        };
        if older.contains(&name) {
            continue;
        }
        let text = read(&page);
        let opening = text
            .lines()
            .skip(1)
            .find(|l| !l.trim().is_empty())
            .unwrap_or("");
        assert!(
            opening.starts_with("**After this page**"),
            "{page} should open with what a reader can do after reading it, not `{opening}`"
        );
    }
}
