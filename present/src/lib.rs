//! Chronocooked Lab presentation: what the lab draws and lays out for people and other
//! tools, above the metrics of `chronocooked-analysis` (which computes; this crate shows).
//!
//! * [`figures`] — the drawing kit every page uses (plotters: SVG and PNG charts, heat maps
//!   and the standard figures of evaluations, recordings and runs) and the HTML page kit
//!   (`markup`);
//! * [`report`] — the leaderboard (HTML with inline SVG, Markdown, CSV; its one column table,
//!   `columns`), the committed baselines beside a user's rows and the mechanism cards;
//! * [`fingerprint`] — one agent's fingerprint: the protocol it plays and the folders it
//!   leaves (`play`), and its card (`fingerprint.md`, `.html`, `.png`); the placement among
//!   the mechanisms is `chronocooked_analysis::fingerprint`, re-exported here;
//! * [`mechanisms`] — the files of a mechanisms study: signature and identification tables
//!   (CSV, Markdown) and the fingerprint figures;
//! * [`eval_folder`] — the evaluation folder `eval` writes (records, `eval.json`, metrics,
//!   figures, activity);
//! * [`export`] — NPZ (numpy) + CSV + JSON-metadata export of activity and evaluation
//!   records.

#![warn(missing_docs)]

pub mod eval_folder;
pub mod export;
pub mod figures;
pub mod fingerprint;
pub mod mechanisms;
pub mod report;
