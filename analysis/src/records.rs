//! Evaluation records: the conditions a task is tested under ([`Condition`],
//! [`ConditionKind`]) and one evaluated episode with its condition ([`EvalRecord`], a line
//! of `records.jsonl`, read back by [`read_records`]). The protocol
//! ([`crate::evaluation::protocol`]) writes them; the behavioural metrics, the report,
//! exports and the paper's analyses read them.

use chronocooked_env::Task;
pub use chronocooked_env::task::condition::{Condition, ConditionKind};
use chronocooked_models::EpisodeRecord;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One evaluated episode with its condition.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EvalRecord {
    /// Condition.
    pub condition: Condition,
    /// Episode.
    pub episode: EpisodeRecord,
}

impl EvalRecord {
    /// Checks the episode ([`EpisodeRecord::validate`]), that it is of its condition's
    /// duration, and that a multi-oven episode
    /// carries every oven's state at every step (records written before the ovens' state
    /// moved out of the step info lack it; their metrics would silently miss every oven).
    pub fn validate(&self) -> Result<(), String> {
        self.episode.validate()?;
        if self.condition.td != self.episode.td {
            return Err(format!(
                "field `condition.td`: {}, but the episode's td is {} (every condition plays \
                 episodes of its own duration)",
                self.condition.td, self.episode.td
            ));
        }
        if self.condition.kind == ConditionKind::MultiOven
            && self.episode.ovens.len() != self.episode.actions.len()
        {
            return Err(format!(
                "field `ovens`: {} entries for {} actions (a multi-oven episode records every \
                 oven's state at every step; evaluate the run again to rewrite older records)",
                self.episode.ovens.len(),
                self.episode.actions.len()
            ));
        }
        Ok(())
    }
}

/// File name of an evaluation folder's per-episode records (JSON lines of [`EvalRecord`];
/// the folder's other files are named in `chronocooked_present::eval_folder`).
pub const RECORDS: &str = "records.jsonl";

/// Reads the per-episode records (`records.jsonl`) of an `eval` output folder, each checked
/// ([`EvalRecord::validate`]); errors name
/// the file (and the line and field of a malformed record). A file without any record is an
/// error ("no episodes"), never an empty evaluation.
pub fn read_records(folder: &std::path::Path) -> Result<Vec<EvalRecord>, String> {
    let path = folder.join(RECORDS);
    // Checked against the folder's SHA-256 record, which every evaluation writes: an edited
    // record is refused, never scored, and so is one whose record was removed.
    let text = chronocooked_env::integrity::read_verified(&path)
        .map_err(|e| e.to_string())
        .and_then(|b| {
            String::from_utf8(b).map_err(|_| format!("{}: not UTF-8 text", path.display()))
        })?;
    let records: Vec<EvalRecord> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            let at = || format!("{} line {}", path.display(), i + 1);
            let r: EvalRecord = serde_json::from_str(l).map_err(|e| format!("{}: {e}", at()))?;
            r.validate().map_err(|e| format!("{}: {e}", at()))?;
            Ok(r)
        })
        .collect::<Result<_, String>>()?;
    if records.is_empty() {
        return Err(format!(
            "{}: no episodes (an evaluation has at least one record)",
            path.display()
        ));
    }
    if folder.join(EVAL_INFO).is_file()
        && let Some(n) = read_eval_info(folder)?.episodes
        && n != records.len()
    {
        return Err(format!(
            "{}: {} episodes, but {} says field `episodes`: {n} (a record line was deleted or \
             repeated)",
            path.display(),
            records.len(),
            folder.join(EVAL_INFO).display()
        ));
    }
    Ok(records)
}

/// How episodes are played.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Mode {
    /// Greedy, one episode per free start cell.
    Reference,
    /// `episodes` per condition, random start cells, sampled actions.
    Stochastic {
        /// Episodes per condition.
        episodes: usize,
    },
}

/// File name of the evaluation's description ([`EvalInfo`]).
pub const EVAL_INFO: &str = "eval.json";
/// File name of the metrics computed from the records ([`Metrics`]).
pub const METRICS: &str = "metrics.json";

/// What an evaluation was (`eval.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EvalInfo {
    /// Name of the evaluated model (a leaderboard row).
    pub model: String,
    /// Task the protocol was built for, with its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Reference (greedy, every start cell) or stochastic protocol.
    pub mode: Mode,
    /// Seed of the evaluation.
    pub seed: u64,
    /// Set when the evaluated run had not finished training (`eval --unfinished`): the env
    /// step (PPO) of the checkpoint that was evaluated, 0 when it had none to name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unfinished_at_step: Option<u64>,
    /// Number of evaluated episodes, the lines of `records.jsonl` (written by every
    /// evaluation; `None` in folders written before it was kept): a deleted or repeated
    /// record line is refused when the records are read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub episodes: Option<usize>,
}

/// Checks that `dir` holds a complete evaluation: `eval.json`, `records.jsonl` and
/// `metrics.json`, the metrics being written last (`evaluation::folder::start_writing`),
/// so a folder without them is one whose writer stopped half-way (killed, out of disk). The
/// error names the missing file and the command that completes the folder: recomputing
/// the metrics and figures from whole records (`eval --from DIR --out DIR`), or the
/// evaluation again when its records are missing too. Every reader of evaluation results
/// (report, export, collect, zoo) calls it; `eval --from` itself does not (it completes).
pub fn check_complete_eval(dir: &Path) -> Result<(), String> {
    let missing: Vec<&str> = [EVAL_INFO, RECORDS, METRICS]
        .into_iter()
        .filter(|f| std::fs::symlink_metadata(dir.join(f)).is_err())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let d = dir.display();
    let how = if missing.contains(&RECORDS) || missing.contains(&EVAL_INFO) {
        "run the `chronocooked eval` command that wrote it again (same --out)".to_string()
    } else {
        format!(
            "complete it with `chronocooked eval --from {d} --out {d}` (the metrics and \
             figures again from its records), or run its `eval` command again"
        )
    };
    Err(format!(
        "{d}: not a complete evaluation: {} missing (an evaluation writes {METRICS} last; this \
         one was stopped, killed or ran out of disk); {how}",
        missing
            .iter()
            .map(|f| format!("{}", dir.join(f).display()))
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// Reads `eval.json` of an evaluation folder; errors name the file.
pub fn read_eval_info(dir: &Path) -> Result<EvalInfo, String> {
    let path = dir.join(EVAL_INFO);
    if !path.is_file() {
        return Err(format!(
            "{}: no such file ({} is not an eval folder)",
            path.display(),
            dir.display()
        ));
    }
    let text = chronocooked_env::integrity::read_verified(&path)
        .map_err(|e| e.to_string())
        .and_then(|b| {
            String::from_utf8(b).map_err(|_| format!("{}: not UTF-8 text", path.display()))
        })?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}
