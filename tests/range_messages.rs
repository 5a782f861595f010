//! Every range check states its real bounds. Each number of every shipped preset (with all its
//! defaults written out) and of every shipped recipe is set far outside any range; the refusal's
//! `must be in …` gives the bounds the check claims. Then the number is set just outside each
//! finite end: the refusal must name the field, the value and both bounds; and at the end itself
//! (or just inside an open one) no refusal may say it is outside them. A number that no value
//! can make refused, or one refused without stated bounds, must be listed below with the reason.

use std::collections::BTreeSet;

use fairgrasp_env::config::{EnvConfig, presets};
use fairgrasp_policy::recipe::Recipe;

/// Numbers with no range of their own (a count or seed of any size, its type refusing a
/// negative), and why; a name ending in `.` covers the table.
const UNBOUNDED: [(&str, &str); 4] = [
    ("seed", "any seed is a seed"),
    (
        "eval_every",
        "how often a run evaluates: any count of updates",
    ),
    (
        "critic_warmup_updates",
        "updates that train only the critic: any count",
    ),
    (
        "control.tuned.",
        "the record of how a setting was found, read by people, never by the env",
    ),
];

/// Numbers whose rule joins several fields (stated in the message), and the rule's words.
const RULES_OF_SEVERAL_FIELDS: [(&str, &str); 3] = [
    ("task.place.grasp_height", "must hold the cube"),
    ("task.stack.grasp_height", "must hold the cube"),
    ("task.staged", "reach + grasp + lift must be positive"),
];

/// Refusals that state no bounds and need none: the order of a pair's ends, and a negative
/// number in an unsigned field (its type is its lower bound).
const NOT_ABOUT_BOUNDS: [&str; 2] = ["min must not exceed max", "expected u"];

/// One number of a TOML document: its dotted path (`a.b[1]`) and whether it is an integer.
#[derive(Clone, Debug)]
struct Leaf {
    path: Vec<Step>,
    integer: bool,
}

#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

impl Leaf {
    /// `a.b[1]`.
    fn name(&self) -> String {
        let mut out = String::new();
        for step in &self.path {
            match step {
                Step::Key(k) if out.is_empty() => out += k,
                Step::Key(k) => out += &format!(".{k}"),
                Step::Index(i) => out += &format!("[{i}]"),
            }
        }
        out
    }

    /// The field as a refusal names it: without the index of a pair's end.
    fn field_without_index(&self) -> String {
        let name = self.name();
        match name.rfind('[') {
            Some(i) => name[..i].to_string(),
            None => name,
        }
    }

    /// A pair's end (`[0]` or `[1]` of a two-number array).
    fn end_of_pair(&self, doc: &toml::Table) -> Option<usize> {
        let Some(Step::Index(i)) = self.path.last() else {
            return None;
        };
        let parent = Leaf {
            path: self.path[..self.path.len() - 1].to_vec(),
            integer: false,
        };
        match get(doc, &parent.path) {
            Some(toml::Value::Array(a)) if a.len() == 2 => Some(*i),
            _ => None,
        }
    }
}

fn get<'a>(doc: &'a toml::Table, path: &[Step]) -> Option<&'a toml::Value> {
    let (Step::Key(first), rest) = path.split_first()? else {
        return None;
    };
    let mut value = doc.get(first)?;
    for step in rest {
        value = match (step, value) {
            (Step::Key(k), toml::Value::Table(t)) => t.get(k)?,
            (Step::Index(i), toml::Value::Array(a)) => a.get(*i)?,
            _ => return None,
        };
    }
    Some(value)
}

fn set(doc: &mut toml::Table, path: &[Step], new: toml::Value) {
    let (Step::Key(first), rest) = path.split_first().unwrap() else {
        unreachable!("a leaf's path starts with a key")
    };
    let mut value = doc.get_mut(first).unwrap();
    for step in rest {
        value = match (step, value) {
            (Step::Key(k), toml::Value::Table(t)) => t.get_mut(k).unwrap(),
            (Step::Index(i), toml::Value::Array(a)) => &mut a[*i],
            _ => unreachable!("the path was read from this document"),
        };
    }
    *value = new;
}

