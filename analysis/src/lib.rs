//! Chronocooked Lab analysis: behavioural and neural metrics of recorded episodes and
//! activity, the evaluation protocol, the mechanism fingerprints and the compact results
//! folder of a study. It computes and reads; what is drawn and laid out for people (figures,
//! the report, cards, evaluation folders, exports) is `chronocooked-present` above it, and
//! the paper's own analyses are `chronocooked-paper`.
//!
//! * [`stats`] — small statistics shared by the analyses (`Spread`: mean, SD, n across runs);
//! * [`behaviour`] — behavioural metrics: first oven check and the scalar property (`foc`),
//!   psychometric fits (`psychometric`), peak-interval fits (`peak`), per-evaluation metrics
//!   (`metrics`), headline aggregates across seeds (`aggregate`), human play (`human`);
//! * [`neural`] — neural metrics: ramping units, time cells, sequentiality, temporal
//!   information, scaling; elapsed-time decoders (`decode`), spectra and phase coherence
//!   (`oscillation`), the per-model neural summary (`summary`), timing by speed (`speed`:
//!   KiNeT, Remington et al. 2018);
//! * [`job_folder`] — the file names of a sweep job's folder (`job.json`, `run/`, `eval/`,
//!   recorded activity and its summary);
//! * [`results_folder`] — whether a study's compact results folder is complete (the marker of
//!   an unfinished `paper collect`);
//! * [`records`] — evaluation records: conditions and evaluated episodes (`records.jsonl`);
//! * [`reproduction`] — temporal reproduction (Ready-Set-Go): Bayesian observers (BLS, MAP,
//!   ML; Jazayeri & Shadlen 2010) as simulators and as a fitting tool, and the standard
//!   summaries (regression slope, BIAS, √VAR, RMSE, Weber fraction);
//! * [`evaluation`] — the evaluation protocol (`protocol`: conditions per task, the runner
//!   for any agent);
//! * [`mechanisms`] — mechanism fingerprints: each model's behavioural and neural
//!   signatures, and which timing mechanism each trained agent is nearest to;
//! * [`fingerprint`] — one agent's signature placed among the committed mechanisms;
//! * [`columns`] — the table of the metrics an evaluation reports: each one's key, theme,
//!   title, description and how it is read from the metrics (the leaderboard's columns);
//! * [`collect`] — a study's compact results: a sweep's output folder → per job a summary,
//!   one line per evaluation episode, a thinned learning curve and the metrics, which a
//!   repository can keep (`paper collect`).

#![warn(missing_docs)]

pub mod behaviour;
pub mod collect;
pub mod columns;
pub mod evaluation;
pub mod fingerprint;
pub mod job_folder;
pub mod mechanisms;
pub mod neural;
pub mod records;
pub mod reproduction;
pub mod results_folder;
pub mod stats;

pub use behaviour::foc::{
    FocConvention, FocStats, ScalarProperty, episode_foc, first_oven_check, first_oven_check_with,
    foc_stats, scalar_property,
};
pub use behaviour::metrics::{Metrics, compute_metrics};
pub use behaviour::psychometric::{FitError, LogisticFit, ProbeCounts, fit_logistic, fit_with_ci};
pub use evaluation::protocol::{Mode, reference_conditions, run_protocol, run_protocol_recorded};
pub use neural::decode::{DecodeResult, Decoder, decode_time};
pub use neural::{Cube, classify_ramps, sequentiality_index, temporal_information, time_cells};
pub use records::{Condition, ConditionKind, EvalRecord};
