//! The timing models as the temporal part of an agent: started at oven-on, advanced one
//! step at a time, read out as features for TD learning and (drift-diffusion, SBF) as a
//! native "respond now" gate, and trained by their own rule at reinforcement.
//!
//! Time unit: one env step. Memories are kept per visible context (the oven cue value),
//! so a multi-timer agent stores one interval per coloured light. In bisection each model
//! also keeps memories of the two anchors and judges every interval by comparing with them
//! ([`crate::timing::judgment`]).

use crate::activity::StepRecorder;
use crate::timing::judgment::{CategoryMemory, LONG, SHORT, ddm_ratio_rule};
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
    /// This trial's short- and long-anchor accumulators (empty until both drifts exist).
    #[serde(skip)]
    choice_acc: Vec<DriftDiffusion>,
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
    /// Stored times (s) per rewarded choice slot (bisection: short / long counter).
    pub choice_memories: BTreeMap<u8, Vec<f64>>,
    /// Stop responding `stop × (start time)` after starting (`None`: never).
    pub stop: Option<f64>,
    #[serde(skip)]
    rt: SbfRuntime,
}

/// Envelope above which the bisection criterion's coincidence counts as reached.
pub const SBF_CRITERION_THRESHOLD: f64 = 0.5;

/// Per-trial state of an SBF timer: oscillator phases and the complex detector weights
/// `[this trial's memory sample, bisection criterion]` (empty = nothing stored).
#[derive(Debug, Clone, PartialEq, Default)]
struct SbfRuntime {
    now: f64,
    step: Option<u32>,
    cos: Vec<f64>,
    sin: Vec<f64>,
    rot: Vec<(f64, f64)>,
    detectors: Vec<(Vec<f64>, Vec<f64>)>,
    readouts: [f64; 2],
    template: Option<f64>,
    /// Criterion time `√(T_S·T_L)` (s) of this trial, when both anchors are stored.
    criterion: Option<f64>,
    /// The criterion detector's envelope has reached [`SBF_CRITERION_THRESHOLD`].
    criterion_reached: bool,
    /// … and has since peaked: the criterion time has passed.
    criterion_passed: bool,
}

/// Stored times kept per SBF memory.
pub const SBF_MEMORY: usize = 20;

