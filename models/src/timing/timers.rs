//! The timing models as the temporal part of an agent: started at oven-on, advanced one
//! step at a time, read out as features for TD learning and (drift-diffusion, SBF) as a
//! native "respond now" gate, and trained by their own rule at reinforcement.
//!
//! Time unit: one env step. Memories are kept per visible context (the oven cue value),
//! so a multi-timer agent stores one interval per coloured light. In bisection each model
//! also keeps memories of the two anchors and judges every interval by comparing with them
//! ([`crate::timing::judgment`]).

mod choices;

use crate::timing::judgment::{
    Categories, CategoryMemory, Decision, DecisionRule, LONG, SHORT, can_judge, ddm_ratio_rule,
    remembered_slots,
};
use crate::timing::{BeatFrequency, DriftDiffusion, FrequencyLayout, Representation, TimeCells};
use rand::Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Drift-diffusion timer of an agent: one learned drift per context.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DdmTimer {
    /// The accumulator (threshold `z`, noise `m`; its drift is set per context at onset).
    pub acc: DriftDiffusion,
    /// Drift before any learning: `z / initial_interval`.
    pub initial_interval: f64,
    /// Learned drifts per context.
    pub drifts: BTreeMap<u8, f64>,
    /// Drift learning rate `α` (1 = one-shot).
    pub rate: f64,
    /// Respond from `x ≥ start · z` …
    pub start: f64,
    /// … until `x ≥ stop · z` (`None`: never stop; peak-interval behaviour when set).
    pub stop: Option<f64>,
    /// Drifts learned per bisection choice slot (`z/S`, `z/L`) from that anchor's rewarded
    /// intervals.
    #[serde(default)]
    pub choice_drifts: BTreeMap<u8, f64>,
    /// Bisection decision rule (where the criterion lies between the anchors).
    #[serde(default)]
    pub decision: Decision,
    /// Memory noise of the anchor drifts: SD of the log of a per-trial factor on each
    /// remembered drift (a reference-memory sample, Gibbon, Church & Meck 1984); 0 = exact.
    #[serde(default)]
    pub memory_noise: f64,
    /// Drift learning rate at Set in the reproduction task (Ready-Set-Go): the drift of
    /// the context learns the measured interval with [`DriftDiffusion::learn`] at this rate
    /// and the production runs on it. 1 = Simen et al. (2011)'s one-shot duration learning
    /// (the trial's own measurement); below 1 the drift averages the context's past
    /// measurements (memory averaging, a regression to the mean of the prior).
    #[serde(default = "one_shot")]
    pub reproduction_rate: f64,
    /// This trial's accumulator of each remembered anchor, with its slot, in slot order
    /// (fewer than two: no judgment).
    #[serde(skip)]
    choice_acc: Vec<(u8, DriftDiffusion)>,
}

fn one_shot() -> f64 {
    1.0
}

/// A trial's clock-speed factor `exp(σ ε)`, `ε ~ N(0, 1)`; exactly 1 (no draw) at `σ` 0.
fn speed_sample<R: Rng + ?Sized>(sigma: f64, rng: &mut R) -> f64 {
    memory_sample(sigma, rng)
}

/// A multiplicative memory factor `exp(σ ε)`, `ε ~ N(0, 1)`; exactly 1 (no draw) at `σ` 0.
fn memory_sample<R: Rng + ?Sized>(sigma: f64, rng: &mut R) -> f64 {
    if sigma > 0.0 {
        (sigma * rng.sample::<f64, _>(StandardNormal)).exp()
    } else {
        1.0
    }
}

impl DdmTimer {
    /// The accumulator at time 0 on the drift remembered for context `ctx` (the initial
    /// drift `z / initial_interval` before any), with no anchor accumulators.
    fn start_in_context(&mut self, ctx: u8) {
        self.acc.reset();
        self.acc.drift = *self
            .drifts
            .get(&ctx)
            .unwrap_or(&(self.acc.threshold / self.initial_interval));
        self.choice_acc.clear();
    }

