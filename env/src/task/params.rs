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

const TD_RULE: Rule = Rule::Int { lo: 1, hi: MAX_TD };
const BUFFER_RULE: Rule = Rule::Int { lo: 0, hi: MAX_TD };
const CUE_TD_RULE: Rule = Rule::Int { lo: 1, hi: 255 };
const FIXED_TD_RULE: Rule = Rule::Optional(&TD_RULE);

const fn param(
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

const TD: Spec = param(
    "td",
    &["oven_duration"],
    &["params", "td"],
    TD_RULE,
    "target duration (steps)",
);
const FIXED_TD: Spec = param(
    "td",
    &["oven_duration"],
    &["fixed_td"],
    FIXED_TD_RULE,
    "fix the TD of every episode (probes, OOD tests; every oven of a multi-oven episode); none: drawn per episode",
);
const UNDER: Spec = param(
    "under_buffer",
    &["undercooked_buffer"],
    &["params", "under_buffer"],
    BUFFER_RULE,
    "early tolerance of the reward window (steps)",
);
const OVER: Spec = param(
    "over_buffer",
    &["overcooked_buffer"],
    &["params", "over_buffer"],
    BUFFER_RULE,
    "late tolerance of the reward window (steps)",
);
const REDUCED: Spec = param(
    "reduced_reward",
    &[],
    &["params", "reduced_reward"],
    UNIT,
    "reward for soup outside the window",
);
const SHORT: Spec = param(
    "short",
    &["short_duration", "s"],
    &["params", "short"],
    TD_RULE,
    "short anchor S (steps), < long",
);
const LONG: Spec = param(
    "long",
    &["long_duration", "l"],
    &["params", "long"],
    TD_RULE,
    "long anchor L (steps), > short",
);

const FIXED_INTERVAL: &[Spec] = &[TD];

const PEAK_INTERVAL: &[Spec] = &[
    TD,
    param(
        "probe_factor",
        &["k"],
        &["params", "probe_factor"],
        Rule::Mapped {
            inner: &Rule::Int {
                lo: 0,
                hi: MAX_PROBE_FACTOR,
            },
            synonyms: &[("never", "0")],
        },
        "the soup becomes available at probe_factor x td; 0 withholds it for the whole episode",
    ),
];

const BISECTION: &[Spec] = &[SHORT, LONG, FIXED_TD];

const MULTI_TIMER: &[Spec] = &[
    param(
        "tds",
        &["oven_duration_list"],
        &["params", "tds"],
        Rule::List(&CUE_TD_RULE),
        "TD list (distinct; the value cue is a byte); an episode draws uniformly from the first num_timers",
    ),
    param(
        "num_timers",
        &[],
        &["params", "num_timers"],
        Rule::Int { lo: 1, hi: 255 },
        "active TDs, at most the length of tds (grows during a curriculum); setting tds lowers it to their count",
    ),
    param(
        "mode",
        &["undercooked_possible"],
        &["params", "mode"],
        Rule::Mapped {
            inner: &Rule::Choice(&["exact", "lower_bounded"]),
            synonyms: &[("true", "exact"), ("false", "lower_bounded")],
        },
        "exact: take the soup any time, reward 1 inside [TD-under, TD+over]; lower_bounded: take it at timer >= TD, reduced if later than TD+over",
    ),
    param(
        "cue",
        &[],
        &["params", "cue"],
        Rule::Mapped {
            inner: &Rule::Choice(&["value", "categorical"]),
            synonyms: &[("cat", "categorical")],
        },
        "oven channel-4 cue while on: the TD value (reference) or 1+index of the TD",
    ),
    UNDER,
    OVER,
    REDUCED,
    param(
        "td",
        &["oven_duration"],
        &["fixed_td"],
        FIXED_TD_RULE,
        "fix the TD of every episode (probes, OOD tests; value cue: at most 255, categorical cue: one of tds); none: drawn per episode",
    ),
];

const DUAL: &[Spec] = &[
    TD,
    UNDER,
    OVER,
    REDUCED,
    param(
        "sink_reward",
        &[],
        &["params", "sink_reward"],
        UNIT,
        "reward per sink interaction while the oven is on",
    ),
];

const UNCERTAINTY: &[Spec] = &[
    TD,
    param(
        "never_ready_prob",
        &["oven_delay_prob"],
        &["params", "never_ready_prob"],
        UNIT,
        "probability that the oven never becomes ready by itself",
    ),
    OVER,
    param(
        "overcooked_reward",
        &[],
        &["params", "overcooked_reward"],
        UNIT,
        "reward when a self-readied soup is taken after TD+over_buffer",
    ),
    param(
        "manual_reward",
        &["undercooked_reward"],
        &["params", "manual_reward"],
        UNIT,
        "reward for soup readied with the manual button",
    ),
];

/// Largest number of anchors (counters) of the multi-anchor task.
pub const MAX_ANCHORS: usize = 4;
/// Largest number of ovens of the multi-oven task.
pub const MAX_OVENS: usize = 3;

const MULTI_ANCHOR: &[Spec] = &[
    param(
        "anchors",
        &[],
        &["params", "anchors"],
        Rule::List(&TD_RULE),
        "anchor durations (steps), 2 to 4 distinct values in increasing order; counter i pays 1 iff TD == anchors[i]",
    ),
    param(
        "num_anchors",
        &[],
        &["params", "num_anchors"],
        Rule::Optional(&Rule::Int { lo: 2, hi: 4 }),
        "active anchors: the first num_anchors of anchors have counters and are drawn (curriculum 2 -> 3 -> 4); none: all",
    ),
    FIXED_TD,
];

const MULTI_OVEN: &[Spec] = &[
    SHORT,
    LONG,
    param(
        "ovens",
        &["n_ovens"],
        &["params", "ovens"],
        Rule::Int {
            lo: 1,
            hi: MAX_OVENS as u64,
        },
        "number of ovens (curriculum 1 -> 2 -> 3); only the first takes the onion",
    ),
    param(
        "asynchronous",
        &["async"],
        &["params", "asynchronous"],
        Rule::Bool,
        "false: the put starts every oven; true: the put starts the first oven and the others start by themselves at drawn on-times",
    ),
    FIXED_TD,
];

const GAIN_RULE: Rule = Rule::Num {
    ok: gain_ok,
    allowed: "number in [0.5, 3]",
};
fn gain_ok(x: f64) -> bool {
    (0.5..=3.0).contains(&x)
}
const NON_NEGATIVE_STEPS: Rule = Rule::Num {
    ok: steps_ok,
    allowed: "number in [0, 100] (steps)",
};
fn steps_ok(x: f64) -> bool {
    (0.0..=100.0).contains(&x)
}

const REPRODUCTION: &[Spec] = &[
    param(
        "priors",
        &["prior"],
        &["params", "priors"],
        Rule::List(&Rule::Text),
        "priors of the sample interval ts, each drawn with equal probability: short (8-14), intermediate (11-17), long (14-20) — Jazayeri & Shadlen 2010's 494-847, 671-1023, 847-1200 ms at 1 step = 59 ms — or LO-HI (every whole step from LO to HI)",
    ),
    param(
        "prior_cue",
        &[],
        &["params", "prior_cue"],
        Rule::Bool,
        "the counter shows which prior the episode draws from (true: interleaved priors with a cue; false: no cue, as blocked priors)",
    ),
    param(
        "gains",
        &["gain"],
        &["params", "gains"],
        Rule::List(&GAIN_RULE),
        "gains g of the production tp = g*ts (Remington et al. 2018: 1 and 1.5); with two, the counter shows the episode's gain",
    ),
    param(
        "tolerance",
        &[],
        &["params", "tolerance"],
        UNIT,
        "reward window half-width as a fraction of the target g*ts (Jazayeri & Shadlen 2010: a window that scales with ts; NeuroGym ReadySetGo: 0.2)",
    ),
    param(
        "tolerance_steps",
        &[],
        &["params", "tolerance_steps"],
        NON_NEGATIVE_STEPS,
        "constant part of the window half-width (steps; NeuroGym's + c)",
    ),
    param(
        "foreperiod_min",
        &[],
        &["params", "foreperiod_min"],
        Rule::Int { lo: 1, hi: 1000 },
        "shortest foreperiod before the Ready cue (steps)",
    ),
    param(
        "foreperiod_max",
        &[],
        &["params", "foreperiod_max"],
        Rule::Int { lo: 1, hi: 1000 },
        "longest foreperiod before the Ready cue (steps, >= foreperiod_min)",
    ),
    param(
        "td",
        &["ts", "oven_duration"],
        &["fixed_td"],
        FIXED_TD_RULE,
        "fix the sample interval ts of every episode (probes; may lie outside the priors); none: drawn from the episode's prior",
    ),
];

/// The family's own parameters (the common ones are [`COMMON`]).
pub fn family_table(family: TaskFamily) -> &'static [Spec] {
    match family {
        TaskFamily::FixedInterval => FIXED_INTERVAL,
        TaskFamily::PeakInterval => PEAK_INTERVAL,
        TaskFamily::Bisection => BISECTION,
        TaskFamily::MultiTimer => MULTI_TIMER,
        TaskFamily::Dual => DUAL,
        TaskFamily::Uncertainty => UNCERTAINTY,
        TaskFamily::MultiAnchor => MULTI_ANCHOR,
        TaskFamily::MultiOven => MULTI_OVEN,
        TaskFamily::Reproduction => REPRODUCTION,
    }
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
    let table = table(config.family());
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
