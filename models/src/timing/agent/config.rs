//! The settings of a timing agent ([`TimingAgentConfig`]) and their literature defaults.

use crate::timing::sarsa::SarsaConfig;
use serde::{Deserialize, Serialize};

/// Settings of a [`super::TimingAgent`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimingAgentConfig {
    /// TD learner.
    pub sarsa: SarsaConfig,
    /// Exploration rate while training (the trainer anneals it).
    pub epsilon: f64,
    /// Internal cost of one interact (effort), subtracted from the TD reward.
    pub response_cost: f64,
    /// Fraction by which a first-check success shortens the reinforced interval.
    pub probe: f64,
    /// Step size `β` of the learned reward rate `ρ` (reward per step) charged on every step
    /// as the opportunity cost of time — average-reward TD, the tonic-dopamine account of
    /// Niv, Daw, Joel & Dayan (2007): `δ = r − ρ + γ Q' − Q`, `ρ ← ρ + β (r − ρ)`. With it,
    /// wandering away from a task is never free. 0 = off (plain discounted SARSA(λ)).
    #[serde(default)]
    pub opportunity_cost: f64,
    /// The time-out category: once the running interval is this many times the model's
    /// expected time without the task's ready cue ([`Timer::overdue`]: drift-diffusion
    /// `x ≥ k z`, SBF past `k ×` its remembered time; tasks that show a ready cue only), the
    /// TD learner sees the model's categorical "overdue" output (the expected cue was
    /// omitted) instead of its temporal features. The default 1.5 is where the peak
    /// procedure's responding stops, about 1.5–2 × the expected time (Church, Meck & Gibbon
    /// 1994), and the subject turns to other behaviour. 0 = off, and then the temporal
    /// features also stay on (frozen) after the uncertainty task's interval ends: the agent
    /// as it was before the category (agents saved then load with 0).
    #[serde(default)]
    pub overdue_factor: f64,
    /// Wait at the oven while timing: in tasks where nothing but the soup pays during the
    /// interval (no reward sink, no oven button — fixed and peak interval, multi-timer,
    /// bisection), an empty-handed agent next to the running oven may only wait or check,
    /// not walk. Otherwise the TD learner can time the interval with a fixed walking route
    /// (a mediating behaviour whose length is a clock of its own) and the model's
    /// mechanism no longer sets the behaviour: measured with `false`, drift-diffusion
    /// seed 3 at TD 5 and microstimuli seed 2 at TD 8 checked at exactly TD every trial
    /// (CV 0.00 and 0.02) after such a route; on bisection 6-12 (waiting only on the
    /// cue-less tasks, session 14) microstimuli seed 2 stood at different cells when the
    /// short and the long anchor ended, chose the counter by where it stood, and sent
    /// probes of 1 and 2 steps — picked up from the cell it put the onion from — to the
    /// long counter (P(long) 1.00, a non-monotone curve). A gated model whose responding
    /// has stopped (drift-diffusion, SBF past their stop) may leave. Agents saved before
    /// the setting load with `false` (their behaviour unchanged).
    #[serde(default)]
    pub wait_at_oven: bool,
    /// Break-and-run responding of the time-cell agents while waiting at the oven (with
    /// [`Self::wait_at_oven`], in the same tasks except those with a ready cue, where a
    /// check never pays). Drift-diffusion and SBF have a response state of their own — the
    /// gate, open from the threshold crossing to the stop — so this rule is theirs already
    /// (applied on top of the gate it changed SBF's multi-timer training: TD 12 0.38 → 0.00
    /// on seed 0). Time cells have no such state: once the agent has checked the running oven in this interval, it
    /// keeps checking unless its TD readout values waiting above checking by more than one
    /// response cost (`Q(wait) − Q(check) > response_cost`) — a start needs only that a
    /// check is worth more than waiting, a stop needs evidence beyond the cost of one more
    /// response. Fixed-interval responding is a pause followed by an abrupt transition to a
    /// steady high rate that lasts until reinforcement (Schneider 1969; Gallistel, Fairhurst
    /// & Balsam 2004), and a peak-procedure trial has a single run, one start and one stop
    /// (Church, Meck & Gibbon 1994). Without it the greedy readout, whose check-vs-wait
    /// margin near the expected time is about one response cost, alternated checks and
    /// waits in 45–92% of delay-line trials at TD 5 and 20, and the paper's first oven
    /// check — the start of the unbroken run of interacts that ends in the pickup — then
    /// measured the last burst, not the start of responding. Agents saved before the
    /// setting load with `false` (their behaviour unchanged).
    #[serde(default)]
    pub break_and_run: bool,
    /// Ready-Set-Go tasks, time cells: exploration of later responses. When the learner is
    /// about to take the soup during a production, with probability ε (the exploration
    /// rate) it waits instead and responds `z` steps later, `z` uniform on
    /// `1 ..= ⌈response_delay · t⌉` at production time `t` (a span that scales with the
    /// elapsed time, as timing noise does). ε-greedy alone tries a response time later
    /// than the greedy one only with two exploratory actions in a row (wait where it would
    /// respond, then respond where it would wait: about 0.5% of trials at ε 0.15), so the
    /// values of later responses stay at their initial value and the learned production
    /// stays early; this is temporally extended exploration in the sense of Dabney,
    /// Ostrovski & Barreto (2021, ε z-greedy): one exploratory decision held for a random
    /// duration. 0 = off (agents saved before the setting load with 0).
    #[serde(default)]
    pub response_delay: f64,
}

/// Episodes per start cell and condition in the reference protocol for a timing agent with
/// internal noise ([`crate::agent::Agent::noise_draws`]): with 8–12 free start cells, 128–192 episodes
/// per condition. A logistic fit to 8 episodes per probe is nearly separated and
/// underestimates the Weber fraction; at 32 per probe (4 draws, until session 16) an anchor
/// accuracy of 0.93 was measured with a binomial SE of ≈ 0.03, so one evaluation fell below
/// 0.90 about one time in five. 128 per probe halves that SE.
pub const NOISE_DRAWS: usize = 16;

/// Default [`TimingAgentConfig::response_delay`]: later responses are explored up to a
/// quarter of the elapsed production time — about twice the scalar spread of produced
/// intervals (Weber fractions ≈ 0.1–0.15 in Jazayeri & Shadlen 2010), so one delay reaches
/// past the production's own noise. Measured on priors no doc uses (10–16 with 15–21,
/// seed 1, noise-free delay line, 60,000 episodes): productions 0.88–1.00 × `ts` without
/// it, 0.94–1.00 with it.
pub const RESPONSE_DELAY: f64 = 0.25;

/// Default [`TimingAgentConfig::overdue_factor`].
pub const OVERDUE_FACTOR: f64 = 1.5;

impl Default for TimingAgentConfig {
    fn default() -> Self {
        TimingAgentConfig {
            sarsa: SarsaConfig::default(),
            epsilon: 0.1,
            response_cost: 0.01,
            probe: 0.15,
            opportunity_cost: 0.0,
            overdue_factor: OVERDUE_FACTOR,
            wait_at_oven: true,
            break_and_run: true,
            response_delay: RESPONSE_DELAY,
        }
    }
}