fn leaves(value: &toml::Value, path: Vec<Step>, out: &mut Vec<Leaf>) {
    match value {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let mut p = path.clone();
                p.push(Step::Key(k.clone()));
                leaves(v, p, out);
            }
        }
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                let mut p = path.clone();
                p.push(Step::Index(i));
                leaves(v, p, out);
            }
        }
        toml::Value::Integer(_) => out.push(Leaf {
            path,
            integer: true,
        }),
        toml::Value::Float(_) => out.push(Leaf {
            path,
            integer: false,
        }),
        _ => {}
    }
}

/// An interval as a refusal states it: `[0, 0.05]`, `(0, inf)` or `1..=64`.
#[derive(Clone, Debug, PartialEq)]
struct Stated {
    text: String,
    low: f64,
    high: f64,
    low_open: bool,
    high_open: bool,
}

/// The interval after `must be in ` in `message`, if any.
fn stated_bounds(message: &str) -> Option<Stated> {
    ["in ", "inside "].iter().find_map(|marker| {
        message
            .match_indices(marker)
            .find_map(|(i, m)| interval(&message[i + m.len()..]))
    })
}

/// The interval `rest` starts with, if any.
fn interval(rest: &str) -> Option<Stated> {
    let word = rest.split_whitespace().next()?;
    if let Some((low, high)) = word.split_once("..=")
        && low.parse::<f64>().is_ok()
    {
        let high = high.trim_end_matches([',', ';', ')']);
        return Some(Stated {
            text: format!("{low}..={high}"),
            low: low.parse().ok()?,
            high: high.parse().ok()?,
            low_open: false,
            high_open: false,
        });
    }
    let low_open = rest.starts_with('(');
    if !low_open && !rest.starts_with('[') {
        return None;
    }
    let close = rest.find([']', ')'])?;
    let (low, high) = rest[1..close].split_once(", ")?;
    Some(Stated {
        text: rest[..=close].to_string(),
        low: low.parse().ok()?,
        high: high.parse().ok()?,
        low_open,
        high_open: rest.as_bytes()[close] == b')',
    })
}

/// What a loader says of a document: None when it loads.
type Loader<'a> = dyn Fn(&toml::Table) -> Option<String> + 'a;

fn number(leaf: &Leaf, v: f64) -> toml::Value {
    if leaf.integer {
        toml::Value::Integer(v as i64)
    } else {
        toml::Value::Float(v)
    }
}

fn shown(leaf: &Leaf, v: f64) -> String {
    if leaf.integer {
        format!("{}", v as i64)
    } else {
        format!("{v:?}")
    }
}

/// A value just outside `end` (below the low end or above the high end).
fn just_outside(leaf: &Leaf, end: f64, open: bool, below: bool) -> f64 {
    let step = if leaf.integer {
        1.0
    } else {
        1e-6 * end.abs().max(1.0)
    };
    match (open, below) {
        (true, _) => end,
        (false, true) => end - step,
        (false, false) => end + step,
    }
}

/// A value at `end` when it is closed, or just inside it when it is open.
fn just_inside(leaf: &Leaf, end: f64, open: bool, below: bool) -> f64 {
    if !open {
        return end;
    }
    let step = if leaf.integer {
        1.0
    } else {
        1e-6 * end.abs().max(1.0)
    };
    if below { end + step } else { end - step }
}

/// One number of a document, set to chosen values and loaded.
struct Probe<'a> {
    doc: &'a toml::Table,
    leaf: &'a Leaf,
    load: &'a Loader<'a>,
    /// `a.b[1]`.
    name: String,
    /// The field as a refusal names it (`a.b`).
    field: String,
    /// Which end of a pair the number is, if it is one.
    pair_end: Option<usize>,
}

