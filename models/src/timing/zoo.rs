//! Registry of the timing-model agents: names, descriptions, construction.

use crate::timing::agent::{TimingAgent, TimingAgentConfig};
use crate::timing::timers::Timer;
use crate::timing::{FrequencyLayout, Representation};
use chronocooked_env::ChronoEnv;
use chronocooked_env::TaskFamily;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// One timing model of the zoo: its name, what it is, and how its timer is built.
#[derive(Debug, Clone, Copy)]
pub struct TimingModelSpec {
    /// Zoo name.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
    /// Builds the model's untrained timer with its registry defaults (`rng` draws what is
    /// random at construction, e.g. SBF's frequencies); the agent-level defaults (clock
    /// and memory noise, response cost, initial values) are set by [`make_timing_agent`].
    pub build: fn(&mut Xoshiro256PlusPlus) -> Timer,
}

/// Every timing model, in display order.
pub const TIMING_MODELS: [TimingModelSpec; 7] = [
    TimingModelSpec {
        name: "ddm",
        description: "drift-diffusion timer (Simen et al. 2011): z 1, m 0.15 (CV 15%), anchor-memory noise 0.2, drift learning at reinforcement; gates oven checks; SARSA(lambda) over [1, x/z, responding]; bisection: short- and long-anchor drifts, ratio rule",
        build: |_| Timer::ddm(DDM_NOISE),
    },
    TimingModelSpec {
        name: "sbf",
        description: "striatal beat frequency (Matell & Meck 2004): 1000 oscillators 5-15 Hz (random), 25 ms/step, memory noise 0.15, clock noise 0.15, response threshold 0.9; gates oven checks; bisection: coincidence with a criterion pattern at the geometric mean of the anchor memories",
        build: |rng| Timer::sbf(1000, FrequencyLayout::Random, SBF_MEMORY_NOISE, rng),
    },
    TimingModelSpec {
        name: "sbf-even",
        description: "striatal beat frequency with evenly spaced frequencies (aliases at T + k/df)",
        build: |rng| Timer::sbf(1000, FrequencyLayout::Even, SBF_MEMORY_NOISE, rng),
    },
    TimingModelSpec {
        name: "timecells-csc",
        description: "complete serial compound (64-unit delay line), clock noise 0.15, memory noise 0.15 + SARSA(lambda) (Ludvig et al. 2008)",
        build: |_| Timer::time_cells(Representation::csc()),
    },
    TimingModelSpec {
        name: "timecells-ms",
        description: "microstimuli (d 0.95/step, sigma 0.08, m 20), clock noise 0.15, memory noise 0.15 + SARSA(lambda) (Ludvig et al. 2008)",
        build: |_| Timer::time_cells(Representation::microstimulus()),
    },
    TimingModelSpec {
        name: "timecells-presence",
        description: "presence representation (one unit while the oven is on) + SARSA(lambda): cannot time",
        build: |_| Timer::time_cells(Representation::Presence),
    },
    TimingModelSpec {
        name: "timecells-laplace",
        description: "scale-invariant Laplace time cells (24 cells, tau* 1-64 steps, k 8), clock noise 0.15, memory noise 0.15 + SARSA(lambda)",
        build: |_| Timer::time_cells(Representation::laplace()),
    },
];

/// Default diffusion noise `m` of the `ddm` agent: first-passage CV `m/√z` = 15% at
/// threshold `z` = 1, whatever the interval (Simen, Balci, deSouza, Cohen & Holmes 2011:
/// `c = m √A` makes the inverse-Gaussian CV `m/√z`, scalar; CVs of timed responding in
/// rats lie around 0.15–0.35 and in people 0.1–0.3, Gibbon, Church & Meck 1984; Buhusi &
/// Meck 2005). At m = 0.2 the learned first checks ran late at short TDs (FOC/TD 1.32 at
/// TD 6, seed 0). The near-deterministic variant of earlier versions is `--set noise=0.06`.
pub const DDM_NOISE: f64 = 0.15;

/// Default memory noise `κ` of the `sbf` agents: SD of the relative error of a stored time,
/// 15% (Matell & Meck 2004 and Oprisan & Buhusi 2011 obtain scalar timing from variance of
/// the stored oscillator pattern; scalar expectancy theory's memory-constant CV, Gibbon
/// 1977; Gibbon, Church & Meck 1984, is of the same order). The near-deterministic variant
/// of earlier versions is `--set memory_noise=0.05`.
pub const SBF_MEMORY_NOISE: f64 = 0.15;

