//! Structure of the workspace: no import cycles inside any crate, between files or between
//! top-level folders (a file that names an item of another file through `crate::`,
//! `super::`, `self::` or a relative `use child::…` depends on it; references to a file's own ancestors — its `mod.rs` /
//! `lib.rs` — do not count; a name a module re-exports with `pub use` counts as the file
//! that defines it), no crate over 12,000 lines, and the sweep pipeline lives in a library,
//! not in the binary.

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

/// Where a path named in a file starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Root {
    /// `crate::…`: from the crate's root.
    Crate,
    /// `super::…`: from the parent of the file's module.
    Super,
    /// `self::…`, or a relative `use child::…` (2018 paths): from the file's own module.
    /// A relative path whose first segment is no module of the crate (an external crate,
    /// `std`) resolves to the module itself and is dropped.
    Module,
}

/// Crate roots that are never modules of the crate: a `use` that starts with one is no
/// relative path.
const EXTERNAL_ROOTS: [&str; 6] = ["crate", "super", "self", "std", "core", "alloc"];

/// `crate::a::b`, `super::x` and `self::y` paths named in `text`, and the relative paths of
/// its private `use` declarations (`use params::{X, Y}` in `task/mod.rs` names
/// `task::params`; a `pub use` re-export is read by [`re_exports`] instead),
/// comments and test modules dropped; a brace group (`use super::{a::X, b::{Y, Z}}`) gives
/// one path per item.
fn paths(text: &str) -> Vec<(Root, Vec<String>)> {
    let code: String = text
        .split("#[cfg(test)]")
        .next()
        .unwrap()
        .lines()
        .map(|l| l.split("//").next().unwrap())
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = Vec::new();
    for (root, kind) in [
        ("crate::", Root::Crate),
        ("super::", Root::Super),
        ("self::", Root::Module),
    ] {
        for (i, _) in code.match_indices(root) {
            // `x::crate::` is no path root, and `super::super::` is one path, not two.
            let before = code[..i].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut found = vec![];
            use_tree(vec![], &code[i + root.len()..], &mut found);
            out.extend(found.into_iter().map(|segs| (kind, segs)));
        }
    }
    for (i, _) in code.match_indices("use ") {
        // A `use` keyword: at a statement's start (after `;`, `{`, `}`, a newline, or a
        // visibility such as `pub` / `pub(crate)`), not inside a word.
        // A `pub use` re-export is no dependency of the module that re-exports: names used
        // through it count as the file that defines them ([`re_exports`]).
        let before = code[..i].trim_end();
        let visibility = match before.strip_suffix(')') {
            Some(b) => b.rfind('(').map_or(b, |open| &b[..open]).trim_end(),
            None => before,
        };
        let re_export = visibility.ends_with("pub");
        let keyword = !re_export
            && (before.is_empty()
                || before.ends_with([';', '{', '}', ']'])
                || code[..i].ends_with('\n'));
        if !keyword
            || code[..i]
                .chars()
                .last()
                .is_some_and(|c| c.is_alphanumeric() || c == '_')
        {
            continue;
        }
        let tail = code[i + "use ".len()..].trim_start();
        let first = tail
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .next()
            .unwrap_or("");
        if first.is_empty()
            || EXTERNAL_ROOTS.contains(&first)
            || !tail[first.len()..].starts_with("::")
        {
            continue;
        }
        let mut found = vec![];
        use_tree(vec![], tail, &mut found);
        out.extend(found.into_iter().map(|segs| (Root::Module, segs)));
    }
    out
}

/// The paths of the use tree at the start of `tail`, each after `prefix`.
fn use_tree(prefix: Vec<String>, tail: &str, out: &mut Vec<Vec<String>>) {
    let mut segs = prefix;
    let mut tail = tail.trim_start();
    loop {
        if let Some(group) = tail.strip_prefix('{') {
            let mut depth = 0;
            let mut start = 0;
            for (i, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => {
                        use_tree(segs.clone(), &group[start..i], out);
                        return;
                    }
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        use_tree(segs.clone(), &group[start..i], out);
                        start = i + 1;
                    }
                    _ => {}
                }
            }
            return;
        }
        let end = tail
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(tail.len());
        if end == 0 {
            break;
        }
        segs.push(tail[..end].to_string());
        tail = &tail[end..];
        match tail.strip_prefix("::") {
            Some(t) => tail = t.trim_start(),
            None => break,
        }
    }
    if !segs.is_empty() {
        out.push(segs);
    }
}