    /// The remembered anchors `(S*, L*) = (z/A_S, z/A_L)` (steps) from the learned drifts.
    fn anchor_memories(&self) -> Option<(f64, f64)> {
        let z = self.acc.threshold;
        let s = self.choice_drifts.get(&SHORT)?;
        let l = self.choice_drifts.get(&LONG)?;
        Some((z / s, z / l))
    }

    /// The category of the interval that just ended among `k` anchors: the boundaries its
    /// anchor accumulators have passed. Between neighbours `i`, `i + 1` the ratio rule is
    /// [`ddm_ratio_rule`] on their two accumulators; another rule compares their
    /// geometric-average reading `√(x_i/A_i · x_{i+1}/A_{i+1})` with its criterion between
    /// the remembered anchors `z/A`.
    fn category(&self, k: usize) -> Option<u8> {
        if !can_judge(k, self.choice_acc.len()) {
            return None;
        }
        let z = self.acc.threshold;
        let memories: Vec<(u8, f64)> = self
            .choice_acc
            .iter()
            .map(|&(slot, _)| Some((slot, z / *self.choice_drifts.get(&slot)?)))
            .collect::<Option<_>>()?;
        let categories = Categories::new(&memories, &self.decision)?;
        let mut passed = 0;
        for (pair, criterion) in self.choice_acc.windows(2).zip(&categories.boundaries) {
            let (a, b) = (&pair[0].1, &pair[1].1);
            let reached = if self.decision.rule == DecisionRule::Ratio {
                ddm_ratio_rule(a.x, b.x, z)
            } else {
                let tau = (a.x / a.drift * b.x / b.drift).sqrt();
                a.x > 0.0 && b.x > 0.0 && tau >= *criterion
            };
            passed += usize::from(reached);
        }
        Some(categories.slot_after(passed))
    }
}

/// Striatal beat-frequency timer of an agent. Reference memory: the last
/// [`SBF_MEMORY`] stored times per context (the stored pattern of a time `T` is `x(T)`, so
/// keeping times keeps the weight vectors); each trial's coincidence detector is one of
/// them drawn at random (trial-to-trial memory noise → scalar property).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SbfTimer {
    /// Oscillators, memory noise, manipulations.
    pub model: BeatFrequency,
    /// Model seconds per env step.
    pub seconds_per_step: f64,
    /// Response threshold on the detector envelope (0–1).
    pub threshold: f64,
    /// Stored times (s) per context.
    pub memories: BTreeMap<u8, Vec<f64>>,
    /// Stored times (s) per rewarded choice slot (bisection: short / long counter; the
    /// last [`crate::timing::judgment::CATEGORY_MEMORY`] each).
    pub choice_memories: BTreeMap<u8, Vec<f64>>,
    /// Stop responding `stop × (start time)` after starting (`None`: never).
    pub stop: Option<f64>,
    /// Bisection decision rule (where the criterion pattern is stored between the anchors).
    #[serde(default)]
    pub decision: Decision,
    /// Clock noise: SD of the log of a per-trial factor scaling every oscillator's
    /// frequency (trial-to-trial oscillator-frequency variability, Oprisan & Buhusi 2011);
    /// 0 = the oscillators run at their nominal frequencies every trial.
    #[serde(default)]
    pub clock_noise: f64,
    #[serde(skip)]
    rt: Box<SbfRuntime>,
}

/// Envelope (0–1) from which the SBF agent responds: the coincidence detector's match to
/// its remembered pattern. For 5–15 Hz oscillators at 25 ms per step the envelope is
/// `≈ |sinc(0.25 (t − T))|` (t in steps), so responding begins ≈ 1 step before the
/// remembered time at 0.9 (≈ 1.8 steps at the earlier 0.7, which made first checks at
/// TD 4 come at 0.73 × TD; responding only once the envelope had peaked came 10–25% late,
/// through the memories reinforced at late pickups).
pub const SBF_RESPONSE_THRESHOLD: f64 = 0.9;

/// Envelope above which the bisection criterion's coincidence counts as reached.
pub const SBF_CRITERION_THRESHOLD: f64 = 0.5;

