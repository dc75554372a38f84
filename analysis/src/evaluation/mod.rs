//! Evaluation: [`protocol`] — the conditions each task is tested under and the runner that
//! plays them with any agent (reference: greedy, every start cell; stochastic: N sampled
//! episodes). The evaluation folder it fills is `chronocooked_present::eval_folder`.

pub mod protocol;
