//! PPO as Stable-Baselines3 / sb3-contrib implement it (feed-forward and recurrent):
//!
//! * [`config`] — settings (`TrainConfig`, `PpoConfig`) and their `key=value` surface;
//!   [`presets`] — the named presets (reference = the paper's code, fast, …);
//! * [`obs`] — observation encoding for the networks ([`frames`]: stacked observations); [`act`] — batched policy steps,
//!   sampling and log-probabilities; [`rollout`] — the rollout buffer and its minibatch orders (transitions,
//!   BPTT chunks, whole sequences);
//! * [`gae`] — generalised advantage estimation; [`loss`] — the clipped surrogate, value and
//!   entropy terms; [`minibatch`] — one minibatch and its loss at the network outputs;
//!   [`engine`] — the network behind one trait (acting, loss and gradient, parameter sync)
//!   with its two implementations, native and burn;
//!   [`adam`] — Adam with SB3's settings; [`params`] — flat parameter vectors;
//! * [`trainer`] — the update loop, curricula and its checkpointable state ([`state`]);
//! * [`run`] — a run folder trained to its budget (new or resumed), with evaluation,
//!   checkpoints and the final model;
//! * [`agent`] — a trained policy as an [`chronocooked_models::Agent`].

pub mod act;
pub mod adam;
pub mod agent;
pub mod config;
pub mod engine;
pub mod evaluate;
pub mod frames;
pub mod gae;
pub mod loss;
pub mod minibatch;
pub mod obs;
pub mod params;
pub mod presets;
pub mod rollout;
pub mod run;
pub mod run_dir;
pub mod state;
pub mod trainer;
