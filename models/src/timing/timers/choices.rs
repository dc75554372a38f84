//! The timing models' categorical side: anchor memories learned from choices, the
//! k-category judgment of an ended interval, the decision rule and its feedback
//! (bisection, multi-anchor categorization, multi-oven) — and the recording of each
//! model's populations. The clock itself (onset, ticks, features, the response gate,
//! reinforcement of the ready time) is in the parent module.

use super::{SBF_MEMORY, SbfTimer, Timer, memory_sample};
use crate::activity::StepRecorder;
use crate::timing::judgment::{CATEGORY_MEMORY, Categories, Decision, LONG, SHORT, can_judge};
use crate::timing::{DriftDiffusion, Representation};
use rand::Rng;

impl Timer {
    /// Bisection feedback: the interval that just ended (`interval` steps) belonged to
    /// category `slot` ([`SHORT`] or [`LONG`]). Drift-diffusion learns that slot's drift,
    /// SBF stores the pattern (with memory noise), time cells store the decoded duration.
    pub fn reinforce_choice<R: Rng + ?Sized>(&mut self, slot: u8, interval: f64, rng: &mut R) {
        if let Some(measured) = self.measured(interval) {
            self.store_choice(slot, measured, rng);
        }
    }

    /// [`Self::reinforce_choice`] for an interval timed by another clock, `trial` (a copy
    /// of this timer that ran one oven's interval in the multi-oven task): the interval as
    /// `trial` measured it is stored in this timer's memories.
    pub fn reinforce_choice_measured_by<R: Rng + ?Sized>(
        &mut self,
        trial: &Timer,
        slot: u8,
        interval: f64,
        rng: &mut R,
    ) {
        if let Some(measured) = trial.measured(interval) {
            self.store_choice(slot, measured, rng);
        }
    }

    /// An interval of `interval` steps as this trial's clock measured it, in the unit the
    /// model remembers: drift-diffusion steps (its drift rule learns `z/interval`), SBF the
    /// oscillators' phase time (s, this trial's speed factor included), time cells the
    /// population's decoded time (`None` when it decodes none).
    fn measured(&self, interval: f64) -> Option<f64> {
        match self {
            Timer::Ddm(_) => Some(interval),
            Timer::Sbf(s) => Some(s.subjective(interval)),
            Timer::TimeCells(tc) => tc.cells.decoded_time(),
        }
    }