/// The items a module re-exports (`pub use a::b::{X, Y}` in `m` makes `m::X` a name of
/// `a::b::X`), from every file: full re-exported path → full path of the item. Paths are
/// relative to the module (`crate::`, `super::` and `self::` roots resolved); globs and
/// external crates are left out.
fn re_exports(modules: &BTreeMap<Module, PathBuf>) -> BTreeMap<Module, Module> {
    let mut out = BTreeMap::new();
    for (m, f) in modules {
        let text = std::fs::read_to_string(f).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for (i, _) in code.match_indices("pub use ") {
            let mut found = vec![];
            use_tree(vec![], &code[i + "pub use ".len()..], &mut found);
            for segs in found {
                let (mut base, rest): (Module, &[String]) = match segs.first().map(String::as_str) {
                    Some("crate") => (vec![], &segs[1..]),
                    Some("self") => (m.clone(), &segs[1..]),
                    Some("super") => {
                        let mut b = m.clone();
                        let mut r = segs.as_slice();
                        while r.first().is_some_and(|x| x == "super") {
                            b.pop();
                            r = &r[1..];
                        }
                        (b, r)
                    }
                    _ => (m.clone(), segs.as_slice()),
                };
                let Some(name) = rest.last() else { continue };
                base.extend(rest.iter().cloned());
                let mut probe = base.clone();
                probe.pop();
                if modules.contains_key(&probe) && !probe.is_empty() {
                    let mut alias = m.clone();
                    alias.push(name.clone());
                    if alias != base {
                        out.insert(alias, base);
                    }
                }
            }
        }
    }
    out
}

/// `path` with re-exported names replaced by the items they name (up to 8 hops).
fn through_re_exports(mut path: Module, re: &BTreeMap<Module, Module>) -> Module {
    for _ in 0..8 {
        let hit = (1..=path.len())
            .rev()
            .find_map(|k| re.get(&path[..k]).map(|t| (k, t)));
        match hit {
            Some((k, target)) => {
                let mut p = target.clone();
                p.extend(path[k..].iter().cloned());
                path = p;
            }
            None => break,
        }
    }
    path
}

