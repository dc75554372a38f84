//! Temporal reproduction (Ready-Set-Go; Jazayeri & Shadlen 2010, Remington et al. 2018; the
//! paper names it as future work): reproduce the interval between two oven cues.

use super::bisection::any_td;
use super::{Family, ResponseKind, RuleSet, TaskSpec, condition, wrong_family};
use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::{ReadySetGo, decimal};
use crate::settings::{self, Rule, Spec, UNIT};
use crate::task::condition::{Condition, ConditionKind};
use crate::task::params::{FIXED_TD_RULE, param};
use crate::task::reset_option::ResetOption;
use crate::task::{AUTO_LAYOUT, REPRODUCTION_LAYOUT, Task, TaskConfig, TaskFamily, TaskParams};

/// The reproduction family.
pub(crate) struct Reproduction;

/// The named priors of the reproduction task: Jazayeri & Shadlen 2010's short
/// (494–847 ms), intermediate (671–1023 ms) and long (847–1200 ms) priors at 1 step ≈ 59 ms,
/// 7 whole steps each, overlapping as theirs do (short and long share their end point).
pub const NAMED_PRIORS: [(&str, u32, u32); 3] =
    [("short", 8, 14), ("intermediate", 11, 17), ("long", 14, 20)];

/// Parses a prior (`short`, `intermediate`, `long` or `LO-HI`) into its inclusive range of
/// whole steps.
pub fn parse_prior(text: &str) -> Result<(u32, u32), EnvError> {
    let t = text.trim();
    if let Some(&(_, lo, hi)) = NAMED_PRIORS.iter().find(|(n, ..)| *n == t) {
        return Ok((lo, hi));
    }
    let bad = || {
        EnvError::param(
            "priors",
            t,
            "short, intermediate, long, or LO-HI with whole steps 1 <= LO < HI <= 1000",
        )
    };
    let (lo, hi) = t.split_once('-').ok_or_else(bad)?;
    let (lo, hi): (u32, u32) = (
        lo.trim().parse().map_err(|_| bad())?,
        hi.trim().parse().map_err(|_| bad())?,
    );
    if lo < 1 || hi <= lo || hi > 1000 {
        return Err(bad());
    }
    Ok((lo, hi))
}

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