/// Per-trial state of an SBF timer: oscillator phases and the complex detector weights
/// `[this trial's memory sample, criterion 1, criterion 2, …]` (empty = nothing stored).
#[derive(Debug, Clone, PartialEq, Default)]
struct SbfRuntime {
    now: f64,
    step: Option<u32>,
    cos: Vec<f64>,
    sin: Vec<f64>,
    rot: Vec<(f64, f64)>,
    detectors: Vec<(Vec<f64>, Vec<f64>)>,
    /// Envelope of each detector (index as `detectors`).
    readouts: Vec<f64>,
    template: Option<f64>,
    /// Criterion times (s) of this trial: one per boundary between neighbouring anchor
    /// slots (empty until two slots are stored).
    criteria: Vec<f64>,
    /// The slots the criteria separate (one more than the criteria).
    criterion_slots: Vec<u8>,
    /// This trial's clock-speed factor (0 before the first onset: read as 1).
    speed: f64,
    /// Per criterion: its detector's envelope has reached [`SBF_CRITERION_THRESHOLD`] …
    criterion_reached: Vec<bool>,
    /// … and has since peaked: that criterion time has passed.
    criterion_passed: Vec<bool>,
}

/// Stored times kept per SBF context memory (the interval of each fixed-interval context);
/// the anchors of choices keep [`crate::timing::judgment::CATEGORY_MEMORY`].
pub const SBF_MEMORY: usize = 20;

impl SbfTimer {
    /// Appends `t` to `memory`, dropping the oldest beyond `capacity` times.
    fn store(memory: &mut Vec<f64>, t: f64, capacity: usize) {
        if memory.len() >= capacity {
            memory.remove(0);
        }
        memory.push(t);
    }

    /// Complex detector weights `mean_j exp(i 2π fᵢ T_j)` of stored times `times`.
    fn detector(&self, times: &[f64]) -> (Vec<f64>, Vec<f64>) {
        if times.is_empty() {
            return (Vec::new(), Vec::new());
        }
        let n = times.len() as f64;
        let two_pi = 2.0 * std::f64::consts::PI;
        self.model
            .freqs
            .iter()
            .map(|f| {
                times.iter().fold((0.0, 0.0), |(c, s), t| {
                    let (sn, cs) = (two_pi * f * t).sin_cos();
                    (c + cs / n, s + sn / n)
                })
            })
            .unzip()
    }

    fn sample<R: Rng + ?Sized>(memory: Option<&Vec<f64>>, rng: &mut R) -> Option<f64> {
        memory
            .filter(|m| !m.is_empty())
            .map(|m| m[rng.random_range(0..m.len())])
    }

    fn onset<R: Rng + ?Sized>(&mut self, ctx: u8, categories: usize, rng: &mut R) {
        let template = Self::sample(self.memories.get(&ctx), rng);
        // One sample of each remembered anchor (`judgment::remembered_slots`; nothing is
        // drawn until a judgment can be made): a chain of criteria, one per boundary
        // between neighbouring slots.
        let known = remembered_slots(categories, |slot| {
            let m = self.choice_memories.get(&slot).filter(|m| !m.is_empty())?;
            Some(m.len() as f64)
        });
        let anchors = if can_judge(categories, known.len()) {
            remembered_slots(categories, |slot| {
                Self::sample(self.choice_memories.get(&slot), rng)
            })
        } else {
            Vec::new()
        };
        let judged = Categories::new(&anchors, &self.decision);
        let criteria = judged
            .as_ref()
            .map(|c| c.boundaries.clone())
            .unwrap_or_default();
        let mut detectors = vec![self.detector(template.as_slice())];
        detectors.extend(criteria.iter().map(|&c| self.detector(&[c])));
        let n = criteria.len();
        let speed = speed_sample(self.clock_noise, rng);
        *self.rt = SbfRuntime {
            template,
            readouts: vec![0.0; detectors.len()],
            criteria,
            criterion_slots: judged.map(|c| c.slots).unwrap_or_default(),
            detectors,
            speed,
            criterion_reached: vec![false; n],
            criterion_passed: vec![false; n],
            ..SbfRuntime::default()
        };
        let w = 2.0 * std::f64::consts::PI * self.speed() * self.seconds_per_step;
        self.rt.rot = self.model.freqs.iter().map(|f| (w * f).sin_cos()).collect();
    }