fn import_graph(src: &Path) -> BTreeMap<Module, BTreeSet<Module>> {
    let mut files = vec![];
    rust_files(src, &mut files);
    let modules: BTreeMap<Module, PathBuf> = files
        .iter()
        .map(|f| (module_of(src, f), f.clone()))
        .collect();
    let re = re_exports(&modules);
    let mut graph = BTreeMap::new();
    for (m, f) in &modules {
        let mut deps = BTreeSet::new();
        for (root, segs) in paths(&std::fs::read_to_string(f).unwrap()) {
            let mut full: Module = if root == Root::Module {
                let mut base = m.clone();
                base.extend(segs.iter().cloned());
                base
            } else if root == Root::Super {
                // `super` is the parent of the module the file defines, whether the file
                // is a leaf (`a/b.rs` = `a::b`) or a folder's `mod.rs` (`a/mod.rs` = `a`).
                let mut base = m.clone();
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
            full = through_re_exports(full, &re);
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

/// The graph of a crate's top-level folders (`src/<folder>/`): an edge wherever a file of
/// one names an item of another. (Top-level files are nodes of the file graph only.)
fn folder_graph(graph: &BTreeMap<Module, BTreeSet<Module>>) -> BTreeMap<Module, BTreeSet<Module>> {
    let folders: BTreeSet<Module> = graph
        .keys()
        .filter(|m| m.len() > 1)
        .map(|m| m[..1].to_vec())
        .collect();
    let folder = |m: &Module| folders.get(&m.iter().take(1).cloned().collect::<Module>());
    let mut out: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (m, deps) in graph {
        let Some(from) = folder(m) else { continue };
        let entry = out.entry(from.clone()).or_default();
        entry.extend(
            deps.iter()
                .filter_map(folder)
                .filter(|d| *d != from)
                .cloned(),
        );
    }
    out
}

/// The first import cycle of the crate whose sources are in `src`, between files or
/// between top-level folders, named for a failure message.
fn cycle_in(src: &Path) -> Option<String> {
    let graph = import_graph(src);
    assert!(graph.len() > 1, "{}: no modules found", src.display());
    let show = |c: Vec<Module>| {
        let names: Vec<String> = c.iter().map(|m| m.join("/")).collect();
        names.join(" → ")
    };
    if let Some(c) = find_cycle(&graph) {
        return Some(format!("file-level import cycle {}", show(c)));
    }
    find_cycle(&folder_graph(&graph)).map(|c| format!("folder-level import cycle {}", show(c)))
}

/// The edges `a → b` of `graph` that lie on a cycle (`b` reaches `a`), as `a → b` text.
fn cyclic_edges(graph: &BTreeMap<Module, BTreeSet<Module>>) -> BTreeSet<String> {
    let reaches = |from: &Module, to: &Module| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(v) = stack.pop() {
            if &v == to {
                return true;
            }
            if seen.insert(v.clone()) {
                stack.extend(graph.get(&v).into_iter().flatten().cloned());
            }
        }
        false
    };
    let mut out = BTreeSet::new();
    for (a, deps) in graph {
        for b in deps {
            if reaches(b, a) {
                out.insert(format!("{} → {}", a.join("/"), b.join("/")));
            }
        }
    }
    out
}

const CRATES: [&str; 9] = [
    "env", "models", "training", "analysis", "present", "paper", "pipeline", "python", ".",
];

#[test]
fn no_crate_has_a_file_level_import_cycle() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for krate in CRATES {
        let graph = import_graph(&root.join(krate).join("src"));
        assert!(graph.len() > 1, "{krate}: no modules found");
        if let Some(cycle) = find_cycle(&graph) {
            let names: Vec<String> = cycle.iter().map(|m| m.join("/")).collect();
            panic!("{krate}: import cycle {}", names.join(" → "));
        }
    }
}

#[test]
fn no_import_cycle_between_top_level_folders() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cyclic = Vec::new();
    for krate in CRATES {
        let graph = folder_graph(&import_graph(&root.join(krate).join("src")));
        let edges = cyclic_edges(&graph);
        if !edges.is_empty() {
            cyclic.push(format!("{krate}: {edges:?}"));
        }
    }
    assert!(
        cyclic.is_empty(),
        "folder edges on cycles: {}",
        cyclic.join(", ")
    );
}

/// The most lines of Rust a crate's `src/` may hold (ARCHITECTURE, "One purpose per crate"):
/// a crate that grows past it has taken a second job.
const MAX_CRATE_LINES: usize = 12_000;

#[test]
fn no_crate_holds_more_than_its_share_of_lines() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut over = Vec::new();
    for krate in CRATES {
        let mut files = Vec::new();
        rust_files(&root.join(krate).join("src"), &mut files);
        let lines: usize = files
            .iter()
            .map(|f| std::fs::read_to_string(f).unwrap().lines().count())
            .sum();
        assert!(lines > 1000, "{krate}: only {lines} lines found");
        if lines > MAX_CRATE_LINES {
            over.push(format!("{krate}: {lines} lines"));
        }
    }
    assert!(over.is_empty(), "over {MAX_CRATE_LINES} lines: {over:?}");
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
}