impl Probe<'_> {
    /// What the loader says with the number set to `v` (with `both_ends`, a pair's two ends, so
    /// that they stay in order).
    fn load_with(&self, v: f64, both_ends: bool) -> Option<String> {
        let mut d = self.doc.clone();
        let mut path = self.leaf.path.clone();
        if both_ends && self.pair_end.is_some() {
            for end in [0, 1] {
                *path.last_mut().unwrap() = Step::Index(end);
                set(&mut d, &path, number(self.leaf, v));
            }
        }
        set(&mut d, &self.leaf.path, number(self.leaf, v));
        (self.load)(&d)
    }

    /// The bounds the refusals of far values state; else the problem (None when the number is
    /// listed as unbounded or as one of a rule of several fields).
    fn stated(&self) -> Result<Stated, Option<String>> {
        // Far beyond any range, and within an f32 (some recipe numbers are f32).
        let far: &[f64] = if self.leaf.integer {
            &[1e12, -1.0]
        } else {
            &[1e30, -1e30]
        };
        let refusals: Vec<String> = far
            .iter()
            .filter_map(|v| self.load_with(*v, true))
            .filter(|m| !NOT_ABOUT_BOUNDS.iter().any(|words| m.contains(words)))
            .collect();
        if let Some(stated) = refusals.iter().find_map(|m| stated_bounds(m)) {
            return Ok(stated);
        }
        let name = &self.name;
        if refusals.is_empty() {
            return Err(listed(&UNBOUNDED, &self.field)
                .is_none()
                .then(|| format!("{name}: accepts {far:?}, and is not listed as unbounded")));
        }
        match listed(&RULES_OF_SEVERAL_FIELDS, &self.field) {
            Some(words)
                if refusals
                    .iter()
                    .all(|m| m.contains(words) || !m.contains(&self.field)) =>
            {
                Err(None)
            }
            _ => Err(Some(format!(
                "{name}: refused without stated bounds: {refusals:?}"
            ))),
        }
    }

    /// Just outside `end`, a refusal naming the field, the value and `stated`; at `end` (just
    /// inside it when open), no refusal saying it is outside. The problem, if any.
    fn check_end(&self, stated: &Stated, end: f64, open: bool, below: bool) -> Option<String> {
        let (leaf, name, field) = (self.leaf, &self.name, &self.field);
        let outside = just_outside(leaf, end, open, below);
        let value = shown(leaf, outside);
        match self.load_with(outside, false) {
            None => {
                return Some(format!(
                    "{name} = {value} is accepted, outside {}",
                    stated.text
                ));
            }
            // A negative count is refused by its unsigned type, which states the bound 0.
            Some(m) if leaf.integer && outside < 0.0 && m.contains("expected u") => {}
            Some(m)
                if !(names_field(&m, field)
                    && names_value(&m, leaf, outside)
                    && m.contains(&stated.text)) =>
            {
                return Some(format!(
                    "{name} = {value}: the refusal does not name the field, the value and {}: {m}",
                    stated.text
                ));
            }
            Some(_) => {}
        }
        let inside = just_inside(leaf, end, open, below);
        let m = self.load_with(inside, false)?;
        (names_field(&m, field) && stated_bounds(&m).as_ref() == Some(stated)).then(|| {
            format!(
                "{name} = {}: inside {} but refused as outside: {m}",
                shown(leaf, inside),
                stated.text
            )
        })
    }
}