const PARAMS: &[Spec] = &[
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

fn distinct_f32(values: &[f32]) -> bool {
    values
        .iter()
        .enumerate()
        .all(|(i, a)| values[i + 1..].iter().all(|b| a != b))
}

/// Every whole-step range of `params`' priors (nothing for other families or bad priors).
fn prior_ranges(params: &TaskParams) -> Vec<(u32, u32)> {
    match params {
        TaskParams::Reproduction { priors, .. } => {
            priors.iter().filter_map(|p| parse_prior(p).ok()).collect()
        }
        _ => Vec::new(),
    }
}

impl Family for Reproduction {
    fn task(&self) -> TaskSpec {
        TaskSpec {
            id: "Reproduction-v0",
            family: TaskFamily::Reproduction,
            tags: &["timing", "reproduction", "production", "ready-set-go"],
            summary: "Temporal reproduction (Ready-Set-Go): reproduce the interval between two oven cues",
            description: "Layout 5x3 `..D/.../V../.../...`: delivery (0,2) code 4, oven (2,0) code 5, loaded \
(no onion). Measurement: after a foreperiod (2-6 steps) the oven flashes Ready (channel 4 = 2 for one \
step), and ts steps later Set; ts is drawn uniformly from the episode's prior (default short 8-14 or \
long 14-20 steps, Jazayeri & Shadlen 2010's priors scaled to steps; the counter's channel 4 shows \
which, prior_cue=true). Production: the oven shows on (1) from Set; taking the soup out tp steps \
after Set produces tp, and delivering it pays max(0, 1 - |tp - g*ts| / w) with w = tolerance*g*ts \
+ tolerance_steps (linear in the error inside a window that scales with the interval, as Jazayeri \
& Shadlen 2010 rewarded; defaults 0.2 and 1 step, NeuroGym ReadySetGo's 0.2*t + c). Taking the soup \
before Set does nothing; a late soup is delivered unpaid (the episode ends at delivery or the \
time limit). Gains g (default 1; 1,1.5 \
as Remington et al. 2018) are cued on the counter. Design decisions (the public code has no \
reproduction task; the paper names it as future work): cues as oven flashes, the loaded oven, \
reward at delivery.",
            source: "paper Discussion (future work); Jazayeri & Shadlen 2010; Remington et al. 2018 (design decisions documented)",
        }
    }

    fn params(&self) -> &'static [Spec] {
        PARAMS
    }

    fn defaults(&self) -> (&'static str, TaskParams) {
        (
            AUTO_LAYOUT,
            TaskParams::Reproduction {
                priors: vec!["short".into(), "long".into()],
                prior_cue: true,
                gains: vec![1.0],
                tolerance: 0.2,
                tolerance_steps: 1.0,
                foreperiod_min: 2,
                foreperiod_max: 6,
            },
        )
    }

    fn auto_layout(&self, _params: &TaskParams) -> &'static str {
        REPRODUCTION_LAYOUT
    }

    fn required_objects(&self, _params: &TaskParams) -> Vec<ObjectKind> {
        vec![ObjectKind::DeliveryCounter, ObjectKind::Oven]
    }

    fn check(&self, config: &TaskConfig) -> Result<(), EnvError> {
        let TaskParams::Reproduction {
            priors,
            gains,
            foreperiod_min,
            foreperiod_max,
            tolerance,
            tolerance_steps,
            ..
        } = &config.params
        else {
            return Err(wrong_family("reproduction", &config.params));
        };
        if priors.is_empty() || priors.len() > 3 {
            return Err(EnvError::param(
                "priors",
                priors.join(","),
                "1 to 3 priors (short, intermediate, long or LO-HI)",
            ));
        }
        let mut longest = 0;
        for p in priors {
            longest = longest.max(parse_prior(p)?.1);
        }
        if gains.is_empty() || gains.len() > 2 || !distinct_f32(gains) {
            return Err(EnvError::param(
                "gains",
                settings::display(&serde_json::json!(gains)),
                "1 or 2 distinct gains in [0.5, 3]",
            ));
        }
        if foreperiod_min > foreperiod_max {
            return Err(EnvError::param(
                "foreperiod_max",
                foreperiod_max,
                format!("integer >= foreperiod_min ({foreperiod_min})"),
            ));
        }
        // The latest response the window pays must fit in the episode.
        let g = gains.iter().copied().fold(0.0f32, f32::max) as f64;
        let target = g * f64::from(longest);
        let latest = f64::from(*foreperiod_max)
            + f64::from(longest)
            + target
            + f64::from(*tolerance) * target
            + f64::from(*tolerance_steps);
        if latest.ceil() as u64 + 1 > u64::from(config.max_timesteps) {
            return Err(EnvError::param(
                "max_timesteps",
                config.max_timesteps,
                format!(
                    "at least {} (foreperiod + longest ts + the latest paid production)",
                    latest.ceil() as u64 + 1
                ),
            ));
        }
        Ok(())
    }

    fn fixed_td_fits(&self, _params: &TaskParams, td: u32) -> bool {
        any_td(td)
    }

    fn rules(&self, config: &TaskConfig, layout: &Layout) -> Result<RuleSet, EnvError> {
        let TaskParams::Reproduction {
            priors,
            prior_cue,
            gains,
            tolerance,
            tolerance_steps,
            foreperiod_min,
            foreperiod_max,
        } = &config.params
        else {
            return Err(wrong_family("reproduction", &config.params));
        };
        let priors = priors
            .iter()
            .map(|p| parse_prior(p))
            .collect::<Result<Vec<_>, _>>()?;
        RuleSet::ready_set_go(ReadySetGo {
            priors,
            gains: gains.clone(),
            tolerance: decimal(f64::from(*tolerance)),
            tolerance_steps: decimal(f64::from(*tolerance_steps)),
            foreperiod: (*foreperiod_min, *foreperiod_max),
            prior_cue: *prior_cue,
            counter: layout.cells_of(ObjectKind::DeliveryCounter)[0],
        })
    }

    fn reward_window(&self, params: &TaskParams) -> Option<(f32, f32)> {
        match params {
            TaskParams::Reproduction {
                tolerance,
                tolerance_steps,
                ..
            } => Some((*tolerance, *tolerance_steps)),
            _ => None,
        }
    }

    fn set_reward_window(&self, params: &mut TaskParams, tol: f32, steps: f32) {
        if let TaskParams::Reproduction {
            tolerance,
            tolerance_steps,
            ..
        } = params
        {
            *tolerance = tol;
            *tolerance_steps = steps;
        }
    }

    fn response_kind(&self) -> Option<ResponseKind> {
        Some(ResponseKind::Reproduce)
    }

    /// The start cell, the sample interval ts (`td`), and the prior and gain indices.
    fn reset_options(&self) -> &'static [ResetOption] {
        &[
            ResetOption::Start,
            ResetOption::Td,
            ResetOption::Prior,
            ResetOption::Gain,
        ]
    }

    fn condition_kind(&self) -> ConditionKind {
        ConditionKind::Reproduction
    }

    /// Every sample interval of every prior, at every gain (the context set by reset
    /// options, so the cue shows as in training).
    fn conditions(&self, task: &Task, config: &TaskConfig) -> Result<Vec<Condition>, EnvError> {
        let TaskParams::Reproduction { priors, gains, .. } = &config.params else {
            return Err(wrong_family("reproduction", &config.params));
        };
        let mut out = Vec::new();
        for (p, prior) in priors.iter().enumerate() {
            let (lo, hi) = parse_prior(prior)?;
            for (g, gain) in gains.iter().enumerate() {
                for ts in lo..=hi {
                    let mut c = condition(ConditionKind::Reproduction, task, ts);
                    c.factor = Some(f64::from(*gain));
                    c.context = Some([p as u8, g as u8]);
                    out.push(c);
                }
            }
        }
        Ok(out)
    }

    /// Every sample interval of the priors, once each, in increasing order.
    fn evaluation_tds(&self, params: &TaskParams) -> Vec<u32> {
        let mut ts: Vec<u32> = prior_ranges(params)
            .into_iter()
            .flat_map(|(lo, hi)| lo..=hi)
            .collect();
        ts.sort_unstable();
        ts.dedup();
        ts
    }

    /// Each prior's shortest and longest sample interval.
    fn demo_conditions(&self, params: &TaskParams) -> Vec<(u32, Option<bool>)> {
        prior_ranges(params)
            .into_iter()
            .flat_map(|(lo, hi)| [(lo, None), (hi, None)])
            .collect()
    }
}