#[test]
fn paths_are_read_from_use_trees_and_expressions() {
    let p = paths(
        "use super::gae::x; fn f() { crate::ppo::loss::y(); } // crate::no\n\
         use super::super::up::Z; use crate::{a::{b, c::D}, e};",
    );
    let names: Vec<(Root, String)> = p.into_iter().map(|(s, m)| (s, m.join("::"))).collect();
    let expect = [
        (Root::Crate, "ppo::loss::y"),
        (Root::Crate, "a::b"),
        (Root::Crate, "a::c::D"),
        (Root::Crate, "e"),
        (Root::Super, "gae::x"),
        (Root::Super, "super::up::Z"),
    ];
    let expect: Vec<(Root, String)> = expect.iter().map(|(s, m)| (*s, m.to_string())).collect();
    assert_eq!(names, expect);
    // Relative `use` paths and `self::` paths are read too; external crates are not.
    let p = paths(
        "mod params;\nuse params::{MAX, MIN};\npub(crate) use self::inner::K;\n\
         use serde::Serialize; use std::fmt; fn reuse() {}\n",
    );
    let names: Vec<(Root, String)> = p.into_iter().map(|(s, m)| (s, m.join("::"))).collect();
    let expect = [
        (Root::Module, "inner::K"),
        (Root::Module, "params::MAX"),
        (Root::Module, "params::MIN"),
        (Root::Module, "serde::Serialize"),
    ];
    let expect: Vec<(Root, String)> = expect.iter().map(|(s, m)| (*s, m.to_string())).collect();
    assert_eq!(names, expect);
}

