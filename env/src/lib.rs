//! # chronocooked-env
//!
//! The Chronocooked benchmark for implicit interval timing: a tiny
//! Overcooked-like gridworld in which an invisible oven timer must be inferred.
//!
//! * [`registry`] — versioned task ids (`FixedInterval-v0`, `Bisection-v0`, …)
//!   with documented defaults; [`task`] — parameters and validation.
//! * [`ChronoEnv`] — gymnasium-shaped `reset(seed, options)` / `step(action)`
//!   with reference semantics (see [`kitchen`] for the exact step order).
//! * [`VecEnv`] — N envs into preallocated buffers with documented autoreset.
//! * [`obs`] — the reference "codes" encoding and a one-hot view for networks.
//! * [`oracle`] — optimal scripted policies; [`render`] — ASCII, PNG, GIF;
//!   [`trace`] — JSON-lines episode traces; [`fs`] — the one atomic file write;
//!   [`integrity`] — SHA-256 records of learned state; [`markdown`] — the one Markdown
//!   table writer.

#![warn(missing_docs)]

pub mod action;
pub mod bench;
pub mod env;
pub mod error;
pub mod fs;
pub mod info;
pub mod integrity;
pub mod interrupt;
pub mod kitchen;
pub mod layout;
pub mod markdown;
pub mod obs;
pub mod oracle;
pub mod registry;
pub mod render;
mod rules;
pub mod settings;
mod spec;
pub mod task;
pub mod trace;
pub mod vec_env;

pub use action::{Action, parse_action_list};
pub use env::ChronoEnv;
pub use error::EnvError;
pub use info::{Carry, Counter, Events, INFO_KEYS, Info, OvenSet};
pub use kitchen::{
    CODE_CHANNELS, Kitchen, KitchenSnapshot, KitchenState, MultiOvenState, PerOven, ResetOptions,
    RsgState, Transition, derive_seed,
};
pub use layout::{Layout, ObjectKind};
pub use obs::{BoxSpace, Discrete, OneHotEncoder};
pub use oracle::{Oracle, optimal_return};
pub use registry::{TaskSpec, all_tasks, find_task, tasks_with_tag};
pub use rules::ReadySetGo;
pub use task::family::ResponseKind;
pub use task::reset_option::{BASIC_RESET_OPTIONS, ResetOption};
pub use task::{
    CueMode, Growth, RewardMode, Task, TaskConfig, TaskFamily, TaskParams, make_config,
};
pub use vec_env::{Autoreset, VecEnv, VecEnvSnapshot};