/// Default clock noise of the `sbf` agents: SD 15% of the log of a per-trial factor scaling
/// every oscillator's frequency (Oprisan & Buhusi 2011 show that trial-to-trial variability
/// of the oscillators' frequencies, like memory variance, gives scalar timing). With memory
/// noise alone the criterion of a bisection judgment varies, the clock does not, and the
/// Weber fraction stayed at 0.04–0.07, with clock noise 0.1 at 0.065–0.10 (below the
/// range animals show, 0.1–0.3). `--set clock_noise=0` for nominal frequencies.
pub const SBF_CLOCK_NOISE: f64 = 0.15;

/// Default memory noise of the anchor memories of a bisection judgment for drift-diffusion
/// (a per-trial factor on each remembered drift; time cells: [`TIME_CELL_MEMORY_NOISE`]):
/// SD of its log, scalar expectancy theory's memory-constant variance
/// (Gibbon 1977; Gibbon, Church & Meck 1984 fit memory CVs of about 0.15–0.3): 0.2. The
/// drift-diffusion judgment reads two accumulators and so averages part of their noise
/// (log-SD ≈ 0.76 m), and time cells stored their estimates exactly: without memory noise
/// their Weber fractions were 0.05–0.1 (drift-diffusion), 0.07–0.13 (microstimuli) and
/// 0.03 (Laplace), below the 0.1–0.3 animals show.
pub const DDM_MEMORY_NOISE: f64 = 0.2;

/// Default memory noise of the time cells' stored anchor estimates: SD of the log of a
/// factor on each stored duration estimate, 0.15 — the low end of scalar expectancy theory's
/// fitted memory CVs (0.15–0.3, Gibbon, Church & Meck 1984) and the SBF agents' memory
/// noise ([`SBF_MEMORY_NOISE`]). The low end because in temporal bisection the referents'
/// memory is the minor source of variance, perception the dominant one (Rodríguez-Gironés &
/// Kacelnik 2001: psychometric functions steeper with fixed than with roving referents;
/// Allan 2002: referent memory "not a dominant source of variability"), and a stored
/// estimate already carries the clock-speed noise of the trial that stored it
/// ([`TIME_CELL_CLOCK_NOISE`]): at 0.15 the memory factor is a quarter of the judgment's
/// log-variance (`c² + (c² + m²)/2` with c = m = 0.15), at 0.2 it was 37%. Measured on
/// five ratio-2 and two ratio-3 pairs, 12 seeds each (RESULTS.md, "Anchor memory of the
/// time cells"): Weber fractions 0.10–0.15 and anchors 0.91–1.00 at 0.15; at 0.2, on the
/// ratio-2 pairs, Weber fractions 0.12–0.17 and anchors 0.87–0.97, 25 of 180 runs below 0.90.
pub const TIME_CELL_MEMORY_NOISE: f64 = 0.15;

/// Default clock-speed noise of the time-cell agents (`timecells-csc`, `-ms`, `-laplace`):
/// SD 15% of the log of a per-trial factor scaling the representation's time, so every
/// cell's peak time varies in proportion to itself (scalar expectancy theory's clock-speed
/// variance, Gibbon 1977; Gibbon, Church & Meck 1984; neither Ludvig, Sutton & Kehoe 2008
/// nor Shankar & Howard 2012 give their representations trial-to-trial variability, so the
/// value is the behavioural CV the other models are given). `--set clock_noise=0` restores
/// the deterministic representations. Laplace time cells had 0.05 until session 15, when
/// their clock-speed factor scaled every cell's amplitude by `r^{−k}` as well as its time
/// (a missing factor in the propagator, `TimeCells::tick`): at 0.15 that made FI first
/// checks non-scalar (CV 0.24–0.72). With the factor fixed, the shared 0.15 gives FI first-check
/// CV 0.14–0.17 at TD 5 and 20 (seeds 0–5; RESULTS.md "Literature-calibrated variability").
pub const TIME_CELL_CLOCK_NOISE: f64 = 0.15;

/// Default internal cost of one interact for the time-cell agents (reward units; 0.01 for
/// the other models). Time cells have no native response gate, so whether to check the
/// oven is itself learned by TD; with a noisy clock and checks that cost almost nothing,
/// checking early is nearly free and the first check drifts to ≈ 0.75 × TD (measured with
/// `scripts/scalar-property.py`, clock noise 0.15, cost 0.01: FOC/TD 0.74–0.79 for
/// microstimuli). At 0.05 first checks came at ≈ TD (0.87–1.01) but the lower-bounded
/// multi-timer failed (delay line 0.00 on seed 0, where 0.01 or an exact clock give 1.00)
/// and microstimuli lost the uncertainty time-out; 0.03 keeps both tasks (1.00) with FOC/TD
/// 0.84–1.04 (RESULTS.md "Timing models"). The cost has no literature value; the rule is the
/// smallest of 0.01, 0.03, 0.05 at which first checks on fixed interval are not early
/// (FOC/TD ≥ 0.8 at TD 4–24): 0.03 for the delay line and microstimuli,
/// [`LAPLACE_RESPONSE_COST`] for Laplace time cells.
pub const TIME_CELL_RESPONSE_COST: f64 = 0.03;