/// Writes a small crate source tree (`(path, text)` pairs) into a temporary folder.
fn planted(files: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in files {
        let p = dir.path().join(path);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    dir
}

#[test]
fn a_cycle_through_a_crate_root_re_export_is_caught() {
    // `a.rs` names `b.rs`'s item through the crate root's re-export, `b.rs` names `a.rs`.
    let tree = [
        ("lib.rs", "pub mod a;\npub mod b;\npub use b::{Other, Y};\n"),
        ("a.rs", "pub struct X;\nfn f() -> crate::Y { crate::Y }\n"),
        (
            "b.rs",
            "pub struct Y;\npub struct Other;\nuse crate::a::X;\n",
        ),
    ];
    let dir = planted(&tree);
    let cycle = cycle_in(dir.path()).expect("the cycle through the re-export is found");
    assert!(cycle.contains('a') && cycle.contains('b'), "{cycle}");
    // Naming the crate root's own item is no dependency on `b`.
    let mut acyclic = tree;
    acyclic[1] = ("a.rs", "pub struct X;\nfn f() -> crate::Z { crate::Z }\n");
    acyclic[0] = ("lib.rs", "pub mod a;\npub mod b;\npub struct Z;\n");
    assert_eq!(cycle_in(planted(&acyclic).path()), None);
}

#[test]
fn a_planted_super_cycle_between_leaf_files_is_caught() {
    // `a/x.rs` and `a/y.rs` name each other through `super::` (their parent `a`).
    let tree = [
        ("lib.rs", "pub mod a;\npub mod b;\n"),
        ("a/mod.rs", "pub mod x;\npub mod y;\n"),
        ("a/x.rs", "use super::y::Y;\npub struct X;\n"),
        (
            "a/y.rs",
            "pub struct Y;\npub fn f() -> super::x::X { super::x::X }\n",
        ),
        ("b.rs", "use crate::a::x::X;\n"),
    ];
    let dir = planted(&tree);
    let cycle = cycle_in(dir.path()).expect("the planted cycle is found");
    assert!(cycle.contains("a/x") && cycle.contains("a/y"), "{cycle}");

    // Without the way back there is no cycle; references to ancestors do not count.
    let mut acyclic = tree;
    acyclic[3] = (
        "a/y.rs",
        "pub struct Y;\nuse super::Thing;\nuse crate::a;\n",
    );
    let dir = planted(&acyclic);
    assert_eq!(cycle_in(dir.path()), None);

    // A cycle between two top-level folders through different files is caught too.
    let folders = [
        ("lib.rs", "pub mod p;\npub mod q;\n"),
        ("p/mod.rs", "pub mod one;\npub mod two;\n"),
        ("p/one.rs", "pub struct One;\n"),
        ("p/two.rs", "use crate::q::three::Three;\n"),
        ("q/mod.rs", "pub mod three;\n"),
        ("q/three.rs", "use crate::p::one::One;\npub struct Three;\n"),
    ];
    let dir = planted(&folders);
    let cycle = cycle_in(dir.path()).expect("the folder cycle is found");
    assert!(cycle.starts_with("folder-level"), "{cycle}");
}

#[test]
fn a_planted_cycle_through_a_relative_use_is_caught() {
    // The shape of the env crate's old cycle: `registry` names `task`, `task/mod.rs` names
    // its child `params` by a relative `use`, and `params` names `registry`.
    let tree = [
        ("lib.rs", "pub mod registry;\npub mod task;\n"),
        ("registry.rs", "use crate::task::Task;\npub fn all() {}\n"),
        (
            "task/mod.rs",
            "pub mod params;\nuse params::MAX;\npub struct Task;\n",
        ),
        (
            "task/params.rs",
            "pub const MAX: u8 = 1;\nfn f() { crate::registry::all() }\n",
        ),
    ];
    let dir = planted(&tree);
    let cycle = cycle_in(dir.path()).expect("the cycle through `use params::` is found");
    assert!(
        cycle.contains("task/params") && cycle.contains("registry"),
        "{cycle}"
    );
    // A `pub use` re-export of the child is no dependency of the parent: names used through
    // it count as the child's, which names nothing here.
    let mut re_exported = tree;
    re_exported[2] = (
        "task/mod.rs",
        "pub mod params;\npub use params::MAX;\npub struct Task;\n",
    );
    assert_eq!(cycle_in(planted(&re_exported).path()), None);
    // … but a name used through the re-export is the child's: `registry` naming
    // `crate::task::MAX` depends on `task/params`, which names `registry`.
    re_exported[1] = ("registry.rs", "use crate::task::MAX;\npub fn all() {}\n");
    let cycle = cycle_in(planted(&re_exported).path()).expect("the cycle through the re-export");
    assert!(
        cycle.contains("task/params") && cycle.contains("registry"),
        "{cycle}"
    );
    // With the table moved to the registry, as in the env crate today, there is none.
    let mut acyclic = tree;
    acyclic[3] = ("task/params.rs", "pub const MAX: u8 = 1;\n");
    assert_eq!(cycle_in(planted(&acyclic).path()), None);
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

/// Package → enabled features, as `cargo tree` resolves them for `selection` (`-e edges`).
fn resolved_features(selection: &[&str], edges: &str) -> BTreeMap<String, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = std::process::Command::new(env!("CARGO"))
        .current_dir(root)
        .args([
            "tree", "--locked", "--prefix", "none", "-f", "{p}|{f}", "-e", edges,
        ])
        .args(selection)
        .output()
        .expect("cargo runs");
    assert!(
        out.status.success(),
        "cargo tree {selection:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.replace(" (*)", "").replace(" (proc-macro)", ""))
        .filter_map(|l| {
            let (p, f) = l.split_once('|')?;
            Some((p.trim().to_string(), f.trim().to_string()))
        })
        .collect()
}

/// Every dependency the wheel (`chronocooked-py` alone, as maturin builds it) and the binary
/// (`cargo build --workspace --bins`) share with the test build (`cargo test --workspace`)
/// is resolved with the same features, so neither build compiles burn and the lab a second
/// time. A difference names the package; python/Cargo.toml's unification block fixes it.
#[test]
fn the_wheel_and_the_binary_reuse_the_test_build() {
    let tests = resolved_features(&["--workspace"], "all");
    for (what, selection) in [
        ("the wheel", vec!["-p", "chronocooked-py"]),
        ("the binary", vec!["--workspace"]),
    ] {
        let build = resolved_features(&selection, "normal,build");
        let differ: Vec<String> = build
            .iter()
            .filter(|(p, f)| tests.get(*p).is_some_and(|t| t != *f))
            .map(|(p, f)| format!("{p}: [{f}] vs tests [{}]", tests[p]))
            .collect();
        assert!(
            build.len() > 100,
            "{what}: cargo tree listed {}",
            build.len()
        );
        assert!(
            differ.is_empty(),
            "{what} resolves other features: {differ:#?}"
        );
    }
}
