//! The timing agents on multi-oven bisection (`MultiOven-v0`): one clock per oven, each a
//! copy of the agent's timer started when its oven is seen to turn on, judged against the
//! one shared memory of the anchors (see the parent module's "Several ovens").

use super::TimingAgent;
use crate::agent::Percept;
use crate::timing::judgment::LONG;
use crate::timing::sarsa::Active;
use crate::timing::timers::Timer;
use chronocooked_env::{Action, CODE_CHANNELS};

/// One oven's clock in a multi-oven episode: a copy of the agent's timer started at the
/// oven's onset.
#[derive(Debug, Clone, Default)]
pub(super) struct OvenClock {
    pub(super) timer: Option<Timer>,
    running: bool,
    clock: u32,
    interval: Option<u32>,
    judgment: Option<u8>,
}

/// What the codes observation shows of a multi-oven kitchen: each oven's value (0 off,
/// 1 on, 2 ready) and the oven the carried soup came from.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct OvenView {
    values: Vec<u8>,
    /// Whether each oven is in the kitchen (its cell shows an object): a probe in a
    /// kitchen with fewer ovens than the agent trained with leaves the others' cells free.
    present: Vec<bool>,
    soup_from: Option<usize>,
}

impl TimingAgent {
    /// Whether the agent times several ovens (one clock each).
    pub(super) fn multi_oven(&self) -> bool {
        !self.oven_cells.is_empty()
    }

    /// Each oven's visible value and the carried soup's oven (its code on the soup channel
    /// equals that oven's code on the object channel).
    pub(super) fn view_ovens(&self, obs: &[u8], p: &Percept) -> OvenView {
        let at = |cell: usize, channel: usize| obs[cell * CODE_CHANNELS + channel];
        let soup = at(p.cell, 3);
        OvenView {
            values: self.oven_cells.iter().map(|&c| at(c, 4)).collect(),
            present: self.oven_cells.iter().map(|&c| at(c, 0) != 0).collect(),
            soup_from: (p.carry == 2)
                .then(|| self.oven_cells.iter().position(|&c| at(c, 0) == soup))
                .flatten(),
        }
    }

    /// Multi-oven state: cell × (empty, onion, soup of oven 1, 2, 3) × each of three ovens
    /// off / on / ready / absent.
    pub(super) fn multi_state_index(&self, p: &Percept, v: &OvenView) -> u32 {
        let carry = match (p.carry, v.soup_from) {
            (2, Some(i)) => 2 + i as u32,
            (c, _) => u32::from(c.min(1)),
        };
        // Always three ovens, an absent one as a fourth value, so a state means the same
        // with 1, 2 or 3 ovens: what the curriculum's first levels teach carries over, and
        // the protocol's one-oven probes of a 3-oven agent land on the one-oven states it
        // learned. (Read as "off", an absent oven made a one-oven soup look like the last
        // of three, worth a third: measured, the 3-oven synchronous agents then bumped into
        // walls on every one-oven probe, interact and a bump tied at 0.24.)
        let ovens = (0..3).fold(0u32, |acc, i| {
            let value = match (v.present.get(i), v.values.get(i)) {
                (Some(true), Some(&o)) => u32::from(o.min(2)),
                _ => 3,
            };
            acc * 4 + value
        });
        (p.cell as u32 * 5 + carry) * 64 + ovens
    }