/// The reason `field` is listed in `table` (a name ending in `.` covers the table), if it is.
fn listed(table: &'static [(&'static str, &'static str)], field: &str) -> Option<&'static str> {
    table
        .iter()
        .find(|(f, _)| *f == field || (f.ends_with('.') && field.starts_with(f)))
        .map(|(_, r)| *r)
}

/// Walks one leaf; returns a problem, if any.
fn walk_leaf(doc: &toml::Table, leaf: &Leaf, load: &Loader) -> Option<String> {
    let probe = Probe {
        doc,
        leaf,
        load,
        name: leaf.name(),
        field: leaf.field_without_index(),
        pair_end: leaf.end_of_pair(doc),
    };
    let stated = match probe.stated() {
        Ok(stated) => stated,
        Err(problem) => return problem,
    };
    let ends = [
        (stated.low, stated.low_open, true),
        (stated.high, stated.high_open, false),
    ];
    // A pair's low end is its first number's, its high end its second's.
    ends.into_iter()
        .enumerate()
        .filter(|(i, (end, _, _))| end.is_finite() && probe.pair_end.is_none_or(|e| e == *i))
        .find_map(|(_, (end, open, below))| probe.check_end(&stated, end, open, below))
}

/// Whether `message` names `field` (`ppo.gamma`), as its path or as `ppo: gamma`.
fn names_field(message: &str, field: &str) -> bool {
    let as_section = field
        .rsplit_once('.')
        .map(|(table, key)| format!("{table}: {key} ="));
    [" =", "["]
        .iter()
        .any(|next| message.contains(&format!("{field}{next}")))
        || as_section.is_some_and(|s| message.contains(&s))
}

/// Whether `message` names `v` as `leaf` holds it (`0.5`, `1e-6`, `0`, `0.0`).
fn names_value(message: &str, leaf: &Leaf, v: f64) -> bool {
    message.contains(&shown(leaf, v)) || message.contains(&format!("{v}"))
}

/// Walks every number of `doc`; returns the problems and how many numbers had stated bounds.
fn walk(doc: &toml::Table, load: &Loader, seen: &mut BTreeSet<String>) -> Vec<String> {
    let mut all = Vec::new();
    leaves(&toml::Value::Table(doc.clone()), Vec::new(), &mut all);
    all.iter()
        .filter(|leaf| seen.insert(leaf.name()))
        .filter_map(|leaf| walk_leaf(doc, leaf, load))
        .collect()
}

#[test]
fn every_preset_number_is_refused_outside_the_bounds_its_message_states() {
    let load = |d: &toml::Table| {
        EnvConfig::from_toml_str(&toml::to_string(d).unwrap())
            .err()
            .map(|e| e.to_string())
    };
    let mut seen = BTreeSet::new();
    let mut problems = Vec::new();
    for (name, _, _) in presets::PRESETS {
        let full = presets::load(name).unwrap().to_toml();
        let doc: toml::Table = toml::from_str(&full).unwrap();
        problems.extend(walk(&doc, &load, &mut seen));
    }
    assert!(seen.len() > 80, "only {} numbers walked", seen.len());
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_recipe_number_is_refused_outside_the_bounds_its_message_states() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("range-messages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("recipe.toml");
    let load = |d: &toml::Table| {
        std::fs::write(&file, toml::to_string(d).unwrap()).unwrap();
        Recipe::from_toml_file(&file).err().map(|e| e.to_string())
    };
    let mut seen = BTreeSet::new();
    let mut problems = Vec::new();
    for name in fairgrasp_policy::recipes::names() {
        let path = format!("assets/experiments/{name}.toml");
        let recipe = Recipe::from_toml_file(std::path::Path::new(&path)).unwrap();
        // Every field written out, defaults too.
        let doc: toml::Table = toml::from_str(&toml::to_string(&recipe).unwrap()).unwrap();
        problems.extend(walk(&doc, &load, &mut seen));
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(seen.len() > 20, "only {} numbers walked", seen.len());
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// What every end of every list is set to: none of them is a value any field may take.
const HOSTILE_ENDS: [f64; 5] = [1e308, -1e308, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// Every list of numbers in `value` (a range `[min, max]`, a position, the home joints), as its
/// path, its length and whether it holds integers.
fn number_lists(value: &toml::Value, path: Vec<Step>, out: &mut Vec<(Vec<Step>, usize, bool)>) {
    match value {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let mut p = path.clone();
                p.push(Step::Key(k.clone()));
                number_lists(v, p, out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|v| v.is_integer() || v.is_float()) => {
            out.push((path, a.len(), a.iter().all(|v| v.is_integer())));
        }
        _ => {}
    }
}

/// Every range and every list of a fixed length, walked in every shipped preset with its
/// defaults written out (so every list of every table, present and future, that a preset of
/// its task carries: the settings have no list of their ranges apart from themselves): each
/// end set to 1e308, -1e308, NaN, inf and -inf, and the list made one element longer (a
/// number, then a string) and one shorter, must be refused naming the field (the sampler
/// panicked on `task.stack.base_radius = [0.3, 1e308]`; `fixture_friction = [0.3, 1.2, 9.0]`
/// was read as `[0.3, 1.2]`). A far end is refused stating bounds whose ends are finite.
#[test]
fn every_list_refuses_hostile_ends_and_other_lengths_naming_the_field() {
    let load = |d: &toml::Table| {
        EnvConfig::from_toml_str(&toml::to_string(d).unwrap())
            .err()
            .map(|e| e.to_string())
    };
    let mut seen = BTreeSet::new();
    let mut problems = Vec::new();
    for (preset, _, _) in presets::PRESETS {
        let full = presets::load(preset).unwrap().to_toml();
        let doc: toml::Table = toml::from_str(&full).unwrap();
        let mut lists = Vec::new();
        number_lists(&toml::Value::Table(doc.clone()), Vec::new(), &mut lists);
        for (path, len, integer) in lists {
            let leaf = Leaf {
                path: path.clone(),
                integer,
            };
            let field = leaf.name();
            if !seen.insert(field.clone()) {
                continue;
            }
            let Some(toml::Value::Array(list)) = get(&doc, &path) else {
                unreachable!("the path was read from this document")
            };
            let mut expect = |d: &toml::Table, what: String, bounded: bool| match load(d) {
                None => problems.push(format!("{preset}: {field} {what}: accepted")),
                Some(m) if !names_field(&m, &field) && !m.contains(&format!("{field}:")) => {
                    problems.push(format!(
                        "{preset}: {field} {what}: the refusal does not name the field: {m}"
                    ))
                }
                Some(m)
                    if bounded
                        && stated_bounds(&m)
                            .is_none_or(|b| !b.low.is_finite() || !b.high.is_finite()) =>
                {
                    problems.push(format!(
                        "{preset}: {field} {what}: no finite bounds stated: {m}"
                    ))
                }
                Some(_) => {}
            };
            for i in 0..len {
                let mut end = path.clone();
                end.push(Step::Index(i));
                for v in HOSTILE_ENDS {
                    let mut d = doc.clone();
                    set(&mut d, &end, toml::Value::Float(v));
                    // A far end of a list of floats states finite bounds: the low end pulled
                    // down, the high end pushed up (the other way round a pair is disordered).
                    let bounded =
                        !integer && ((v == 1e308 && i + 1 == len) || (v == -1e308 && i == 0));
                    expect(&d, format!("[{i}] = {v}"), bounded);
                }
                if integer {
                    for v in [i64::MAX, i64::MIN] {
                        let mut d = doc.clone();
                        set(&mut d, &end, toml::Value::Integer(v));
                        expect(&d, format!("[{i}] = {v}"), false);
                    }
                }
            }
            let lengths: [(Vec<toml::Value>, &str); 3] = [
                (
                    list.iter().chain(list.last()).cloned().collect(),
                    "one element longer",
                ),
                (
                    list.iter()
                        .cloned()
                        .chain([toml::Value::String("junk".into())])
                        .collect(),
                    "one string longer",
                ),
                (list[..len - 1].to_vec(), "one element shorter"),
            ];
            for (other, what) in lengths {
                let mut d = doc.clone();
                set(&mut d, &path, toml::Value::Array(other));
                expect(&d, what.to_string(), false);
            }
        }
    }
    for walked in [
        "randomization.radius",
        "randomization.angle",
        "randomization.friction",
        "randomization.mass_scale",
        "randomization.nudge.distance",
        "randomization.nudge.step",
        "randomization.camera_offset.xyz",
        "task.place.fixture_radius",
        "task.place.fixture_angle",
        "task.place.grip_tilt",
        "task.place.fixture_friction",
        "task.stack.base_radius",
        "task.stack.base_angle",
        "arm.home_joints",
    ] {
        assert!(seen.contains(walked), "{walked} was not walked: {seen:?}");
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// The examples, refused with the field, the value, the bounds and their reason.
#[test]
fn a_range_the_sampler_cannot_draw_from_is_refused_with_its_bound_and_reason() {
    for (table, key) in [
        ("task.stack", "base_radius"),
        ("task.place", "fixture_radius"),
        ("randomization", "radius"),
    ] {
        let kind = table.strip_prefix("task.").unwrap_or("lift");
        let text = format!("[task]\nkind = \"{kind}\"\n[{table}]\n{key} = [0.3, 1e308]\n");
        let e = EnvConfig::from_toml_str(&text).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "{table}.{key} = [0.3, 1e308]: both ends must be in [0, 1] m (the FR3 reaches \
                 0.622 m from its shoulder: no mount reaches a cube 1 m from the base)"
            )
        );
    }
    let e = EnvConfig::from_toml_str(
        "[task]\nkind = \"place\"\n[task.place]\nfixture_friction = [0.3, 1.2, 9.0]\n",
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "task.place.fixture_friction = [0.3, 1.2, 9.0]: has 3 elements: it must hold exactly 2"
    );
    let e = EnvConfig::from_toml_str(
        "[task]\nkind = \"stack\"\n[task.stack]\nbase_radius = [0.25, 0.4, \"junk\", {a = 1}]\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("task.stack.base_radius = [0.25, 0.4, \"junk\", { a = 1 }]: has 4 elements and mixes a number, a string and a table"),
        "{e}"
    );
}

/// A training config's `[env]` table is laid over its preset and read by the same rules: a list
/// of another length and a range past its bounds are refused naming `env.<field>`.
#[test]
fn a_training_configs_env_table_is_read_by_the_same_rules() {
    use fairgrasp_policy::recipe::env::with_env_table;
    let stack = presets::load("stack").unwrap();
    for (table, message) in [
        (
            "[task.stack]\nbase_radius = [0.25, 0.4, 0.5]\n",
            "env.task.stack.base_radius = [0.25, 0.4, 0.5]: has 3 elements: it must hold exactly 2",
        ),
        (
            "[task.stack]\nbase_radius = [0.3, 1e308]\n",
            "env.task.stack.base_radius = [0.3, 1e308]: both ends must be in [0, 1] m",
        ),
        (
            "[task.place]\ngrip_tilt = [0.07, 0.17]\n",
            "[task.place] is the place task's table, and this config's task is stack",
        ),
    ] {
        let overrides: toml::Table = toml::from_str(table).unwrap();
        let e = with_env_table(stack.clone(), Some(&overrides))
            .unwrap_err()
            .to_string();
        assert!(e.contains(message), "{table}: {e}");
    }
}

#[test]
fn the_stated_bounds_are_read_as_written() {
    let s = stated_bounds("physics.dt = 0.1: must be in (0, 0.05] s").unwrap();
    assert_eq!(
        (s.low, s.high, s.low_open, s.high_open),
        (0.0, 0.05, true, false)
    );
    let s = stated_bounds("n_envs = 0: must be in 1..=64").unwrap();
    assert_eq!((s.low, s.high, s.text.as_str()), (1.0, 64.0, "1..=64"));
    let s = stated_bounds("x = [-4.0, 1.0]: both ends must be in [-3.141592653589793, inf) rad")
        .unwrap();
    assert!(s.high.is_infinite() && s.high_open && s.low == -std::f64::consts::PI);
    assert_eq!(stated_bounds("x = 1: must be finite"), None);
}