    /// Starts the oscillators at phase 0 with clock-speed factor `speed` and one detector of
    /// the stored time `template` (s; `None`: nothing to match): the reproduction task's
    /// Ready (no template) and Set (the pattern stored at Set).
    fn start_clock(&mut self, template: Option<f64>, speed: f64) {
        let detectors = vec![self.detector(template.as_slice())];
        *self.rt = SbfRuntime {
            template,
            readouts: vec![0.0; detectors.len()],
            detectors,
            speed,
            ..SbfRuntime::default()
        };
        let w = 2.0 * std::f64::consts::PI * self.speed() * self.seconds_per_step;
        self.rt.rot = self.model.freqs.iter().map(|f| (w * f).sin_cos()).collect();
    }

    /// Model seconds this trial's clock measured for an interval of `steps` env steps: the
    /// trial's speed factor times the nominal time (the manipulation `k` is a distortion of
    /// the running clock only, so memories stay in normal-speed time).
    fn subjective(&self, steps: f64) -> f64 {
        let trial = if self.rt.speed > 0.0 {
            self.rt.speed
        } else {
            1.0
        };
        steps * self.seconds_per_step * trial
    }

    /// The running clock's speed: the manipulation `k` times this trial's factor.
    fn speed(&self) -> f64 {
        let trial = if self.rt.speed > 0.0 {
            self.rt.speed
        } else {
            1.0
        };
        self.model.clock_speed * trial
    }

    /// Oscillators at `t` steps and every detector's envelope `|Σ e^{iφᵢ} conj(Wᵢ)| / N`.
    fn advance(&mut self, t: u32) {
        let speed = self.speed();
        let rt = &mut self.rt;
        rt.now = t as f64 * self.seconds_per_step;
        if rt.step.is_some_and(|k| k + 1 == t) && rt.rot.len() == rt.cos.len() {
            // One step later: rotate every phasor by e^{i 2π k fᵢ Δt}.
            for ((c, s), (rs, rc)) in rt.cos.iter_mut().zip(rt.sin.iter_mut()).zip(&rt.rot) {
                let (c0, s0) = (*c, *s);
                *c = c0 * rc - s0 * rs;
                *s = s0 * rc + c0 * rs;
            }
        } else {
            let w = 2.0 * std::f64::consts::PI * speed * rt.now;
            rt.cos.clear();
            rt.sin.clear();
            for f in &self.model.freqs {
                let (sn, cs) = (w * f).sin_cos();
                rt.cos.push(cs);
                rt.sin.push(sn);
            }
        }
        rt.step = Some(t);
        let n = self.model.freqs.len().max(1) as f64;
        let two_pi_k = 2.0 * std::f64::consts::PI * speed;
        rt.readouts.resize(rt.detectors.len().max(1), 0.0);
        for (k, (c, s)) in rt.detectors.iter().enumerate() {
            if c.is_empty() {
                rt.readouts[k] = 0.0;
                continue;
            }
            // z = Σ e^{iφᵢ} conj(Wᵢ) / N and, for the criterion, dz/dt = Σ iωᵢ e^{iφᵢ} conj(Wᵢ) / N.
            let (mut re, mut im, mut dre, mut dim) = (0.0, 0.0, 0.0, 0.0);
            for i in 0..c.len() {
                let (a, b) = (
                    rt.cos[i] * c[i] + rt.sin[i] * s[i],
                    rt.sin[i] * c[i] - rt.cos[i] * s[i],
                );
                re += a;
                im += b;
                if k >= 1 {
                    let w = two_pi_k * self.model.freqs[i];
                    dre -= w * b;
                    dim += w * a;
                }
            }
            rt.readouts[k] = (re * re + im * im).sqrt() / n;
            if k >= 1 {
                // d|z|²/dt = 2 Re(conj(z) dz/dt): the envelope is falling after its peak.
                let falling = re * dre + im * dim <= 0.0;
                let j = k - 1;
                if rt.readouts[k] >= SBF_CRITERION_THRESHOLD {
                    rt.criterion_reached[j] = true;
                    rt.criterion_passed[j] |= falling;
                } else if rt.criterion_reached[j] {
                    rt.criterion_passed[j] = true;
                }
            }
        }
    }
}

