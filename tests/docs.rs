//! The documentation's links: every relative link of README, the guide (`docs/`),
//! ARCHITECTURE, RESULTS, BENCHMARKS and every study's README names a file or folder that
//! exists, every guide page is reachable from the README, and RESULTS is a findings page that
//! links every study.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The relative link targets `](target)` of a Markdown text (anchors dropped).
fn relative_links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("](") {
        rest = &rest[i + 2..];
        let Some(end) = rest.find(')') else { break };
        let target = rest[..end].split('#').next().unwrap_or_default();
        let external = ["http:", "https:", "mailto:"]
            .iter()
            .any(|p| target.starts_with(p));
        if !target.is_empty() && !external && !target.contains(char::is_whitespace) {
            out.push(target.to_string());
        }
        rest = &rest[end..];
    }
    out
}

fn pages() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = [
        "README.md",
        "ARCHITECTURE.md",
        "RESULTS.md",
        "BENCHMARKS.md",
    ]
    .iter()
    .map(|f| root().join(f))
    .collect();
    v.extend(markdown_in("docs"));
    v.extend(markdown_in("docs/tutorials"));
    v.extend(study_pages());
    v
}

/// The Markdown pages directly in the repository folder `dir`, sorted.
fn markdown_in(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    v.sort();
    v
}

/// The README of every study folder under `results/` (each study's detail).
fn study_pages() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("results"))
        .unwrap()
        .flatten()
        .map(|e| e.path().join("README.md"))
        .filter(|p| p.is_file())
        .collect();
    v.sort();
    v
}

#[test]
fn results_is_a_findings_page_that_links_every_study() {
    let results = std::fs::read_to_string(root().join("RESULTS.md")).unwrap();
    let lines = results.lines().count();
    assert!(
        lines <= 200,
        "RESULTS.md has {lines} lines (at most 200: detail goes to results/<study>/README.md)"
    );
    let links = relative_links(&results);
    let studies = study_pages();
    assert!(studies.len() >= 10, "{} study READMEs", studies.len());
    for page in studies {
        let rel = page
            .strip_prefix(root())
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        assert!(links.contains(&rel), "RESULTS.md does not link {rel}");
    }
}

#[test]
fn every_relative_link_of_the_documentation_resolves() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let dir = page.parent().unwrap_or(Path::new("."));
        for link in relative_links(&text) {
            if !dir.join(&link).exists() {
                broken.push(format!("{}: {link}", page.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links: {broken:#?}");
}

#[test]
fn every_guide_page_is_linked_from_the_readme_and_the_readme_fits_on_a_few_screens() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.lines().count() <= 250,
        "README.md has {} lines",
        readme.lines().count()
    );
    let links = relative_links(&readme);
    for page in pages()
        .iter()
        .filter(|p| p.starts_with(root().join("docs")))
    {
        let name = page.file_name().unwrap().to_str().unwrap();
        if name == "README.md" || name == "paper-protocol.md" {
            continue;
        }
        let want = page
            .strip_prefix(root())
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        assert!(links.contains(&want), "README does not link {want}");
    }
    // The eight journeys, each one click from the README.
    let tutorials: Vec<&String> = links
        .iter()
        .filter(|l| l.starts_with("docs/tutorials/"))
        .collect();
    assert_eq!(tutorials.len(), 8, "{tutorials:?}");
}

#[test]
fn the_link_reader_finds_relative_links_only() {
    let links = relative_links(
        "[a](docs/x.md) [b](https://e.org) [c](#top) [d](../y.md#s) ![i](img/p.png)",
    );
    assert_eq!(links, ["docs/x.md", "../y.md", "img/p.png"]);
}

#[test]
fn the_committed_cli_reference_is_the_one_the_parser_generates() {
    let out = crate::common::run_ok(&["cli-reference"]);
    let committed = std::fs::read_to_string(root().join("docs/cli.md")).unwrap();
    assert!(
        committed == out,
        "docs/cli.md is stale: regenerate it with `chronocooked cli-reference > docs/cli.md`"
    );
    for command in [
        "train",
        "eval",
        "verify",
        "mechanisms",
        "fingerprint",
        "sweep",
    ] {
        assert!(
            out.contains(&format!("## `chronocooked {command}`")),
            "{command}"
        );
    }
}

/// The repository paths a Markdown text names in backticks (`env/src/registry.rs`,
/// `results/paper-core/`): tokens whose first folder is one of the repository's own, with any
/// `:line` or `#anchor` suffix dropped; tokens with placeholders (`<study>`, `*`, `…`) and
/// output folders (`lab-out/`, `runs/`) are not paths of the repository.
fn named_paths(text: &str) -> Vec<String> {
    const ROOTS: [&str; 18] = [
        "env", "models", "training", "analysis", "present", "paper", "pipeline", "python", "src",
        "tests", "sweeps", "results", "docs", "scripts", "zoo", "examples", "bench", ".ci",
    ];
    let mut out = Vec::new();
    for token in text.split('`').skip(1).step_by(2) {
        if token.contains(char::is_whitespace) {
            continue;
        }
        let path = token
            .split([':', '#'])
            .next()
            .unwrap_or_default()
            .trim_end_matches(['.', ',', ';', ')']);
        let Some((first, _)) = path.split_once('/') else {
            continue;
        };
        let placeholder = path.contains(['<', '>', '*', '{', '}', '…', '[', ']', '$']);
        if ROOTS.contains(&first) && !placeholder {
            out.push(path.to_string());
        }
    }
    out
}

#[test]
fn the_path_reader_keeps_repository_paths_only() {
    let paths = named_paths(
        "`env/src/registry.rs:73` `results/<study>/` `lab-out/demo` `cargo test` \
         `present/src/report/` `docs/cli.md#train` `x`",
    );
    assert_eq!(
        paths,
        ["env/src/registry.rs", "present/src/report/", "docs/cli.md"]
    );
}

#[test]
fn every_path_the_documentation_names_exists() {
    let mut stale = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for path in named_paths(&text) {
            if !root().join(&path).exists() {
                stale.push(format!("{}: {path}", page.display()));
            }
        }
    }
    assert!(stale.is_empty(), "paths that do not exist: {stale:#?}");
}
