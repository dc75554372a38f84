//! Every shell command block of the README and the guide (`docs/`, `docs/tutorials/`) runs
//! as written, on the binary this test suite built.
//!
//! A fenced block whose info string starts with `bash`, `sh` or `shell` is run by `bash`
//! (`set -euo pipefail`) with `chronocooked` on the `PATH` (this build's binary) and
//! `cargo run --release --` read as `chronocooked` (`cargo run --release --example NAME --` as
//! the example's binary, `NAME`). A page's blocks run in order in one
//! scratch folder (so a tutorial's later steps read its earlier outputs) that holds links to
//! the repository's own folders (`sweeps/`, `results/`, `zoo/`, `examples/`, …). Two words in
//! the info string say how a long block is run, and nothing else does:
//!
//! * `bash test-args="ARGS"`: ARGS are appended to each `chronocooked` command of the block
//!   (a tiny budget or `--dry-run` for what takes minutes in full);
//! * `bash not-run="REASON"`: not run here, for the reason given (the test script itself;
//!   the wheel's install, which `scripts/test.sh` does before pytest runs the Python blocks).
//!
//! Blocks that show output or a command's synopsis are `text`. The run fails on any error,
//! and if a documented command wrote into the repository's own tracked files.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One fenced shell block of a page.
#[derive(Debug)]
struct Block {
    /// The page, relative to the repository.
    page: String,
    /// 1-based line of the opening fence.
    line: usize,
    /// The info string after the fence (`bash test-args="--dry-run"`).
    info: String,
    /// The block's text.
    text: String,
}

impl Block {
    /// The value of `key="…"` in the info string.
    fn directive(&self, key: &str) -> Option<String> {
        let start = self.info.find(&format!("{key}=\""))? + key.len() + 2;
        let end = self.info[start..].find('"')? + start;
        Some(self.info[start..end].to_string())
    }

    /// The script that runs the block: continuation lines joined, `cargo run --release --`
    /// read as `chronocooked`, the block's test arguments appended to each `chronocooked`
    /// command.
    fn script(&self) -> String {
        let extra = self.directive("test-args");
        let joined = self.text.replace("\\\n", " ");
        let mut out = String::from("set -euo pipefail\n");
        for line in joined.lines() {
            let mut line = example_command(line).replace("cargo run --release --", "chronocooked");
            if let Some(extra) = &extra
                && line.trim_start().starts_with("chronocooked ")
            {
                let (command, comment) = match line.find(" #") {
                    Some(i) => (line[..i].to_string(), line[i..].to_string()),
                    None => (line.clone(), String::new()),
                };
                line = format!("{} {extra}{comment}", command.trim_end());
            }
            out.push_str(&line);
            out.push('\n');
        }
        out
    }
}

/// `cargo run --release --example NAME -- ARGS` read as `NAME ARGS` (the example's binary,
/// built with the tests, is on the `PATH` too); other lines as they are.
fn example_command(line: &str) -> String {
    const RUN: &str = "cargo run --release --example ";
    let Some(at) = line.find(RUN) else {
        return line.to_string();
    };
    let rest = &line[at + RUN.len()..];
    let name = rest.split_whitespace().next().unwrap_or("");
    let args = rest[name.len()..].trim_start();
    let args = args.strip_prefix("--").unwrap_or(args);
    format!("{}{name}{args}", &line[..at])
}

/// The fenced shell blocks of `text` (a page named `page`).
fn shell_blocks(page: &str, text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open: Option<(usize, String, String)> = None;
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        match &mut open {
            None => {
                if let Some(info) = trimmed.strip_prefix("```") {
                    open = Some((i + 1, info.trim().to_string(), String::new()));
                }
            }
            Some((start, info, body)) => {
                if trimmed.starts_with("```") {
                    let shell = ["bash", "sh", "shell"]
                        .contains(&info.split_whitespace().next().unwrap_or(""));
                    if shell {
                        out.push(Block {
                            page: page.to_string(),
                            line: *start,
                            info: info.clone(),
                            text: body.clone(),
                        });
                    }
                    open = None;
                } else {
                    body.push_str(line);
                    body.push('\n');
                }
            }
        }
    }
    out
}

/// README and every Markdown page of the guide, relative to the repository.
fn documented_pages() -> Vec<String> {
    let mut pages = vec!["README.md".to_string()];
    for dir in ["docs", "docs/tutorials"] {
        let Ok(entries) = std::fs::read_dir(root().join(dir)) else {
            continue;
        };
        let mut found: Vec<String> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "md"))
            .map(|p| format!("{dir}/{}", p.file_name().unwrap().to_string_lossy()))
            .collect();
        found.sort();
        pages.extend(found);
    }
    pages
}

