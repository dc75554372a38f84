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
