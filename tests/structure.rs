//! Structure of the workspace: no file-level import cycles inside any crate (a file that
//! names an item of another file through `crate::` or `super::` depends on it; references
//! to a file's own ancestors — its `mod.rs` / `lib.rs` — do not count), and the sweep
//! pipeline lives in a library, not in the binary.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Module = Vec<String>;

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Module path of a source file relative to the crate's `src/`.
fn module_of(src: &Path, file: &Path) -> Module {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Module = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// `crate::a::b` / `super::x` paths named in `text` (comments and test modules dropped).
fn paths(text: &str) -> Vec<(bool, Vec<String>)> {
    let code: String = text
        .split("#[cfg(test)]")
        .next()
        .unwrap()
        .lines()
        .map(|l| l.split("//").next().unwrap())
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = Vec::new();
    for root in ["crate::", "super::"] {
        let mut rest = code.as_str();
        while let Some(i) = rest.find(root) {
            let before = rest[..i].chars().last();
            rest = &rest[i + root.len()..];
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let mut segs = vec![];
            let mut tail = rest;
            loop {
                let end = tail
                    .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .unwrap_or(tail.len());
                if end == 0 {
                    break;
                }
                segs.push(tail[..end].to_string());
                tail = &tail[end..];
                match tail.strip_prefix("::") {
                    Some(t) => tail = t,
                    None => break,
                }
            }
            out.push((root == "super::", segs));
        }
    }
    out
}

fn import_graph(src: &Path) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut files = vec![];
    rust_files(src, &mut files);
    let modules: BTreeMap<Module, PathBuf> = files
        .iter()
        .map(|f| (module_of(src, f), f.clone()))
        .collect();
    let mut graph = BTreeMap::new();
    for (m, f) in &modules {
        let is_mod_file = matches!(
            f.file_name().unwrap().to_str().unwrap(),
            "mod.rs" | "lib.rs" | "main.rs"
        );
        let mut deps = BTreeSet::new();
        for (is_super, segs) in paths(&std::fs::read_to_string(f).unwrap()) {
            let mut full: Module = if is_super {
                let mut base = m.clone();
                if !is_mod_file {
                    base.pop();
                }
                base.pop();
                let mut s = segs.as_slice();
                while s.first().is_some_and(|x| x == "super") {
                    base.pop();
                    s = &s[1..];
                }
                base.extend(s.iter().cloned());
                base
            } else {
                segs
            };
            while !full.is_empty() && !modules.contains_key(&full) {
                full.pop();
            }
            let ancestor = full.len() < m.len() && m.starts_with(&full);
            if !full.is_empty() && &full != m && !ancestor {
                deps.insert(full);
            }
        }
        graph.insert(m.clone(), deps);
    }
    graph
}

/// A cycle in `graph`, if any (depth-first search with colours).
fn find_cycle(graph: &BTreeMap<Module, BTreeSet<Module>>) -> Option<Vec<Module>> {
    fn visit(
        v: &Module,
        g: &BTreeMap<Module, BTreeSet<Module>>,
        colour: &mut BTreeMap<Module, u8>,
        stack: &mut Vec<Module>,
    ) -> Option<Vec<Module>> {
        colour.insert(v.clone(), 1);
        stack.push(v.clone());
        for w in &g[v] {
            match colour.get(w).copied().unwrap_or(0) {
                0 => {
                    if let Some(c) = visit(w, g, colour, stack) {
                        return Some(c);
                    }
                }
                1 => {
                    let at = stack.iter().position(|x| x == w).unwrap();
                    return Some(stack[at..].to_vec());
                }
                _ => {}
            }
        }
        stack.pop();
        colour.insert(v.clone(), 2);
        None
    }
    let mut colour = BTreeMap::new();
    for v in graph.keys() {
        if colour.get(v).copied().unwrap_or(0) == 0
            && let Some(c) = visit(v, graph, &mut colour, &mut vec![])
        {
            return Some(c);
        }
    }
    None
}

#[test]
fn no_crate_has_a_file_level_import_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for krate in [
        "env", "models", "training", "analysis", "pipeline", "python", ".",
    ] {
        let graph = import_graph(&root.join(krate).join("src"));
        assert!(graph.len() > 1, "{krate}: no modules found");
        if let Some(cycle) = find_cycle(&graph) {
            let names: Vec<String> = cycle.iter().map(|m| m.join("/")).collect();
            panic!("{krate}: import cycle {}", names.join(" → "));
        }
    }
}

#[test]
fn the_cycle_finder_finds_a_planted_cycle() {
    let m = |s: &str| vec![s.to_string()];
    let mut g: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    g.insert(m("a"), [m("b")].into());
    g.insert(m("b"), [m("c")].into());
    g.insert(m("c"), [m("a")].into());
    g.insert(m("d"), [m("a")].into());
    assert_eq!(find_cycle(&g).map(|c| c.len()), Some(3));
    g.get_mut(&m("c")).unwrap().clear();
    assert_eq!(find_cycle(&g), None);
    // `super::` from a leaf file names a sibling; `crate::` names a module path.
    let p = paths("use super::gae::x; fn f() { crate::ppo::loss::y(); } // crate::no");
    assert_eq!(p.len(), 2);
}

#[test]
fn the_sweep_pipeline_is_a_library_and_the_binary_does_not_run_stages() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let job = std::fs::read_to_string(root.join("pipeline/src/job.rs")).unwrap();
    assert!(job.contains("pub fn run_job("));
    let sweep = std::fs::read_to_string(root.join("src/cmd/sweep.rs")).unwrap();
    for stage_call in [
        "cmd::train::run",
        "cmd::eval::run",
        "cmd::record::",
        "cmd::export::run",
    ] {
        assert!(
            !sweep.contains(stage_call),
            "src/cmd/sweep.rs calls {stage_call}"
        );
    }
    assert!(sweep.contains("chronocooked_pipeline::run_job"));
}
