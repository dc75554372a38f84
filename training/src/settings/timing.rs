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

/// Overrides of a timing agent's parameters, shared by every family (`None`: the model's
/// default) plus its family's timer parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimingAgentSettings {
    /// SARSA(λ) learning rate.
    #[serde(default)]
    pub alpha: Option<f64>,
    /// Discount per step.
    #[serde(default)]
    pub gamma: Option<f64>,
    /// Eligibility-trace decay.
    #[serde(default)]
    pub lambda: Option<f64>,
    /// Initial Q of unvisited state–action pairs.
    #[serde(default)]
    pub q_init: Option<f64>,
    /// Internal cost of one interact.
    #[serde(default)]
    pub response_cost: Option<f64>,
    /// Probability of an exploratory check.
    #[serde(default)]
    pub probe: Option<f64>,
    /// Step size of the learned reward rate charged per step (0 = off).
    #[serde(default)]
    pub opportunity_cost: Option<f64>,
    /// Multiple of the expected time past which a missing ready cue is a category (0 = off).
    #[serde(default)]
    pub overdue_factor: Option<f64>,
    /// While the oven runs, an empty-handed agent next to it waits or checks.
    #[serde(default)]
    pub wait_at_oven: Option<bool>,
    /// Time cells: once a check of the running oven failed, keep checking (break-and-run).
    #[serde(default)]
    pub break_and_run: Option<bool>,
    /// Time cells on reproduction: span of an exploratory delayed response, as a fraction
    /// of the production time (0 = off).
    #[serde(default)]
    pub response_delay: Option<f64>,
    /// Bisection criterion between the remembered anchors.
    #[serde(default)]
    pub decision_rule: Option<DecisionRule>,
    /// The timer's own parameters (by family).
    pub timer: TimerSettings,
}

/// Timer parameters of one model family (`None`: the model's default).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "family", rename_all = "snake_case", deny_unknown_fields)]
pub enum TimerSettings {
    /// Drift-diffusion timer.
    Ddm {
        /// Diffusion noise m.
        #[serde(default)]
        noise: Option<f64>,
        /// SD of the log of a per-trial factor on each remembered anchor drift.
        #[serde(default)]
        memory_noise: Option<f64>,
        /// Drift learning rate at Set in the reproduction task (1 = one-shot).
        #[serde(default)]
        reproduction_rate: Option<f64>,
    },
    /// Striatal beat-frequency timer.
    Sbf {
        /// CV of the stored duration (κ).
        #[serde(default)]
        memory_noise: Option<f64>,
        /// SD of the log of a per-trial oscillator-frequency factor.
        #[serde(default)]
        clock_noise: Option<f64>,
    },
    /// Time cells, microstimuli, CSC, presence.
    TimeCells {
        /// SD of the log of a factor on each stored anchor estimate.
        #[serde(default)]
        memory_noise: Option<f64>,
        /// SD of the log of a per-trial clock-speed factor.
        #[serde(default)]
        clock_noise: Option<f64>,
    },
}

impl TimerSettings {
    /// No override, for the family of `timer`.
    pub fn family_of(timer: &Timer) -> Self {
        match timer {
            Timer::Ddm(_) => TimerSettings::Ddm {
                noise: None,
                memory_noise: None,
                reproduction_rate: None,
            },
            Timer::Sbf(_) => TimerSettings::Sbf {
                memory_noise: None,
                clock_noise: None,
            },
            Timer::TimeCells(_) => TimerSettings::TimeCells {
                memory_noise: None,
                clock_noise: None,
            },
        }
    }
}

impl TimingAgentSettings {
    /// No override, for a timer of the family of `timer`.
    pub fn none(timer: TimerSettings) -> Self {
        TimingAgentSettings {
            alpha: None,
            gamma: None,
            lambda: None,
            q_init: None,
            response_cost: None,
            probe: None,
            opportunity_cost: None,
            overdue_factor: None,
            wait_at_oven: None,
            break_and_run: None,
            response_delay: None,
            decision_rule: None,
            timer,
        }
    }