impl SbfTimer {
    fn store(memory: &mut Vec<f64>, t: f64) {
        if memory.len() == SBF_MEMORY {
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

    fn onset<R: Rng + ?Sized>(&mut self, ctx: u8, rng: &mut R) {
        let template = Self::sample(self.memories.get(&ctx), rng);
        let criterion = if self.choice_memories.len() == 2 {
            let short = Self::sample(self.choice_memories.get(&SHORT), rng);
            let long = Self::sample(self.choice_memories.get(&LONG), rng);
            short.zip(long).map(|(s, l)| (s * l).sqrt())
        } else {
            None
        };
        let detectors = vec![
            self.detector(template.as_slice()),
            self.detector(criterion.as_slice()),
        ];
        let w = 2.0 * std::f64::consts::PI * self.model.clock_speed * self.seconds_per_step;
        let rot = self.model.freqs.iter().map(|f| (w * f).sin_cos()).collect();
        self.rt = SbfRuntime {
            template,
            criterion,
            detectors,
            rot,
            ..SbfRuntime::default()
        };
    }

    /// Oscillators at `t` steps and every detector's envelope `|Σ e^{iφᵢ} conj(Wᵢ)| / N`.
    fn advance(&mut self, t: u32) {
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
            let w = 2.0 * std::f64::consts::PI * self.model.clock_speed * rt.now;
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
        let two_pi_k = 2.0 * std::f64::consts::PI * self.model.clock_speed;
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
                if k == 1 {
                    let w = two_pi_k * self.model.freqs[i];
                    dre -= w * b;
                    dim += w * a;
                }
            }
            rt.readouts[k] = (re * re + im * im).sqrt() / n;
            if k == 1 {
                // d|z|²/dt = 2 Re(conj(z) dz/dt): the envelope is falling after its peak.
                let falling = re * dre + im * dim <= 0.0;
                if rt.readouts[1] >= SBF_CRITERION_THRESHOLD {
                    rt.criterion_reached = true;
                    rt.criterion_passed |= falling;
                } else if rt.criterion_reached {
                    rt.criterion_passed = true;
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
    /// Drift-diffusion timer: `z` 1, noise `m`, initial interval 8 steps, rate 0.2.
    pub fn ddm(noise: f64) -> Self {
        Timer::Ddm(DdmTimer {
            acc: DriftDiffusion::new(1.0 / 8.0, 1.0, noise),
            initial_interval: 8.0,
            drifts: BTreeMap::new(),
            rate: 0.2,
            start: 1.0,
            stop: None,
            choice_drifts: BTreeMap::new(),
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
            threshold: 0.7,
            memories: BTreeMap::new(),
            choice_memories: BTreeMap::new(),
            stop: None,
            rt: SbfRuntime::default(),
        })
    }

    /// Time-cell representation.
    pub fn time_cells(repr: Representation) -> Self {
        Timer::TimeCells(TimeCellTimer {
            cells: TimeCells::new(repr),
            anchors: CategoryMemory::default(),
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
            Timer::Sbf(s) => s.rt = SbfRuntime::default(),
            Timer::TimeCells(tc) => tc.cells.clear(),
        }
    }

    /// The timed event (oven on) in context `ctx`: reset to time 0 (`rng` draws the
    /// SBF's memory sample of this trial).
    pub fn onset<R: Rng + ?Sized>(&mut self, ctx: u8, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                d.acc.reset();
                d.acc.drift = *d
                    .drifts
                    .get(&ctx)
                    .unwrap_or(&(d.acc.threshold / d.initial_interval));
                d.choice_acc.clear();
                if let (Some(&a_s), Some(&a_l)) =
                    (d.choice_drifts.get(&SHORT), d.choice_drifts.get(&LONG))
                {
                    for drift in [a_s, a_l] {
                        let mut acc = d.acc.clone();
                        acc.drift = drift;
                        d.choice_acc.push(acc);
                    }
                }
            }
            Timer::Sbf(s) => s.onset(ctx, rng),
            Timer::TimeCells(tc) => {
                let noise = tc.cells.speed_noise;
                let speed = if noise > 0.0 {
                    (noise * rng.sample::<f64, _>(StandardNormal)).exp()
                } else {
                    1.0
                };
                tc.cells.onset_with_speed(speed);
            }
        }
    }

    /// Advances one step; `t` is the elapsed steps after the advance.
    pub fn tick<R: Rng + ?Sized>(&mut self, t: u32, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                d.acc.step(1.0, rng);
                for acc in &mut d.choice_acc {
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
                let fallback = s.rt.now > 2.0 * stored / s.model.clock_speed + 0.05;
                fallback || s.rt.readouts[0] >= s.threshold
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
                    .is_some_and(|stored| s.rt.now >= k * stored / s.model.clock_speed)
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
                out.push(s.rt.readouts[0]);
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
                let stored = s.model.stored_time(interval * s.seconds_per_step, rng);
                SbfTimer::store(s.memories.entry(ctx).or_default(), stored);
            }
            Timer::TimeCells(_) => {}
        }
    }

    /// Bisection feedback: the interval that just ended (`interval` steps) belonged to
    /// category `slot` ([`SHORT`] or [`LONG`]). Drift-diffusion learns that slot's drift,
    /// SBF stores the pattern (with memory noise), time cells store the decoded duration.
    pub fn reinforce_choice<R: Rng + ?Sized>(&mut self, slot: u8, interval: f64, rng: &mut R) {
        match self {
            Timer::Ddm(d) => {
                let z = d.acc.threshold;
                let mut acc = DriftDiffusion::new(
                    *d.choice_drifts
                        .get(&slot)
                        .unwrap_or(&(z / d.initial_interval)),
                    z,
                    0.0,
                );
                acc.learn_interval(interval, d.rate);
                d.choice_drifts.insert(slot, acc.drift);
            }
            Timer::Sbf(s) => {
                let stored = s.model.stored_time(interval * s.seconds_per_step, rng);
                SbfTimer::store(s.choice_memories.entry(slot).or_default(), stored);
            }
            Timer::TimeCells(tc) => {
                if let Some(t_hat) = tc.cells.decoded_time() {
                    tc.anchors.store(slot, t_hat.ln());
                }
            }
        }
    }

    /// The bisection judgment at the end of the interval: `Some(true)` "long",
    /// `Some(false)` "short", `None` while the anchors are not both remembered (or the
    /// representation has no time, presence).
    pub fn judge(&self) -> Option<bool> {
        match self {
            Timer::Ddm(d) => match d.choice_acc.as_slice() {
                [s, l] => Some(ddm_ratio_rule(s.x, l.x, d.acc.threshold)),
                _ => None,
            },
            Timer::Sbf(s) => s.rt.criterion.map(|_| s.rt.criterion_passed),
            Timer::TimeCells(tc) => tc.anchors.judge(tc.cells.decoded_time()?.ln()),
        }
    }

    /// Writes the model's populations.
    pub fn record(&self, rec: &mut StepRecorder) {
        match self {
            Timer::Ddm(d) => {
                rec.scalar("accumulator", d.acc.x as f32);
                rec.scalar("drift", d.acc.drift as f32);
            }
            Timer::Sbf(s) => {
                let mut osc: Vec<f32> = s.rt.cos.iter().map(|&v| v as f32).collect();
                osc.resize(s.model.len(), 1.0);
                rec.record("oscillators", &osc);
                let out = s.rt.detectors.first().map_or(0.0, |(c, _)| {
                    c.iter().zip(&s.rt.cos).map(|(w, x)| w * x).sum::<f64>()
                });
                rec.scalar("striatum", out as f32);
                rec.scalar("envelope", s.rt.readouts[0] as f32);
            }
            Timer::TimeCells(tc) => {
                let mut units = Vec::new();
                tc.cells.units_into(&mut units);
                let v: Vec<f32> = units.iter().map(|&x| x as f32).collect();
                rec.record("time_cells", &v);
                if matches!(tc.cells.repr, Representation::Laplace { .. }) {
                    let f: Vec<f32> = tc
                        .cells
                        .laplace_integrators()
                        .iter()
                        .map(|&x| x as f32)
                        .collect();
                    rec.record("laplace", &f);
                }
            }
        }
    }
}