/// Tracked files with changes (`git status --porcelain`, untracked files left out), or
/// `None` where git cannot tell (no git, not a checkout).
fn tracked_changes() -> Option<String> {
    let out = Command::new("git")
        .current_dir(root())
        .args(["status", "--porcelain", "--untracked-files=no"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// A scratch folder for one page: empty, with links to the repository's folders that
/// documented commands read.
fn scratch(page: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("doc-commands")
        .join(page.replace('/', "-"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for name in [
        "sweeps", "results", "zoo", "examples", "scripts", "python", "analysis", "docs",
    ] {
        #[cfg(unix)]
        std::os::unix::fs::symlink(root().join(name), dir.join(name)).unwrap();
    }
    dir
}

/// A folder holding `chronocooked` (a link to this build's binary), for the `PATH`.
fn bin_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("doc-commands-bin");
    std::fs::create_dir_all(&dir).unwrap();
    let link = dir.join("chronocooked");
    let _ = std::fs::remove_file(&link);
    #[cfg(unix)]
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_chronocooked"), &link).unwrap();
    // The examples' binaries (`cargo run --example NAME`), built next to the lab's.
    let built = Path::new(env!("CARGO_BIN_EXE_chronocooked"))
        .parent()
        .unwrap()
        .join("examples");
    for entry in std::fs::read_dir(root().join("examples")).unwrap() {
        let path = entry.unwrap().path();
        let Some(name) = path.file_stem().and_then(|n| n.to_str()) else {
            continue;
        };
        let binary = built.join(name);
        if binary.is_file() {
            let link = dir.join(name);
            let _ = std::fs::remove_file(&link);
            #[cfg(unix)]
            std::os::unix::fs::symlink(&binary, &link).unwrap();
        }
    }
    dir
}

#[test]
fn the_block_reader_joins_lines_maps_cargo_run_and_appends_test_arguments() {
    let blocks = shell_blocks(
        "x.md",
        "text\n```bash test-args=\"--dry-run\"\ncargo run --release -- demo   # the demo\n\
         chronocooked train \\\n    --steps 10\nls out\n```\n```text\nnot a command\n```\n",
    );
    assert_eq!(blocks.len(), 1);
    assert_eq!(blocks[0].line, 2);
    assert_eq!(
        blocks[0].directive("test-args").as_deref(),
        Some("--dry-run")
    );
    assert_eq!(
        blocks[0].script(),
        "set -euo pipefail\nchronocooked demo --dry-run # the demo\n\
         chronocooked train      --steps 10 --dry-run\nls out\n"
    );
}

#[test]
fn an_example_run_through_cargo_reads_as_the_example_binary() {
    assert_eq!(
        example_command("cargo run --release --example interval_production -- env list"),
        "interval_production env list"
    );
    assert_eq!(example_command("  cargo run --release --example x"), "  x");
    assert_eq!(example_command("chronocooked demo"), "chronocooked demo");
}

#[test]
fn every_documented_command_block_runs() {
    let before = tracked_changes();
    let path = format!(
        "{}:{}",
        bin_dir().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut ran = 0;
    let mut not_run = Vec::new();
    for page in documented_pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        let blocks = shell_blocks(&page, &text);
        if blocks.is_empty() {
            continue;
        }
        let dir = scratch(&page);
        for b in &blocks {
            if let Some(reason) = b.directive("not-run") {
                assert!(!reason.trim().is_empty(), "{}:{}: a reason", b.page, b.line);
                not_run.push(format!("{}:{}", b.page, b.line));
                continue;
            }
            let out = Command::new("bash")
                .current_dir(&dir)
                .env("PATH", &path)
                .args(["-c", &b.script()])
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}:{} failed:\n{}\nstdout:\n{}\nstderr:\n{}",
                b.page,
                b.line,
                b.script(),
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            ran += 1;
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
    // The README's two commands and the eight tutorials' blocks, at least.
    assert!(ran >= 10, "only {ran} blocks ran");
    assert!(
        not_run.len() <= 3,
        "blocks not run: {not_run:?} (each needs a reason, and few may have one)"
    );
    if let Some(before) = before {
        assert_eq!(
            tracked_changes().unwrap_or_default(),
            before,
            "a documented command changed the repository's tracked files"
        );
    }
}
