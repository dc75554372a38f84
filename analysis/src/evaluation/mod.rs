//! Evaluation:
//!
//! * [`protocol`] — the conditions each task is tested under and the runner that plays them
//!   with any agent (reference: greedy, every start cell; stochastic: N sampled episodes);
//! * [`folder`] — the evaluation folder (`records.jsonl`, `eval.json`, `metrics.json`,
//!   figures, optional activity) written by `eval` and by the Python `evaluate`.

pub mod folder;
pub mod protocol;