/// Internal check cost of the `timecells-laplace` agent (see [`TIME_CELL_RESPONSE_COST`]):
/// with clock noise 0.15, at 0.03 its FI first-check runs came at 0.80–0.91 × TD at TD 20 and
/// 38–48% of TD-5 trials had an isolated check in the first two steps; at 0.05 at 0.84–1.13 × TD
/// (CV 0.14–0.17) at TD 5 and 20, seeds 0–5 (`python3 scripts/fi-seeds.py`, session 15).
pub const LAPLACE_RESPONSE_COST: f64 = 0.05;

/// Initial value of every unvisited state–action pair of the `timecells-csc` agent
/// (optimistic: the full reward). The complete serial compound gives each step its own
/// unit, so its TD learner is tabular in time and optimistic initial values explore every
/// step systematically (Sutton & Barto 2018, §2.6): ε-greedy alone never learns a one-step
/// window (the dual task: 0% on four seeds), because soup taken early pays the reduced
/// reward at once and skipping it TD − 3 steps in a row is improbable. Measured with
/// optimism: dual 100% on four seeds, FI, bisection and uncertainty unchanged (100%).
/// Dense representations (microstimuli, Laplace) share weights across steps, so a bias
/// cannot be optimistic per step; they keep 0.
pub const CSC_Q_INIT: f64 = 1.0;

/// Initial values in Ready-Set-Go (reproduction) tasks (every model): 0, no optimism.
/// There a response ends the trial, so an optimistic value of responding explores by
/// taking the soup at every (measurement, time) pair of the delay line's `N²` conjunctive
/// code until each has been tried often enough to fall — measured with the CSC's 1.0:
/// 13.7% success after 6000 episodes, every production about half of `ts`.
pub const REPRODUCTION_Q_INIT: f64 = 0.0;

/// Initial value of every unvisited state–action pair of every timing agent on the
/// multi-oven task (optimistic). After a wrong delivery the other ovens' soups are still to
/// come, so its value stays positive, while the untried right counter sits at the initial
/// value: with 0 the greedy policy kept the wrong counter for one oven's soups
/// (drift-diffusion seed 2 on 2 asynchronous ovens, SBF seed 1 on 3: one oven's P(long) flat
/// at 1.0 or 0.0 while the clocks judged it right). The value must exceed what a wrong
/// delivery keeps — at most (n − 1)/n of the episode's reward, discounted over the ≥ 10 steps
/// to the next delivery (γ¹⁰ = 0.74): ≤ 0.49 with 3 ovens — and stay below what a paid
/// delivery on one oven is worth (1): at 1.0 the one-oven probes of 3-oven agents walked into
/// a wall, an untried action tying with the learned delivery (eval has no exploration). At
/// 0.5 the six failing runs of 24 (drift-diffusion, SBF, microstimuli; 2–3 ovens, seeds 1–2)
/// reached an evaluation success of 0.92–1.00 (Sutton & Barto 2018, §2.6, optimistic initial
/// values). The temporal features are off in this task (the ovens show ready), so the
/// optimism holds for dense representations too.
pub const MULTI_OVEN_Q_INIT: f64 = 0.5;

/// Whether `name` is a timing model.
pub fn is_timing_model(name: &str) -> bool {
    TIMING_MODELS.iter().any(|m| m.name == name)
}

/// Whether timing model `name` gates its responses natively ([`Timer::has_gate`]:
/// drift-diffusion and SBF respond when their clock says so; the time cells' responses are
/// learned by TD). `None` for an unknown name.
pub fn has_native_gate(name: &str) -> Option<bool> {
    let spec = TIMING_MODELS.iter().find(|m| m.name == name)?;
    Some((spec.build)(&mut Xoshiro256PlusPlus::seed_from_u64(0)).has_gate())
}