    /// Runs each oven's clock from what is visible: a clock starts (a copy of the agent's
    /// timer, at its onset) when its oven is seen to turn on, ticks while it cooks, and at
    /// the ready cue ends, judges the interval, and (training) learns the cue's time by the
    /// model's own rule into the shared timer.
    pub(super) fn update_oven_clocks(&mut self, view: &OvenView) {
        let n = self.oven_cells.len();
        self.ep.clocks.resize_with(n, OvenClock::default);
        let last = std::mem::replace(&mut self.ep.view, view.clone());
        for i in 0..n {
            let (was, now) = (last.values.get(i).copied().unwrap_or(0), view.values[i]);
            let c = &mut self.ep.clocks[i];
            if was == 0 && now != 0 && !c.running && c.interval.is_none() {
                let mut timer = self.timer.clone();
                timer.clear();
                timer.onset(1, self.categories, &mut self.rng);
                timer.tick(1, &mut self.rng);
                *c = OvenClock {
                    timer: Some(timer),
                    running: true,
                    clock: 1,
                    interval: None,
                    judgment: None,
                };
            } else if c.running && now == 1 {
                c.clock += 1;
                if let Some(t) = c.timer.as_mut() {
                    t.tick(c.clock, &mut self.rng);
                }
                continue;
            } else if !(c.running && now != 1) {
                continue;
            }
            if now == 2 {
                c.running = false;
                c.interval = Some(c.clock);
                let Some(t) = c.timer.as_mut() else { continue };
                c.judgment = t.judge(self.categories);
                if self.training {
                    t.reinforce(1, f64::from(c.clock), true, &mut self.rng);
                    self.timer.adopt_context_memory(t, 1);
                }
            } else if now == 0 {
                c.running = false;
            }
        }
    }

    /// One decision in the multi-oven task: the TD learner over (cell, carry with the soup's
    /// oven, every oven's state) × (bias, the judgment of the carried soup's oven). The
    /// ovens show ready, so the clocks serve the judgments only (temporal features off, no
    /// gate).
    pub(super) fn act_multi_oven(&mut self, obs: &[u8]) -> Action {
        let p = self.parser.parse(obs);
        let view = self.view_ovens(obs, &p);
        self.update_oven_clocks(&view);
        let judgment = view.soup_from.and_then(|i| self.ep.clocks.get(i)?.judgment);
        let mut features = std::mem::take(&mut self.phi);
        features.clear();
        features.push(1.0);
        features.resize(1 + self.timer.n_features(), 0.0);
        for slot in 0..self.judgment_features {
            features.push(f64::from(judgment == Some(slot as u8)));
        }
        features.push(0.0);
        let s = self.multi_state_index(&p, &view);
        let active = Active::of(&features);
        let mut q = std::mem::take(&mut self.q);
        self.learner.q_all_active(s, &active, &mut q);
        let allowed: Vec<usize> = (0..Action::COUNT).collect();
        let eps = if self.training {
            self.config.epsilon
        } else {
            0.0
        };
        let a = self.learner.choose(&q, &allowed, eps, &mut self.rng);
        self.learn(Some(q[a]));
        self.ep.value = q[a];
        if self.training {
            self.learner.visit_active(s, a, &active);
        }
        self.ep.pending = Some((s, a, active));
        self.ep.last = Some(p);
        self.phi = features;
        self.q = q;
        Action::ALL[a]
    }

    /// Multi-oven feedback: the soup the agent carried left its hands at a counter — that
    /// oven's interval was short (short counter paid, or long counter unpaid) or long; the
    /// shared memory stores it as that oven's clock measured it.
    pub(super) fn oven_delivery_feedback(&mut self, reward: f32, next_obs: &[u8]) {
        let (Some(p), Some(i)) = (self.ep.last, self.ep.view.soup_from) else {
            return;
        };
        if !self.training || self.parser.parse(next_obs).carry == 2 {
            return;
        }
        let Some(&(_, chosen)) = self.choice_cells.iter().find(|(c, _)| *c == p.cell) else {
            return;
        };
        let Some(clock) = self.ep.clocks.get(i) else {
            return;
        };
        let (Some(trial), Some(interval)) = (clock.timer.as_ref(), clock.interval) else {
            return;
        };
        let category = if reward > 0.0 { chosen } else { LONG - chosen };
        if let Some(judged) = clock.judgment {
            self.timer
                .judgment_feedback(judged == LONG, category == LONG);
        }
        self.timer.reinforce_choice_measured_by(
            trial,
            category,
            f64::from(interval),
            &mut self.rng,
        );
    }
}
