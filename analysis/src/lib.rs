//! Chronocooked Lab analysis: behavioural and neural metrics of recorded episodes and
//! activity (grows with its issue).
//!
//! * [`foc`] — first oven check (the paper's FI measure), per-TD statistics, scalar property;
//! * [`psychometric`] — bisection P(long), logistic fit by binomial maximum likelihood,
//!   BP / T25 / T75 / DL / WF with bootstrap intervals;
//! * [`neural`] — ramping units, time cells, temporal information, sequentiality index;
//! * [`decode`] — cross-validated ridge and Bayesian decoders of elapsed time;
//! * [`peak`] — PI Gaussian(+baseline) fit and single-trial start/stop analysis;
//! * [`oscillation`] — Welch spectra and inter-trial phase coherence;
//! * [`summary`] — per-model neural summary (fractions of ramping / time / oscillating
//!   units, sequentiality, decoding error);
//! * [`aggregate`] — headline numbers, mean ± SD across seeds, episodes to adapt;
//! * [`human`] — recorded human play (`env play`) as evaluation records;
//! * [`export`] / [`npz`] — NPZ (numpy) + CSV + JSON-metadata export of activity and
//!   evaluation records;
//! * [`report`] — leaderboard (self-contained HTML with inline SVG, Markdown, CSV);
//! * [`figures`] — SVG/PNG figures (plotters, bundled font);
//! * [`protocol`] — evaluation conditions per task and the runner (any agent);
//! * [`eval_folder`] — the evaluation folder (`records.jsonl`, `eval.json`, `metrics.json`,
//!   figures) written by `eval` and by the Python `evaluate`;
//! * [`metrics`] — behavioural metrics of an evaluation from its per-episode records;
//! * [`paper`] — the paper's study: compact sweep results, the paper's analyses beside the
//!   lab's, and the comparison with the paper's numbers.

pub mod aggregate;
pub mod decode;
pub mod eval_folder;
pub mod export;
pub mod figures;
pub mod foc;
pub mod human;
pub mod leaderboard;
pub mod metrics;
pub mod neural;
pub mod npz;
pub mod oscillation;
pub mod paper;
pub mod peak;
pub mod protocol;
pub mod psychometric;
pub mod report;
pub mod summary;

pub use decode::{DecodeResult, Decoder, decode_time};
pub use foc::{
    FocConvention, FocStats, ScalarProperty, episode_foc, first_oven_check, first_oven_check_with,
    foc_stats, scalar_property,
};
pub use metrics::{Metrics, compute_metrics};
pub use neural::{Cube, classify_ramps, sequentiality_index, temporal_information, time_cells};
pub use protocol::{
    Condition, EvalRecord, Mode, reference_conditions, run_protocol, run_protocol_recorded,
};
pub use psychometric::{FitError, LogisticFit, ProbeCounts, fit_logistic, fit_with_ci};
