//! One function per stage of a study job; each reads and writes its own folder, so the CLI
//! commands (`train`, `eval`, `adapt`, `record`, `export`) and the sweep pipeline
//! ([`crate::run_job`]) run the same code.
//!
//! * [`train`] — a PPO agent or a timing model into a run folder (new or resumed);
//! * [`evaluate`] — the task's reference (or stochastic) protocol with a trained run or a
//!   reference agent, recorded play of a human, or metrics recomputed from saved records;
//! * [`levels`] — a multi-timer run's per-level curriculum policies, each in its level's
//!   test setting (the paper's notebooks);
//! * [`adapt`] — uncertainty adaptation of a trained run;
//! * [`record`] — the neural activity of a trained run, its summary and figures;
//! * [`export`] — activity datasets and evaluation records as NPZ + CSV + JSON metadata;
//! * [`verify`] — what a folder claims, re-derived from what determines it.

pub mod adapt;
pub mod evaluate;
pub mod export;
pub mod fingerprint;
pub mod levels;
pub mod record;
pub mod scaling;
pub mod train;
pub mod verify;

pub use adapt::{AdaptRequest, adapt};
pub use evaluate::{
    EvalOutcome, EvalRequest, EvalSubject, evaluate, evaluate_human, rescore_eval_folder,
};
pub use export::export;
pub use fingerprint::{
    FingerprintOutcome, FingerprintRequest, SweepFingerprint, fingerprint, fingerprint_sweep,
    sweep_line,
};
pub use record::{RecordOutcome, RecordRequest, record};
pub use scaling::{ScalingJob, ScalingOutcome, record_scaling};
pub use train::{Quiet, TrainObserver, TrainOutcome, TrainRequest, train};
pub use verify::{Difference, Verification, VerifyRequest, verify};