/// Builds an untrained timing agent `name` for `env`'s task (`seed` draws SBF frequencies).
/// Errors name the allowed values.
pub fn make_timing_agent(name: &str, env: &ChronoEnv, seed: u64) -> Result<TimingAgent, String> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let Some(spec) = TIMING_MODELS.iter().find(|m| m.name == name) else {
        let names: Vec<&str> = TIMING_MODELS.iter().map(|m| m.name).collect();
        return Err(format!(
            "unknown timing model `{name}`; allowed: {}",
            names.join(", ")
        ));
    };
    if env.config().response_kind().is_none() {
        return Err(format!(
            "task {} declares no response the timing models know (produce an interval, \
             categorise a duration, reproduce one: its family's `response_kind`); \
             train a PPO model on it instead",
            env.config().id
        ));
    }
    let timer = (spec.build)(&mut rng);
    let mut agent = TimingAgent::new(name, timer, env, TimingAgentConfig::default());
    if name == "timecells-csc" {
        agent.learner.q_init = CSC_Q_INIT;
    }
    if env.family() == TaskFamily::MultiOven {
        agent.learner.q_init = MULTI_OVEN_Q_INIT;
    }
    if env.ready_set_go().is_some() {
        agent.learner.q_init = REPRODUCTION_Q_INIT;
    }
    match &mut agent.timer {
        Timer::TimeCells(tc) if !matches!(tc.cells.repr, Representation::Presence) => {
            tc.cells.clock_noise = TIME_CELL_CLOCK_NOISE;
            tc.memory_noise = TIME_CELL_MEMORY_NOISE;
            agent.config.response_cost = match tc.cells.repr {
                Representation::Laplace { .. } => LAPLACE_RESPONSE_COST,
                _ => TIME_CELL_RESPONSE_COST,
            };
        }
        Timer::Sbf(s) => s.clock_noise = SBF_CLOCK_NOISE,
        Timer::Ddm(d) => d.memory_noise = DDM_MEMORY_NOISE,
        _ => {}
    }
    Ok(agent)
}

/// Why a timing model cannot meet a task's reference success (≥ 90%), by mechanism, or
/// `None` where it learns the task (or the limit is not a mechanism: see the notes).
/// `task` is a registered task id; `exact_window` says whether the full reward needs the
/// soup taken inside a window of one step (multi-timer `mode=exact`, the dual task with
/// zero buffers — the defaults).
pub fn task_limit(model: &str, task: &str, exact_window: bool) -> Option<&'static str> {
    let timed = !matches!(task, "FixedInterval-v0" | "PeakInterval-v0");
    if model == "timecells-presence" && timed && task != "MultiTimer-v0" {
        return Some(PRESENCE_LIMIT);
    }
    if !exact_window {
        return None;
    }
    match model {
        "timecells-presence" => Some(PRESENCE_LIMIT),
        "ddm" => Some(
            "scalar variability: the response time has SD = CV x TD (default CV = m/sqrt(z) = 0.15), \
             so a tuned timer lands in a one-step window with probability 2*Phi(0.5/(0.15 TD)) - 1 \
             = 0.42 at TD 6, 0.29 at TD 9, 0.18 at TD 15 (>= 90% only at TD 1)",
        ),
        "sbf" | "sbf-even" => Some(
            "temporal resolution: the coincidence envelope |sinc(pi df (t - T))| of 5-15 Hz \
             oscillators is ~4 steps wide at 25 ms/step (first zero at 100 ms) and memory noise \
             scales with T, so the response cannot be confined to one step",
        ),
        "timecells-ms" => Some(
            "temporal resolution: microstimuli are Gaussian in trace height (sigma 0.08); at TD 9-15 \
             one step moves the trace by 0.032-0.024 (0.4-0.3 sigma), and clock noise (0.15) \
             moves the trace's time by 15%, so a linear readout cannot respond at one step only",
        ),
        "timecells-laplace" => Some(
            "scale invariance: a Laplace time cell's width grows with its peak time (CV \
             1/sqrt(k+1) = 0.33), ~3-5 steps at TD 9-15, so a linear readout cannot respond at \
             one step only",
        ),
        "timecells-csc" => Some(
            "scalar variability: the default clock noise (0.15) moves the unit active at TD by \
             15% of TD from trial to trial, so no readout lands in a one-step window on every \
             trial; with clock_noise=0 the delay line (one unit per step, optimistic initial \
             values) learns one-step windows (dual task: 100%)",
        ),
        _ => None,
    }
}

/// Why the presence representation cannot do the timed tasks.
const PRESENCE_LIMIT: &str = "no elapsed-time information: the single presence unit is constant while the oven is on, so no readout can tell one elapsed time from another (it solves fixed interval and the lower-bounded multi-timer only by checking repeatedly)";
