//! The file names of a run folder — one trained agent, a PPO policy or a timing model — in
//! one place. The training crate writes run folders and reads them back with their types
//! (`chronocooked_training::run_dir` for PPO, `timing_run` for the timing models); the
//! analysis crate, the pipeline and the CLI read the same files by these names.
//!
//! ```text
//! RUN_DIR/config.json     the resolved training config
//! RUN_DIR/policy.json     PPO: the policy's architecture and input shape
//! RUN_DIR/command.txt     the command line(s) that produced the run
//! RUN_DIR/curves.csv      the learning curve
//! RUN_DIR/checkpoints/    PPO: resumable trainer states
//! RUN_DIR/model.bpk       PPO: the final policy (burnpack)
//! RUN_DIR/levels/level-L.bpk  PPO, multi-timer curriculum: the policy as it left level L
//!                         (the final policy for the last level reached)
//! RUN_DIR/agent.json      timing models: the trained agent (settings and learned state)
//! RUN_DIR/summary.json    written last: the run finished
//! ```

/// The resolved training config (JSON).
pub const CONFIG: &str = "config.json";
/// The policy's architecture and input shape (JSON; PPO runs).
pub const POLICY: &str = "policy.json";
/// The command line(s) that produced the run, one per line.
pub const COMMAND: &str = "command.txt";
/// The learning curve (CSV, one row per update or per training block).
pub const CURVES: &str = "curves.csv";
/// The folder of resumable trainer states (PPO runs).
pub const CHECKPOINTS: &str = "checkpoints";
/// The final policy (burnpack; PPO runs).
pub const MODEL: &str = "model.bpk";
/// The folder of the multi-timer curriculum's per-level policies (PPO runs).
pub const LEVELS: &str = "levels";

/// The file name (inside [`LEVELS`]) of the policy that left curriculum level `level`
/// (for the last level reached: the final policy), as the paper's code keeps
/// `rl_model_env<level>_<steps>_steps` for every level.
pub fn level_model(level: usize) -> String {
    format!("level-{level}.bpk")
}

/// A timing model's trained agent (JSON: its settings and learned state); an adaptation
/// folder keeps the adapted agent under the same name.
pub const AGENT: &str = "agent.json";
/// The run's own figures (its learning curve, SVG and PNG).
pub const FIGURES: &str = "figures";
/// The run's summary (JSON), written last: its presence marks a finished run.
pub const SUMMARY: &str = "summary.json";

/// What readers outside the training crate need of a run's [`CONFIG`], typed (PPO and
/// timing runs alike; the full configurations are the training crate's `TrainConfig` and
/// `TimingRunConfig`): which kind of run it is, its preset, budget and curriculum, and the
/// PPO settings kept verbatim.
#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize)]
pub struct ConfigHeader {
    /// `"timing"` for a timing-model run; absent for PPO runs.
    #[serde(default)]
    pub kind: Option<String>,
    /// PPO preset (`reference`, `fast`); empty for timing runs.
    #[serde(default)]
    pub preset: String,
    /// PPO env-step budget; 0 for timing runs.
    #[serde(default)]
    pub total_steps: u64,
    /// PPO curriculum; `None` for timing runs.
    #[serde(default)]
    pub curriculum: Option<CurriculumHeader>,
    /// The PPO settings as written (`null` for timing runs): copied, never read field by
    /// field outside the training crate.
    #[serde(default)]
    pub ppo: serde_json::Value,
}

/// A PPO run's curriculum in its [`CONFIG`]: its kind (`none`, `multi_timer`, …).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
pub struct CurriculumHeader {
    /// Curriculum kind.
    pub kind: String,
}

impl ConfigHeader {
    /// Whether the run is a timing model's.
    pub fn is_timing(&self) -> bool {
        self.kind.as_deref() == Some("timing")
    }

    /// The curriculum kind (`None` without one).
    pub fn curriculum_kind(&self) -> Option<&str> {
        self.curriculum.as_ref().map(|c| c.kind.as_str())
    }
}

/// Reads the [`CONFIG`] of the run folder `run`; the error names the file and the field.
pub fn read_config_header(run: &std::path::Path) -> Result<ConfigHeader, String> {
    let path = run.join(CONFIG);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// A run folder's learning curve ([`CURVES`]) read back, the one reader of that file: its
/// header and every complete row (a row cut short by a killed writer — fewer fields than
/// the header — is left out). A field that is not a number (an empty evaluation column)
/// reads as NaN. Written by the trainers with `format!`, so that curves stay byte-identical
/// across builds; read with the `csv` crate.
#[derive(Debug, Clone, PartialEq)]
pub struct Curves {
    /// Column names.
    pub header: Vec<String>,
    /// Complete rows, `[rows, columns]`.
    pub rows: Vec<Vec<f64>>,
}

impl Curves {
    /// Reads `path`; the error names the file.
    pub fn read(path: &std::path::Path) -> Result<Curves, String> {
        let fail = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        let mut rd = csv::ReaderBuilder::new()
            .flexible(true)
            .from_path(path)
            .map_err(|e| fail(&e))?;
        let header: Vec<String> = rd
            .headers()
            .map_err(|e| fail(&e))?
            .iter()
            .map(str::to_string)
            .collect();
        let mut rows = Vec::new();
        for rec in rd.records() {
            let rec = rec.map_err(|e| fail(&e))?;
            if rec.len() == header.len() {
                rows.push(rec.iter().map(|v| v.parse().unwrap_or(f64::NAN)).collect());
            }
        }
        Ok(Curves { header, rows })
    }

    /// The index of column `name`.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// Column `name`, one value per row (`None` without that column).
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let i = self.index(name)?;
        Some(self.rows.iter().map(|r| r[i]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::Curves;

    #[test]
    fn a_curve_reads_complete_rows_and_names_its_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("curves.csv");
        // A header, two rows (one with an empty evaluation field), a row cut by a kill.
        std::fs::write(
            &path,
            "update,env_steps,eval_success\n1,1000,\n2,2000,0.5\n3,30",
        )
        .unwrap();
        let c = Curves::read(&path).unwrap();
        assert_eq!(c.rows.len(), 2);
        assert_eq!(c.column("env_steps").unwrap(), vec![1000.0, 2000.0]);
        let eval = c.column("eval_success").unwrap();
        assert!(eval[0].is_nan() && eval[1] == 0.5);
        assert!(c.column("nope").is_none());
        let e = Curves::read(&dir.path().join("missing.csv")).unwrap_err();
        assert!(e.contains("missing.csv"), "{e}");
    }
}