/// Time cells as an agent's timer: the population and its bisection memories.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimeCellTimer {
    /// The population.
    pub cells: TimeCells,
    /// Decoded log durations of the rewarded short and long trials.
    #[serde(default)]
    pub anchors: CategoryMemory,
    /// Bisection decision rule (where the criterion lies between the anchors).
    #[serde(default)]
    pub decision: Decision,
    /// Memory noise: SD of the log of a factor on each stored anchor estimate (scalar
    /// expectancy theory's memory-constant variance, Gibbon 1977); 0 = exact storage.
    #[serde(default)]
    pub memory_noise: f64,
    /// This trial's remembered anchors `(slot, steps)`, sampled at onset.
    #[serde(skip)]
    trial_anchors: Vec<(u8, f64)>,
}

/// Which timing model an agent uses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Timer {
    /// Drift-diffusion accumulator.
    Ddm(DdmTimer),
    /// Striatal beat frequency.
    Sbf(SbfTimer),
    /// Time cells / microstimuli / CSC / presence (timing learned by TD alone).
    TimeCells(TimeCellTimer),
}

impl Timer {
    /// Drift-diffusion timer: `z` 1, noise `m`, initial interval 8 steps, rate 0.1.
    pub fn ddm(noise: f64) -> Self {
        Timer::Ddm(DdmTimer {
            acc: DriftDiffusion::new(1.0 / 8.0, 1.0, noise),
            initial_interval: 8.0,
            drifts: BTreeMap::new(),
            rate: 0.1,
            start: 1.0,
            stop: None,
            choice_drifts: BTreeMap::new(),
            decision: Decision::default(),
            memory_noise: 0.0,
            reproduction_rate: one_shot(),
            choice_acc: Vec::new(),
        })
    }

    /// SBF timer: `n` oscillators 5–15 Hz, 25 ms per step, memory noise `kappa`.
    pub fn sbf<R: Rng + ?Sized>(
        n: usize,
        layout: FrequencyLayout,
        kappa: f64,
        rng: &mut R,
    ) -> Self {
        let mut model = BeatFrequency::new(n, 5.0, 15.0, layout, rng);
        model.memory_noise = kappa;
        model.learning_rate = 0.5;
        Timer::Sbf(SbfTimer {
            model,
            seconds_per_step: 0.025,
            threshold: SBF_RESPONSE_THRESHOLD,
            memories: BTreeMap::new(),
            choice_memories: BTreeMap::new(),
            stop: None,
            decision: Decision::default(),
            clock_noise: 0.0,
            rt: Box::default(),
        })
    }

    /// Time-cell representation.
    pub fn time_cells(repr: Representation) -> Self {
        Timer::TimeCells(TimeCellTimer {
            cells: TimeCells::new(repr),
            anchors: CategoryMemory::default(),
            decision: Decision::default(),
            memory_noise: 0.0,
            trial_anchors: Vec::new(),
        })
    }

    /// Number of temporal features handed to the TD learner (bias excluded).
    pub fn n_features(&self) -> usize {
        match self {
            Timer::Ddm(_) => 2,
            Timer::Sbf(_) => 2,
            Timer::TimeCells(tc) => tc.cells.repr.size(),
        }
    }

    /// Whether any of the model's noise sources is on (its behaviour varies from trial to
    /// trial with its RNG).
    pub fn is_noisy(&self) -> bool {
        match self {
            Timer::Ddm(d) => d.acc.noise > 0.0 || d.memory_noise > 0.0,
            Timer::Sbf(s) => s.model.memory_noise > 0.0 || s.clock_noise > 0.0,
            Timer::TimeCells(tc) => tc.cells.clock_noise > 0.0 || tc.memory_noise > 0.0,
        }
    }

    /// The same timer with every noise source off ([`Self::is_noisy`] false): diffusion and
    /// memory noise (drift-diffusion), memory and clock noise (SBF), clock-speed and
    /// memory noise (time cells) — the setting of the mechanisms' exact known answers.
    pub fn noise_free(mut self) -> Self {
        match &mut self {
            Timer::Ddm(d) => {
                d.acc.noise = 0.0;
                d.memory_noise = 0.0;
            }
            Timer::Sbf(s) => {
                s.model.memory_noise = 0.0;
                s.clock_noise = 0.0;
            }
            Timer::TimeCells(tc) => {
                tc.cells.clock_noise = 0.0;
                tc.memory_noise = 0.0;
            }
        }
        self
    }