    /// Every parameter's value in `agent` (its defaults, for a freshly built one).
    pub fn of(agent: &TimingAgent) -> Self {
        let timer = match &agent.timer {
            Timer::Ddm(d) => TimerSettings::Ddm {
                noise: Some(d.acc.noise),
                memory_noise: Some(d.memory_noise),
                reproduction_rate: Some(d.reproduction_rate),
            },
            Timer::Sbf(s) => TimerSettings::Sbf {
                memory_noise: Some(s.model.memory_noise),
                clock_noise: Some(s.clock_noise),
            },
            Timer::TimeCells(tc) => TimerSettings::TimeCells {
                memory_noise: Some(tc.memory_noise),
                clock_noise: Some(tc.cells.clock_noise),
            },
        };
        let sarsa = &agent.learner.config;
        TimingAgentSettings {
            alpha: Some(sarsa.alpha),
            gamma: Some(sarsa.gamma),
            lambda: Some(sarsa.lambda),
            q_init: Some(agent.learner.q_init),
            response_cost: Some(agent.config.response_cost),
            probe: Some(agent.config.probe),
            opportunity_cost: Some(agent.config.opportunity_cost),
            overdue_factor: Some(agent.config.overdue_factor),
            wait_at_oven: Some(agent.config.wait_at_oven),
            break_and_run: Some(agent.config.break_and_run),
            response_delay: Some(agent.config.response_delay),
            decision_rule: Some(agent.timer.decision().rule),
            timer,
        }
    }

    /// Writes the overrides into `agent`; an agent of another family is an error.
    pub fn apply(&self, agent: &mut TimingAgent) -> Result<(), TrainError> {
        let put = |slot: &mut f64, v: Option<f64>| {
            if let Some(v) = v {
                *slot = v;
            }
        };
        put(&mut agent.learner.config.alpha, self.alpha);
        put(&mut agent.learner.config.gamma, self.gamma);
        put(&mut agent.learner.config.lambda, self.lambda);
        put(&mut agent.learner.q_init, self.q_init);
        put(&mut agent.config.response_cost, self.response_cost);
        put(&mut agent.config.probe, self.probe);
        put(&mut agent.config.opportunity_cost, self.opportunity_cost);
        put(&mut agent.config.overdue_factor, self.overdue_factor);
        put(&mut agent.config.response_delay, self.response_delay);
        if let Some(w) = self.wait_at_oven {
            agent.config.wait_at_oven = w;
        }
        if let Some(b) = self.break_and_run {
            agent.config.break_and_run = b;
        }
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
        match (self.timer, &mut agent.timer) {
            (
                TimerSettings::Ddm {
                    noise,
                    memory_noise,
                    reproduction_rate,
                },
                Timer::Ddm(d),
            ) => {
                put(&mut d.acc.noise, noise);
                put(&mut d.memory_noise, memory_noise);
                put(&mut d.reproduction_rate, reproduction_rate);
            }
            (
                TimerSettings::Sbf {
                    memory_noise,
                    clock_noise,
                },
                Timer::Sbf(s),
            ) => {
                put(&mut s.model.memory_noise, memory_noise);
                put(&mut s.clock_noise, clock_noise);
            }
            (
                TimerSettings::TimeCells {
                    memory_noise,
                    clock_noise,
                },
                Timer::TimeCells(tc),
            ) => {
                put(&mut tc.memory_noise, memory_noise);
                put(&mut tc.cells.clock_noise, clock_noise);
            }
            (settings, _) => {
                return Err(TrainError::param(
                    "agent.timer",
                    format!("{settings:?}"),
                    &format!("settings of the {} model's family", agent.name),
                ));
            }
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
        "training episodes (6,000; 40,000 on Uncertainty-v0; 60,000 on Reproduction-v0; per level where the reference trains a curriculum: multi-anchor 2, 3, … counters, multi-oven 1, 2, … ovens)",
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
        "final SARSA(lambda) learning rate, annealed from alpha like epsilon (none = constant alpha; 0.005 on Reproduction-v0)",
    ),
    spec(
        "visit_power",
        &["train", "visit_power"],
        UNIT,
        "exponent w of the per-feature step floor n^-w, n = the feature's visits in its state-action pair (Even-Dar & Mansour 2003; 0 = off, 0.85 for the time cells on Reproduction-v0)",
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
