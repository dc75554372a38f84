//! The task parameters: one settings table per task family (key, reference aliases, place
//! in [`TaskConfig`]'s serialised form, accepted values, meaning).
//!
//! These tables are the only description of a task parameter: `--set key=value`, sweep
//! files and Python overrides are parsed by them ([`TaskConfig::set`]), `env list`, the
//! README tables and the Python `tasks()` print them ([`table`], [`crate::settings::listing`]),
//! and [`TaskConfig::validate`] range-checks every configuration against them
//! ([`crate::settings::check`]) before the cross-field rules (S < L, distinct anchors, …).
//! Defaults are the registered task's default configuration
//! ([`crate::registry::TaskSpec::default_config`]).

#[cfg(doc)]
use super::TaskConfig;
use super::TaskFamily;
use crate::settings::{Rule, Spec, UNIT};

/// Largest target duration of any task (steps).
pub const MAX_TD: u64 = 10_000;
/// Largest time limit (steps): 5000× the paper's 200-step episodes.
pub const MAX_TIMESTEPS: u64 = 1_000_000;
/// Largest multiple of TD at which a peak-interval probe releases the soup.
pub const MAX_PROBE_FACTOR: u64 = 1_000;

pub(crate) const TD_RULE: Rule = Rule::Int { lo: 1, hi: MAX_TD };
pub(crate) const BUFFER_RULE: Rule = Rule::Int { lo: 0, hi: MAX_TD };
pub(crate) const CUE_TD_RULE: Rule = Rule::Int { lo: 1, hi: 255 };
pub(crate) const FIXED_TD_RULE: Rule = Rule::Optional(&TD_RULE);

/// One parameter entry (no `only_with` condition).
pub(crate) const fn param(
    key: &'static str,
    aliases: &'static [&'static str],
    path: &'static [&'static str],
    rule: Rule,
    doc: &'static str,
) -> Spec {
    Spec {
        key,
        aliases,
        path,
        rule,
        doc,
        only_with: None,
    }
}

/// Parameters every task accepts.
pub const COMMON: &[Spec] = &[
    param(
        "max_timesteps",
        &["max_steps"],
        &["max_timesteps"],
        Rule::Int {
            lo: 0,
            hi: MAX_TIMESTEPS,
        },
        "time limit: the episode stops when timestep > max_timesteps (so max_timesteps+1 steps), as in the reference",
    ),
    param(
        "reference_compat",
        &["reference"],
        &["reference_compat"],
        Rule::Bool,
        "reference-compatible mode: the time-limit stop is reported as terminated, and the reference's quirks are kept (docs/tasks.md, 'Reference quirks')",
    ),
    param(
        "debug_timer_channel",
        &[],
        &["debug_timer_channel"],
        Rule::Bool,
        "DEBUG: expose the hidden oven timer (+1, 0 = off) in channel 5 at the oven",
    ),
    param(
        "layout",
        &[],
        &["layout"],
        Rule::Text,
        "grid layout, rows joined by '/', cells . O D V S L K B 3 4 W X (`auto`: the task's reference layout); validated: no free cell next to two objects, connected",
    ),
];

pub(crate) const TD: Spec = param(
    "td",
    &["oven_duration"],
    &["params", "td"],
    TD_RULE,
    "target duration (steps)",
);
pub(crate) const FIXED_TD: Spec = param(
    "td",
    &["oven_duration"],
    &["fixed_td"],
    FIXED_TD_RULE,
    "fix the TD of every episode (probes, OOD tests; every oven of a multi-oven episode); none: drawn per episode",
);
pub(crate) const UNDER: Spec = param(
    "under_buffer",
    &["undercooked_buffer"],
    &["params", "under_buffer"],
    BUFFER_RULE,
    "early tolerance of the reward window (steps)",
);
pub(crate) const OVER: Spec = param(
    "over_buffer",
    &["overcooked_buffer"],
    &["params", "over_buffer"],
    BUFFER_RULE,
    "late tolerance of the reward window (steps)",
);
pub(crate) const REDUCED: Spec = param(
    "reduced_reward",
    &[],
    &["params", "reduced_reward"],
    UNIT,
    "reward for soup outside the window",
);
pub(crate) const SHORT: Spec = param(
    "short",
    &["short_duration", "s"],
    &["params", "short"],
    TD_RULE,
    "short anchor S (steps), < long",
);
pub(crate) const LONG: Spec = param(
    "long",
    &["long_duration", "l"],
    &["params", "long"],
    TD_RULE,
    "long anchor L (steps), > short",
);

/// Largest number of anchors (counters) of the multi-anchor task.
pub const MAX_ANCHORS: usize = 4;
/// Largest number of ovens of the multi-oven task.
pub const MAX_OVENS: usize = 3;

/// The family's own parameters (the common ones are [`COMMON`]); declared in the family's
/// file (`task::family`).
pub fn family_table(family: TaskFamily) -> &'static [Spec] {
    family.own_params()
}

/// Every parameter of `family`: its own, then the common ones.
pub fn table(family: TaskFamily) -> Vec<Spec> {
    family_table(family).iter().chain(COMMON).copied().collect()
}

/// One task parameter as `env list`, the README and Python's `tasks()` show it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ParamRow {
    /// The `key=value` key.
    pub key: String,
    /// Other accepted names (the reference's).
    pub aliases: Vec<String>,
    /// Value type (`integer`, `list of integer`, …).
    #[serde(rename = "type")]
    pub kind: String,
    /// The registered task's default, as `key=value` takes it (`none`: unset).
    pub default: String,
    /// Accepted values in words.
    pub allowed: String,
    /// Meaning (with units).
    pub doc: String,
}

/// Every parameter of `config`'s family (its own first) with `config`'s values as defaults.
pub fn rows(config: &super::TaskConfig) -> Vec<ParamRow> {
    let table = config.params_table();
    crate::settings::listing(&table, config)
        .into_iter()
        .map(|s| {
            let spec = table.iter().find(|p| p.key == s.key);
            ParamRow {
                aliases: spec
                    .map(|p| p.aliases.iter().map(|a| a.to_string()).collect())
                    .unwrap_or_default(),
                key: s.key,
                kind: s.kind,
                default: s.value,
                allowed: s.allowed,
                doc: s.doc,
            }
        })
        .collect()
}
