//! The house rule, checked: every file of `src/` imports only from its own layer or the
//! layers below it, and no files import each other in a circle (README, "Layout").
//!
//! An import is any path `crate::a::b...` in the code (a `use` or written inline), a
//! `super::...` path, or a child module named in a folder's `mod.rs` (`pub use child::X`).
//! It is resolved to the file that defines the deepest module it names: `crate::scenario::
//! Sample` is `src/scenario/mod.rs`, `crate::scenario::read::X` is `src/scenario/read.rs`.
//! Unit tests (`#[cfg(test)]` modules at the end of a file) may use what they like and are
//! not read.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, from the ground up, and the top-level modules of `src/` in each. The kernels
/// (a crate of their own) are below all of them.
const LAYERS: &[(&str, &[&str])] = &[
    (
        "data model",
        &["rng", "dist", "qmc", "stability", "scenario"],
    ),
    (
        "physics",
        &["slope", "terrain", "rocks", "control", "reference", "shape"],
    ),
    ("Monte Carlo engine", &["sampling", "sweep"]),
    ("files", &["output", "table"]),
    (
        "statistics",
        &[
            "stats",
            "report",
            "weighting",
            "sensitivity",
            "compare",
            "study",
            "boundary",
            "envelope",
            "exceedance",
            "site",
        ],
    ),
    ("the sweep run", &["run"]),
    ("pictures", &["plot", "scene", "animate", "view"]),
    ("commands", &["commands"]),
];

/// A source file and the module path it defines (`["scenario", "read"]`).
struct File {
    path: PathBuf,
    module: Vec<String>,
    text: String,
}

fn files(dir: &Path, module: &[String], out: &mut Vec<File>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        let name = p.file_stem().unwrap().to_string_lossy().to_string();
        if p.is_dir() {
            let mut m = module.to_vec();
            m.push(name);
            files(&p, &m, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            if module.is_empty() && (name == "lib" || name == "main") {
                continue;
            }
            let mut m = module.to_vec();
            if name != "mod" {
                m.push(name);
            }
            let text = std::fs::read_to_string(&p).unwrap();
            out.push(File {
                path: p,
                module: m,
                text,
            });
        }
    }
}

/// `text` without comments, string literals and the unit tests at its end.
fn code_of(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    let mut out = String::with_capacity(text.len());
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if b[i] == b'\'' && b.get(i + 2) == Some(&b'\'') {
            // A character literal such as '"' or '{'.
            i += 3;
        } else if b[i] == b'\''
            && b.get(i + 1) == Some(&b'\\')
            && let Some(end) = text[i + 2..].find('\'')
        {
            i += end + 3;
        } else {
            out.push(b[i] as char);
            i += 1;
        }
    }
    out
}

fn ident_at(s: &str, i: usize) -> (&str, usize) {
    let end = s[i..]
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(s.len(), |k| i + k);
    (&s[i..end], end)
}

/// The module paths named after a `prefix::` at `i` of `code` (the paths of a `{...}`
/// group each), appended to `prefix`.
fn paths_at(code: &str, mut i: usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    let mut path = prefix;
    loop {
        let rest = &code[i..];
        let skipped = rest.len() - rest.trim_start().len();
        i += skipped;
        if code[i..].starts_with('{') {
            // A group: each item at depth 1 is a path of its own.
            let mut depth = 0;
            let mut start = i + 1;
            for (k, c) in code[i..].char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' | ',' if depth == 1 => {
                        if !code[start..i + k].trim().is_empty() {
                            paths_at(code, start, path.clone(), out);
                        }
                        start = i + k + 1;
                        if c == '}' {
                            return;
                        }
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            return;
        }
        let (id, end) = ident_at(code, i);
        if id.is_empty() {
            break;
        }
        if id == "super" {
            // `super::super::x`: one folder further up.
            path.pop();
        } else {
            path.push(id.to_string());
        }
        if code[end..].starts_with("::") {
            i = end + 2;
        } else {
            break;
        }
    }
    out.push(path);
}