    /// Stores a `measured` duration ([`Self::measured`]) as a member of category `slot`.
    fn store_choice<R: Rng + ?Sized>(&mut self, slot: u8, measured: f64, rng: &mut R) {
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
                acc.learn_interval(measured, d.rate);
                d.choice_drifts.insert(slot, acc.drift);
            }
            Timer::Sbf(s) => {
                // The pattern stored is the oscillators' phases at reinforcement, i.e. the
                // interval as this trial's clock measured it (its speed factor included).
                let stored = s.model.stored_time(measured, rng);
                SbfTimer::store(
                    s.choice_memories.entry(slot).or_default(),
                    stored,
                    CATEGORY_MEMORY,
                );
            }
            Timer::TimeCells(tc) => {
                let stored = measured * memory_sample(tc.memory_noise, rng);
                tc.anchors.store(slot, stored.ln());
            }
        }
    }

    /// Takes over what `trial` (a copy of this timer that ran one oven's interval and was
    /// reinforced at its ready cue) learned for context `ctx`: drift-diffusion its drift,
    /// SBF its newest stored time (appended to this timer's memory). Time cells learn
    /// nothing at the cue.
    pub fn adopt_context_memory(&mut self, trial: &Timer, ctx: u8) {
        match (self, trial) {
            (Timer::Ddm(d), Timer::Ddm(t)) => {
                if let Some(&drift) = t.drifts.get(&ctx) {
                    d.drifts.insert(ctx, drift);
                }
            }
            (Timer::Sbf(s), Timer::Sbf(t)) => {
                if let Some(&newest) = t.memories.get(&ctx).and_then(|m| m.last()) {
                    SbfTimer::store(s.memories.entry(ctx).or_default(), newest, SBF_MEMORY);
                }
            }
            _ => {}
        }
    }

    /// The judgment at the end of the interval among `k` categories (choice slots
    /// `0 … k−1`; bisection: `k` 2, [`SHORT`] / [`LONG`]): the slot of the category the
    /// interval falls in, `None` while not every slot's anchor is remembered (or the
    /// representation has no time, presence).
    pub fn judge(&self, k: usize) -> Option<u8> {
        match self {
            Timer::Ddm(d) => d.category(k),
            Timer::Sbf(s) => {
                let slots = &s.rt.criterion_slots;
                if !can_judge(k, slots.len()) {
                    return None;
                }
                let passed = s.rt.criterion_passed.iter().filter(|&&p| p).count();
                Some(slots[passed.min(slots.len() - 1)])
            }
            Timer::TimeCells(tc) => {
                if !can_judge(k, tc.trial_anchors.len()) {
                    return None;
                }
                let categories = Categories::new(&tc.trial_anchors, &tc.decision)?;
                Some(categories.category(tc.cells.decoded_time()?))
            }
        }
    }

    /// The bisection decision rule of this timer.
    pub fn decision(&self) -> &Decision {
        match self {
            Timer::Ddm(d) => &d.decision,
            Timer::Sbf(s) => &s.decision,
            Timer::TimeCells(tc) => &tc.decision,
        }
    }

    /// The bisection decision rule of this timer, to change it.
    pub fn decision_mut(&mut self) -> &mut Decision {
        match self {
            Timer::Ddm(d) => &mut d.decision,
            Timer::Sbf(s) => &mut s.decision,
            Timer::TimeCells(tc) => &mut tc.decision,
        }
    }

    /// Feedback on a bisection judgment (`judged_long`; the truth `was_long`) for the
    /// decision rule (only the learned rule changes), with the remembered anchors in the
    /// timer's own time unit.
    pub fn judgment_feedback(&mut self, judged_long: bool, was_long: bool) {
        let anchors = match self {
            Timer::Ddm(d) => d.anchor_memories(),
            Timer::Sbf(s) => {
                let mean = |slot: u8| {
                    let m = s.choice_memories.get(&slot).filter(|m| !m.is_empty())?;
                    Some(m.iter().sum::<f64>() / m.len() as f64)
                };
                mean(SHORT).zip(mean(LONG))
            }
            Timer::TimeCells(tc) => tc.anchors.anchors(),
        };
        if let Some((s, l)) = anchors {
            self.decision_mut().feedback(s, l, judged_long, was_long);
        }
    }

    /// Writes the model's populations.
    pub fn record(&self, rec: &mut StepRecorder) {
        self.record_as(rec, "");
    }

    /// Writes the model's populations with `suffix` after each name (multi-oven: one
    /// clock per oven, `accumulator_oven2`, …; empty: the plain names).
    pub fn record_as(&self, rec: &mut StepRecorder, suffix: &str) {
        let name = |base: &str| format!("{base}{suffix}");
        match self {
            Timer::Ddm(d) => {
                rec.scalar(&name("accumulator"), d.acc.x as f32);
                rec.scalar(&name("drift"), d.acc.drift as f32);
            }
            Timer::Sbf(s) => {
                let mut osc: Vec<f32> = s.rt.cos.iter().map(|&v| v as f32).collect();
                osc.resize(s.model.len(), 1.0);
                rec.record(&name("oscillators"), &osc);
                // The striatal coincidence detector's response: the quadrature (cosine and
                // sine weights) match of the oscillators with this trial's remembered
                // pattern, 0–1 — what the agent's response threshold reads. (One in-phase
                // detector alone, Σ wᵢ cos φᵢ, would swing with the ~10 Hz carrier.)
                rec.scalar(
                    &name("striatum"),
                    s.rt.readouts.first().copied().unwrap_or(0.0) as f32,
                );
            }
            Timer::TimeCells(tc) => {
                let mut units = Vec::new();
                tc.cells.units_into(&mut units);
                let v: Vec<f32> = units.iter().map(|&x| x as f32).collect();
                rec.record(&name("time_cells"), &v);
                if matches!(tc.cells.repr, Representation::Laplace { .. }) {
                    let f: Vec<f32> = tc
                        .cells
                        .laplace_integrators()
                        .iter()
                        .map(|&x| x as f32)
                        .collect();
                    rec.record(&name("laplace"), &f);
                }
            }
        }
    }
}