    /// Whether the model gates oven checks natively.
    pub fn has_gate(&self) -> bool {
        !matches!(self, Timer::TimeCells(_))
    }

    /// Clears the clock (episode start).
    pub fn clear(&mut self) {
        match self {
            Timer::Ddm(d) => {
                d.acc.reset();
                d.choice_acc.clear();
            }
            Timer::Sbf(s) => *s.rt = SbfRuntime::default(),
            Timer::TimeCells(tc) => tc.cells.clear(),
        }
    }

    /// The timed event (oven on) in context `ctx` of a task with `categories` choice slots
    /// (2 in bisection): reset to time 0; `rng` draws this trial's memory samples.
    pub fn onset<R: Rng + ?Sized>(&mut self, ctx: u8, categories: usize, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                d.start_in_context(ctx);
                let drifts =
                    remembered_slots(categories, |slot| d.choice_drifts.get(&slot).copied());
                if can_judge(categories, drifts.len()) {
                    for (slot, drift) in drifts {
                        let mut acc = d.acc.clone();
                        // This trial's sample of the anchor's drift memory.
                        acc.drift = drift * memory_sample(d.memory_noise, rng);
                        d.choice_acc.push((slot, acc));
                    }
                }
            }
            Timer::Sbf(s) => s.onset(ctx, categories, rng),
            Timer::TimeCells(tc) => {
                let speed = speed_sample(tc.cells.clock_noise, rng);
                tc.cells.onset_with_speed(speed);
                tc.trial_anchors = remembered_slots(categories, |slot| tc.anchors.draw(slot, rng));
            }
        }
    }

    /// Ready in the reproduction task (Ready-Set-Go) of context `ctx`: the measurement
    /// epoch starts at time 0. Drift-diffusion ramps on the context's remembered drift,
    /// SBF's oscillators start in phase with this trial's speed factor, the time cells
    /// start with theirs.
    pub fn begin_measurement<R: Rng + ?Sized>(&mut self, ctx: u8, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                d.start_in_context(ctx);
            }
            Timer::Sbf(s) => {
                let speed = speed_sample(s.clock_noise, rng);
                s.start_clock(None, speed);
            }
            Timer::TimeCells(tc) => {
                let speed = speed_sample(tc.cells.clock_noise, rng);
                tc.cells.onset_with_speed(speed);
                tc.trial_anchors.clear();
            }
        }
    }

    /// Set in the reproduction task: the measurement epoch of context `ctx` ended after
    /// `ts` steps and the production of `gain × ts` starts at time 0, each model with its
    /// own machinery:
    /// * drift-diffusion learns the drift of the context from the accumulator at Set
    ///   ([`DriftDiffusion::learn`] at [`DdmTimer::reproduction_rate`]: `A ← A z/x(ts)` one
    ///   shot) and ramps again from 0 on that drift divided by the gain;
    /// * SBF stores the oscillators' pattern at Set (the interval as this trial's clock
    ///   measured it, with memory noise) as the detector's weights, and restarts the
    ///   oscillators in phase with a new speed factor divided by the gain: the coincidence
    ///   detector fires when the pattern recurs;
    /// * time cells start again with a new speed factor; what the agent learned by TD
    ///   reads the production from the population and its snapshot at Set (the gain is a
    ///   context the learner sees).
    ///
    /// Measurement and production draw their clock noise independently (the observer
    /// model's `wm` and `wp`, Jazayeri & Shadlen 2010).
    pub fn begin_production<R: Rng + ?Sized>(&mut self, ctx: u8, ts: f64, gain: f64, rng: &mut R) {
        let gain = if gain > 0.0 { gain } else { 1.0 };
        match self {
            Timer::Ddm(d) => {
                d.acc.learn(d.acc.x, d.reproduction_rate);
                d.drifts.insert(ctx, d.acc.drift);
                let drift = d.acc.drift / gain;
                d.acc.reset();
                d.acc.drift = drift;
            }
            Timer::Sbf(s) => {
                let stored = s.model.stored_time(s.subjective(ts), rng);
                let speed = speed_sample(s.clock_noise, rng) / gain;
                s.start_clock(Some(stored), speed);
            }
            Timer::TimeCells(tc) => {
                let speed = speed_sample(tc.cells.clock_noise, rng);
                tc.cells.onset_with_speed(speed);
            }
        }
    }

    /// Advances one step; `t` is the elapsed steps after the advance.
    pub fn tick<R: Rng + ?Sized>(&mut self, t: u32, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                d.acc.step(1.0, rng);
                for (_, acc) in &mut d.choice_acc {
                    acc.step(1.0, rng);
                }
            }
            Timer::Sbf(s) => s.advance(t),
            Timer::TimeCells(tc) => tc.cells.tick(),
        }
    }

    /// Native readout: respond (check the oven) now? `t` = elapsed steps, `started` = the
    /// step responding started in this trial, if it did (responding then continues until
    /// the model's stop rule, if any).
    pub fn respond(&self, t: u32, started: Option<u32>) -> bool {
        match self {
            Timer::Ddm(d) => {
                let z = d.acc.threshold;
                let on = started.is_some() || d.acc.x >= d.start * z || d.acc.crossed_at.is_some();
                on && d.stop.is_none_or(|k| d.acc.x < k * z)
            }
            Timer::Sbf(s) => {
                if let (Some(t0), Some(k)) = (started, s.stop) {
                    return (t as f64) < t0 as f64 * k;
                }
                if started.is_some() {
                    return true;
                }
                let Some(stored) = s.rt.template else {
                    return true; // nothing stored yet: explore by checking
                };
                let fallback = s.rt.now > 2.0 * stored / s.speed() + 0.05;
                fallback || s.rt.readouts.first().is_some_and(|&r| r >= s.threshold)
            }
            Timer::TimeCells(_) => true,
        }
    }

    /// The model's expected time has clearly passed (by the factor `k`) in the running
    /// interval: drift-diffusion `x ≥ k z`; SBF: the clock is past `k ×` its remembered
    /// time. Time cells hold no single expected time (false).
    pub fn overdue(&self, k: f64) -> bool {
        match self {
            Timer::Ddm(d) => d.acc.x >= k * d.acc.threshold,
            Timer::Sbf(s) => {
                s.rt.template
                    .is_some_and(|stored| s.rt.now >= k * stored / s.speed())
            }
            Timer::TimeCells(_) => false,
        }
    }

    /// Temporal features for TD learning into `out` (bias excluded), each within ~[0, 1].
    pub fn features_into(&self, responding: bool, out: &mut Vec<f64>) {
        out.clear();
        match self {
            Timer::Ddm(d) => {
                out.push((d.acc.x / d.acc.threshold).clamp(-1.0, 4.0));
                out.push(f64::from(responding));
            }
            Timer::Sbf(s) => {
                out.push(s.rt.readouts.first().copied().unwrap_or(0.0));
                out.push(f64::from(responding));
            }
            Timer::TimeCells(tc) => {
                tc.cells.normalised_units_into(out);
            }
        }
    }

    /// Native learning at reinforcement: the interval of context `ctx` was `interval`
    /// steps (`x_at` = accumulator value then, for the drift rule).
    pub fn reinforce<R: Rng + ?Sized>(&mut self, ctx: u8, interval: f64, exact: bool, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                if exact {
                    d.acc.learn(d.acc.x.max(1e-6), d.rate);
                } else {
                    d.acc.learn_interval(interval, d.rate);
                }
                d.drifts.insert(ctx, d.acc.drift);
            }
            Timer::Sbf(s) => {
                // The pattern stored is the oscillators' phases at reinforcement, i.e. the
                // interval as this trial's clock measured it (its speed factor included).
                let stored = s.model.stored_time(s.subjective(interval), rng);
                SbfTimer::store(s.memories.entry(ctx).or_default(), stored, SBF_MEMORY);
            }
            Timer::TimeCells(_) => {}
        }
    }
}