/// Every module path `file` names (from the crate root).
fn imports(file: &File, children: &BTreeSet<String>) -> Vec<Vec<String>> {
    let code = code_of(&file.text);
    let mut out = Vec::new();
    let parent: Vec<String> = if file.path.ends_with("mod.rs") {
        file.module.clone()
    } else {
        file.module[..file.module.len().saturating_sub(1)].to_vec()
    };
    let bytes = code.as_bytes();
    let mut i = 0;
    while i < code.len() {
        let boundary = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if boundary && code[i..].starts_with("crate::") {
            paths_at(&code, i + 7, Vec::new(), &mut out);
        } else if boundary && code[i..].starts_with("super::") {
            paths_at(&code, i + 7, parent.clone(), &mut out);
        } else if boundary && bytes[i].is_ascii_lowercase() && file.path.ends_with("mod.rs") {
            // A child of this folder named by a path (`pub use child::X`).
            let (id, end) = ident_at(&code, i);
            if children.contains(id) && code[end..].starts_with("::") {
                let mut m = file.module.clone();
                m.push(id.to_string());
                paths_at(&code, end + 2, m, &mut out);
            }
            i = end.max(i + 1);
            continue;
        }
        i += 1;
    }
    out
}

#[test]
fn arrows_only_go_down_and_no_file_imports_another_in_a_circle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &[], &mut all);
    let by_module: BTreeMap<Vec<String>, usize> = all
        .iter()
        .enumerate()
        .map(|(k, f)| (f.module.clone(), k))
        .collect();
    let layer_of = |top: &str| {
        LAYERS
            .iter()
            .position(|(_, ms)| ms.contains(&top))
            .unwrap_or_else(|| panic!("src/{top}: in no layer of LAYERS (add it where it belongs)"))
    };
    let mut edges: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); all.len()];
    let mut up = Vec::new();
    for (k, f) in all.iter().enumerate() {
        let children: BTreeSet<String> = by_module
            .keys()
            .filter(|m| m.len() == f.module.len() + 1 && m.starts_with(&f.module))
            .map(|m| m.last().unwrap().clone())
            .collect();
        for p in imports(f, &children) {
            // The deepest module of the path that is a file of src/.
            let Some(target) = (1..=p.len())
                .rev()
                .find_map(|n| by_module.get(&p[..n]).copied())
            else {
                continue;
            };
            if target == k {
                continue;
            }
            let (from, to) = (layer_of(&f.module[0]), layer_of(&all[target].module[0]));
            if to > from {
                up.push(format!(
                    "{} ({}) -> {} ({}): {}",
                    f.path.strip_prefix(&src).unwrap().display(),
                    LAYERS[from].0,
                    all[target].path.strip_prefix(&src).unwrap().display(),
                    LAYERS[to].0,
                    p.join("::")
                ));
            }
            edges[k].insert(target);
        }
    }
    assert!(
        up.is_empty(),
        "imports from a lower layer to a higher one:\n{}",
        up.join("\n")
    );
    // A circle: a file that reaches itself (depth-first search, colouring).
    let mut state = vec![0u8; all.len()];
    let mut stack: Vec<usize> = Vec::new();
    fn visit(
        k: usize,
        edges: &[BTreeSet<usize>],
        state: &mut [u8],
        stack: &mut Vec<usize>,
    ) -> Option<Vec<usize>> {
        state[k] = 1;
        stack.push(k);
        for &t in &edges[k] {
            if state[t] == 1 {
                let at = stack.iter().position(|&s| s == t).unwrap();
                return Some(stack[at..].to_vec());
            }
            if state[t] == 0
                && let Some(c) = visit(t, edges, state, stack)
            {
                return Some(c);
            }
        }
        stack.pop();
        state[k] = 2;
        None
    }
    for k in 0..all.len() {
        if state[k] == 0
            && let Some(circle) = visit(k, &edges, &mut state, &mut stack)
        {
            let names: Vec<String> = circle
                .iter()
                .map(|&c| {
                    all[c]
                        .path
                        .strip_prefix(&src)
                        .unwrap()
                        .display()
                        .to_string()
                })
                .collect();
            panic!(
                "files that import each other in a circle: {}",
                names.join(" -> ")
            );
        }
    }
}
