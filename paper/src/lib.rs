//! The paper's study: the paper's analyses of a results folder beside the lab's. The
//! results folder itself — a sweep's output folder made compact (summary, one line per
//! evaluation episode, thinned learning curve, metrics) — is the generic
//! [`chronocooked_analysis::collect`]; this crate reads it.
//!
//! * [`lsq`] — the paper's least-squares psychometric fit (and its failure rules);
//! * [`fi`] — FOC pooled over runs × start cells per TD, CV, scalar-property R²;
//! * [`bisection`] — per-run P(long), run exclusion, averaged curve, per-run BP/DL/WF,
//!   WF vs log2(L/S);
//! * [`multitimer`] — curriculum levels reached, steps and training reward per level, the
//!   final policy's reward and oven-off time per TD;
//! * [`reference`] — the paper's published numbers;
//! * [`compare`] — `comparison.csv` rows, the old agreement rule and the z rule;
//! * [`agreement`] — `agreement.json`: verdict counts per table × source × rule and the
//!   negative control;
//! * [`claims`] — `claims.csv`: the paper's exact-timer and multi-timer statements in words,
//!   each tested on the lab's runs;
//! * [`pi`] — `pi.csv`: the peak-interval probes and the uniform-checking test;
//! * [`spreads`] — `spreads.csv`: each condition's spread on the first four seeds and on
//!   every run;
//! * [`heldout`] — a held-out seed's run against each condition's 95% range for a new run;
//! * [`figures`] — the study's figures in the paper's form;
//! * [`study`] — the whole analysis of a results folder, written as JSON, CSV and Markdown;
//! * [`report`] — the study's `report.html`: agreement per table, figures, every row;
//! * [`analyse`] — all of it for one results folder (`paper analyse`).

#![warn(missing_docs)]

pub mod agreement;
pub mod analyse;
pub mod bisection;
pub mod claims;
pub mod compare;
pub mod fi;
pub mod figures;
pub mod heldout;
pub mod lsq;
pub mod multitimer;
pub mod pi;
pub mod reference;
pub mod report;
pub mod spreads;
pub mod study;
