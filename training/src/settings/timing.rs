//! The settings of a timing-model run: the training schedule and the agent's parameters,
//! typed per model family ([`TimerSettings`]: ddm, sbf, time cells), with every `--set` key
//! of [`crate::TimingRunConfig`] and its accepted values ([`TIMING_SETTINGS`]).
//!
//! [`TimingAgentSettings`] holds overrides (`None`: the model's own default, which may depend
//! on the task); [`TimingAgentSettings::of`] reads an agent's values and
//! [`TimingAgentSettings::apply`] writes the overrides into one — the only code that knows
//! where each parameter lives inside a timing agent.

use super::{NON_NEGATIVE, Rule, Spec, UNIT, non_negative, spec};
use crate::error::TrainError;
use chronocooked_models::timing::agent::TimingAgent;
use chronocooked_models::timing::judgment::DecisionRule;
use chronocooked_models::timing::timers::Timer;
use serde::{Deserialize, Serialize};

/// Declares [`TimingAgentSettings`] once: each setting shared by every family with its
/// documentation, its type and where it lives inside a [`TimingAgent`]. Derives the struct,
/// [`TimingAgentSettings::none`], [`TimingAgentSettings::of`] and the plain writes of
/// [`TimingAgentSettings::apply`] (burn's `#[derive(Config)]` pattern, without a proc macro).
macro_rules! agent_settings {
    ($( $(#[doc = $doc:literal])+ $name:ident: $ty:ty => $($place:ident).+; )+) => {
        /// Overrides of a timing agent's parameters, shared by every family (`None`: the
        /// model's default) plus its family's timer parameters.
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct TimingAgentSettings {
            $(
                $(#[doc = $doc])+
                #[serde(default)]
                pub $name: Option<$ty>,
            )+
            /// Bisection criterion between the remembered anchors.
            #[serde(default)]
            pub decision_rule: Option<DecisionRule>,
            /// The timer's own parameters (by family).
            pub timer: TimerSettings,
        }

        impl TimingAgentSettings {
            /// No override, for a timer of the family of `timer`.
            pub fn none(timer: TimerSettings) -> Self {
                TimingAgentSettings {
                    $($name: None,)+
                    decision_rule: None,
                    timer,
                }
            }

            /// Every parameter's value in `agent` (its defaults, for a freshly built one).
            pub fn of(agent: &TimingAgent) -> Self {
                TimingAgentSettings {
                    $($name: Some(agent.$($place).+),)+
                    decision_rule: Some(agent.timer.decision().rule),
                    timer: TimerSettings::of(&agent.timer),
                }
            }

            /// Writes the shared overrides that need no check into `agent`.
            fn apply_shared(&self, agent: &mut TimingAgent) {
                $(
                    if let Some(v) = self.$name {
                        agent.$($place).+ = v;
                    }
                )+
            }
        }
    };
}

/// Declares [`TimerSettings`] once: per timer family (a [`Timer`] variant of the same name),
/// each parameter with its documentation and where it lives inside that timer. Derives the
/// enum, [`TimerSettings::family_of`], and the reads and writes of
/// [`TimingAgentSettings::of`] and [`TimingAgentSettings::apply`].
macro_rules! timer_settings {
    ($(
        $(#[doc = $vdoc:literal])+
        $variant:ident($timer:ident) {
            $( $(#[doc = $doc:literal])+ $name:ident => $($place:ident).+; )+
        }
    )+) => {
        /// Timer parameters of one model family (`None`: the model's default).
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
        #[serde(tag = "family", rename_all = "snake_case", deny_unknown_fields)]
        pub enum TimerSettings {
            $(
                $(#[doc = $vdoc])+
                $variant {
                    $(
                        $(#[doc = $doc])+
                        #[serde(default)]
                        $name: Option<f64>,
                    )+
                },
            )+
        }

        impl TimerSettings {
            /// No override, for the family of `timer`.
            pub fn family_of(timer: &Timer) -> Self {
                match timer {
                    $(Timer::$variant(_) => TimerSettings::$variant { $($name: None,)+ },)+
                }
            }

            /// Every parameter's value in `timer`.
            fn of(timer: &Timer) -> Self {
                match timer {
                    $(
                        Timer::$variant($timer) => TimerSettings::$variant {
                            $($name: Some($timer.$($place).+),)+
                        },
                    )+
                }
            }

            /// Writes the overrides into `timer`; `false` (nothing written) for a timer of
            /// another family.
            fn apply_to(&self, timer: &mut Timer) -> bool {
                match (self, timer) {
                    $(
                        (TimerSettings::$variant { $($name),+ }, Timer::$variant($timer)) => {
                            $(
                                if let Some(v) = *$name {
                                    $timer.$($place).+ = v;
                                }
                            )+
                            true
                        }
                    )+
                    #[allow(unreachable_patterns)]
                    _ => false,
                }
            }
        }
    };
}

agent_settings! {
    /// SARSA(λ) learning rate.
    alpha: f64 => learner.config.alpha;
    /// Discount per step.
    gamma: f64 => learner.config.gamma;
    /// Eligibility-trace decay.
    lambda: f64 => learner.config.lambda;
    /// Initial Q of unvisited state–action pairs.
    q_init: f64 => learner.q_init;
    /// Internal cost of one interact.
    response_cost: f64 => config.response_cost;
    /// Probability of an exploratory check.
    probe: f64 => config.probe;
    /// Step size of the learned reward rate charged per step (0 = off).
    opportunity_cost: f64 => config.opportunity_cost;
    /// Multiple of the expected time past which a missing ready cue is a category (0 = off).
    overdue_factor: f64 => config.overdue_factor;
    /// While the oven runs, an empty-handed agent next to it waits or checks.
    wait_at_oven: bool => config.wait_at_oven;
    /// Time cells: once a check of the running oven failed, keep checking (break-and-run).
    break_and_run: bool => config.break_and_run;
    /// Time cells on reproduction: span of an exploratory delayed response, as a fraction
    /// of the production time (0 = off).
    response_delay: f64 => config.response_delay;
}

timer_settings! {
    /// Drift-diffusion timer.
    Ddm(d) {
        /// Diffusion noise m.
        noise => acc.noise;
        /// SD of the log of a per-trial factor on each remembered anchor drift.
        memory_noise => memory_noise;
        /// Drift learning rate at Set in the reproduction task (1 = one-shot).
        reproduction_rate => reproduction_rate;
    }
    /// Striatal beat-frequency timer.
    Sbf(s) {
        /// CV of the stored duration (κ).
        memory_noise => model.memory_noise;
        /// SD of the log of a per-trial oscillator-frequency factor.
        clock_noise => clock_noise;
    }
    /// Time cells, microstimuli, CSC, presence.
    TimeCells(tc) {
        /// SD of the log of a factor on each stored anchor estimate.
        memory_noise => memory_noise;
        /// SD of the log of a per-trial clock-speed factor.
        clock_noise => cells.clock_noise;
    }
}

impl TimingAgentSettings {
    /// Writes the overrides into `agent`; an agent of another family is an error, and so is
    /// the learned decision rule for a task with more than two categories.
    pub fn apply(&self, agent: &mut TimingAgent) -> Result<(), TrainError> {
        self.apply_shared(agent);
        if let Some(rule) = self.decision_rule {
            // The learned criterion moves after errors whose true category is known; with
            // more than two counters an unpaid choice says only "not this one"
            // (`timing::judgment`).
            if rule == DecisionRule::Learned && agent.categories > 2 {
                return Err(TrainError::param(
                    "agent.decision_rule",
                    rule.name(),
                    &format!(
                        "ratio, difference or likelihood for a task with {} categories \
                         (learned needs two: an unpaid choice among more does not say which \
                         category was right)",
                        agent.categories
                    ),
                ));
            }
            agent.timer.decision_mut().rule = rule;
        }
        if !self.timer.apply_to(&mut agent.timer) {
            return Err(TrainError::param(
                "agent.timer",
                format!("{:?}", self.timer),
                &format!("settings of the {} model's family", agent.name),
            ));
        }
        Ok(())
    }
}

fn step_size(x: f64) -> bool {
    x > 0.0 && x <= 1.0
}
fn fraction_below_one(x: f64) -> bool {
    (0.0..1.0).contains(&x)
}
fn overdue(x: f64) -> bool {
    x == 0.0 || x >= 1.0
}
fn any(_: f64) -> bool {
    true
}

const STEP_SIZE: Rule = Rule::Num {
    ok: step_size,
    allowed: "number in (0, 1]",
};
const NOISE: Rule = Rule::Num {
    ok: non_negative,
    allowed: "number >= 0 (0 = noise-free)",
};

const fn timer(
    key: &'static str,
    path: &'static [&'static str],
    families: &'static str,
    doc: &'static str,
) -> Spec {
    Spec {
        only_with: Some(families),
        ..spec(key, path, NOISE, doc)
    }
}

/// Most training episodes of a timing run (40,000 take seconds; 10^7 about hours): a
/// larger value is a typo or a corrupt `config.json`, not a run anyone waits for.
pub const MAX_EPISODES: usize = 10_000_000;

/// Every setting of a timing-model run, in display order (a model lists those its family
/// has). Not settings: `task`, `model` and `seed` (`--task`, `--model`, `--seed`) and the
/// task parameters, set as `env.<task parameter>=v`.
pub const TIMING_SETTINGS: &[Spec] = &[
    spec(
        "episodes",
        &["train", "episodes"],
        Rule::Int {
            lo: 1,
            hi: MAX_EPISODES as u64,
        },
        "training episodes (6,000; 40,000 on Uncertainty-v0; 60,000 on Ready-Set-Go (reproduction) tasks; per level where the reference trains a curriculum: multi-anchor 2, 3, … counters, multi-oven 1, 2, … ovens)",
    ),
    spec(
        "epsilon_start",
        &["train", "epsilon_start"],
        UNIT,
        "initial exploration probability",
    ),
    spec(
        "epsilon_end",
        &["train", "epsilon_end"],
        UNIT,
        "final exploration probability",
    ),
    spec(
        "anneal_fraction",
        &["train", "anneal_fraction"],
        STEP_SIZE,
        "fraction of the episodes over which epsilon (and alpha, to alpha_end) anneals",
    ),
    spec(
        "eval_every",
        &["train", "eval_every"],
        Rule::Int {
            lo: 0,
            hi: MAX_EPISODES as u64,
        },
        "episodes between deterministic evaluations (0 = only at the end)",
    ),
    spec(
        "stop_at_success",
        &["train", "stop_at_success"],
        Rule::Optional(&STEP_SIZE),
        "stop once the evaluation reaches this success rate",
    ),
    spec(
        "alpha",
        &["agent", "alpha"],
        STEP_SIZE,
        "SARSA(lambda) learning rate",
    ),
    spec(
        "alpha_end",
        &["train", "alpha_end"],
        Rule::Optional(&STEP_SIZE),
        "final SARSA(lambda) learning rate, annealed from alpha like epsilon (none = constant alpha; 0.005 on Ready-Set-Go tasks)",
    ),
    spec(
        "visit_power",
        &["train", "visit_power"],
        UNIT,
        "exponent w of the per-feature step floor n^-w, n = the feature's visits in its state-action pair (Even-Dar & Mansour 2003; 0 = off, 0.85 for the time cells on Ready-Set-Go tasks)",
    ),
    spec("gamma", &["agent", "gamma"], UNIT, "discount per step"),
    spec(
        "lambda",
        &["agent", "lambda"],
        UNIT,
        "eligibility-trace decay (replacing traces)",
    ),
    spec(
        "q_init",
        &["agent", "q_init"],
        Rule::Num {
            ok: any,
            allowed: "a finite number",
        },
        "initial Q of unvisited state-action pairs",
    ),
    spec(
        "response_cost",
        &["agent", "response_cost"],
        NON_NEGATIVE,
        "internal cost of one interact",
    ),
    spec(
        "probe",
        &["agent", "probe"],
        Rule::Num {
            ok: fraction_below_one,
            allowed: "number in [0, 1)",
        },
        "probability of an exploratory check",
    ),
    spec(
        "opportunity_cost",
        &["agent", "opportunity_cost"],
        Rule::Num {
            ok: fraction_below_one,
            allowed: "number in [0, 1) (0 = off)",
        },
        "step size of the learned reward rate charged on every step (average-reward TD)",
    ),
    spec(
        "overdue_factor",
        &["agent", "overdue_factor"],
        Rule::Num {
            ok: overdue,
            allowed: "0 (off), or a number >= 1",
        },
        "cue tasks: multiple of the expected time past which a missing ready cue is a category",
    ),
    spec(
        "wait_at_oven",
        &["agent", "wait_at_oven"],
        Rule::Bool,
        "FI/PI/multi-timer/bisection: an empty-handed agent at the running oven waits or checks, never walks",
    ),
    spec(
        "break_and_run",
        &["agent", "break_and_run"],
        Rule::Bool,
        "time cells on FI/PI/multi-timer: once a check failed, keep checking unless waiting is worth more by over one response cost",
    ),
    spec(
        "response_delay",
        &["agent", "response_delay"],
        UNIT,
        "time cells on reproduction, training: with probability epsilon a response is delayed by 1..=ceil(x t) steps at production time t (temporally extended exploration; 0 = off)",
    ),
    spec(
        "decision_rule",
        &["agent", "decision_rule"],
        Rule::Choice(&["ratio", "difference", "likelihood", "learned"]),
        "criterion between two remembered anchors (geometric, arithmetic, harmonic mean, or learned from feedback; multi-anchor: one per neighbouring pair, learned needs two counters)",
    ),
    timer(
        "noise",
        &["agent", "timer", "noise"],
        "ddm",
        "diffusion noise m (CV of the crossing time = m/sqrt(z A))",
    ),
    timer(
        "memory_noise",
        &["agent", "timer", "memory_noise"],
        "ddm, sbf, timecells-*",
        "SD (log) of a per-trial factor on each remembered duration (sbf: CV kappa of the stored duration)",
    ),
    Spec {
        only_with: Some("ddm"),
        ..spec(
            "reproduction_rate",
            &["agent", "timer", "reproduction_rate"],
            STEP_SIZE,
            "reproduction: drift learning rate at Set (1 = Simen et al. 2011's one-shot rule; below 1 the drift averages the context's past measurements)",
        )
    },
    timer(
        "clock_noise",
        &["agent", "timer", "clock_noise"],
        "sbf, timecells-*",
        "SD of the log of a per-trial clock-speed factor (0 = nominal)",
    ),
];
