//! Oracle (optimal scripted) policies and a brute-force optimum for checking them.
//!
//! The oracle reads the hidden state (it is a reference policy, not an agent):
//! shortest paths from precomputed BFS tables plus exact waiting.
//!
//! * FI / multi-timer: take the soup at the earliest timer that pays 1
//!   (`TD`, or `max(1, TD − under_buffer)` when undercooking is possible).
//! * Peak interval: check the oven at every step from `timer = TD` on (an ideal
//!   timer's response), which takes the soup once it is released.
//! * Bisection: take the soup when ready; deliver to the short counter iff
//!   `TD² < S·L` (geometric-mean boundary for probes; exact for the anchors).
//! * Dual: put the onion in at the oven neighbour closest to the sink, spend the
//!   wait at the sink and leave exactly in time for the latest rewarded pickup
//!   (`TD + over_buffer`).
//! * Uncertainty: wait at the oven; if it is still dark at `timer = TD`, press the
//!   button and take the (reduced) soup. This is also optimal without hidden
//!   information: the never-ready draw is invisible before TD.
//! * Multi-anchor: take the soup when ready; deliver to the counter of the anchor whose
//!   category holds TD (boundaries at the geometric means of neighbouring anchors; exact
//!   for the anchors themselves).
//! * Multi-oven: put the onion in the first oven, take each soup as soon as its oven is
//!   ready (the nearest ready oven first) and deliver it to the counter of its oven's
//!   duration (geometric-mean boundary); while nothing is ready, wait next to the oven
//!   that will be ready first.
//! * Ready-Set-Go (reproduction): wait next to the oven (its neighbour nearest the
//!   counter) and take the soup `round(g·ts)` steps after Set (the reward's peak; at least
//!   1), then deliver.

use crate::action::Action;
use crate::env::ChronoEnv;
use crate::info::Carry;
use crate::kitchen::{Kitchen, KitchenState, MultiOvenState, RsgState};
use crate::layout::{Layout, ObjectKind};
use crate::rules::{ReadySetGo, Rules};
use crate::task::TaskParams;
use std::collections::HashMap;

/// Optimal scripted policy for one task instance.
#[derive(Debug, Clone)]
pub struct Oracle {
    layout: Layout,
    params: TaskParams,
    /// The kitchen's rules the task runs (the oracle's strategy follows their mechanics).
    rules: Rules,
    /// Ready-Set-Go: the gains of the production.
    rsg: Option<ReadySetGo>,
    /// All-pairs shortest path lengths between cells (moves).
    dist: Vec<Vec<u32>>,
    /// Free cells touching each object kind, indexed by [`ObjectKind::onehot_index`].
    neighbours: Vec<Vec<usize>>,
}

impl Oracle {
    /// Builds the oracle for `env`'s task.
    pub fn new(env: &ChronoEnv) -> Self {
        let layout = env.layout().clone();
        let dist = (0..layout.n_cells())
            .map(|c| layout.distances_to(c))
            .collect();
        let neighbours = ObjectKind::EVERY
            .iter()
            .map(|&kind| {
                layout
                    .free_cells()
                    .iter()
                    .map(|&c| c as usize)
                    .filter(|&c| matches!(layout.adjacent_object(c), Some((k, _)) if k == kind))
                    .collect()
            })
            .collect();
        Oracle {
            layout,
            params: env.config().params.clone(),
            rules: env.spec().rules,
            rsg: env.spec().rsg.clone(),
            dist,
            neighbours,
        }
    }

    /// Ready-Set-Go: this oracle producing `td` itself (gain 1 whatever the episode's
    /// gain), for agents that decide a production's length and let the oracle walk and
    /// take the soup. Other tasks: unchanged.
    pub fn producing_td(mut self) -> Self {
        if let Some(rsg) = self.rsg.as_mut() {
            rsg.gains = vec![1.0];
        }
        self
    }

    /// Free cells from which `kind` can be used.
    fn adjacent_to(&self, kind: ObjectKind) -> &[usize] {
        &self.neighbours[kind.onehot_index()]
    }

    fn d(&self, a: usize, b: usize) -> u32 {
        self.dist[b][a]
    }

    /// Nearest cell of `set` from `from` (ties: the first in row-major order).
    fn nearest(&self, from: usize, set: &[usize]) -> usize {
        *set.iter()
            .min_by_key(|&&c| self.d(from, c))
            .expect("validated layouts give every object a free neighbour")
    }

    /// One move along a shortest path from `from` to `to` (`Wait` when already there).
    fn step_towards(&self, from: usize, to: usize) -> Action {
        if from == to {
            return Action::Wait;
        }
        let here = self.d(from, to);
        for a in [Action::Down, Action::Up, Action::Right, Action::Left] {
            let n = self.layout.move_from(from, a);
            if n != from && self.d(n, to) < here {
                return a;
            }
        }
        Action::Wait
    }

    /// Go to `target` and interact there.
    fn go_and_interact(&self, from: usize, target: usize) -> Action {
        if from == target {
            Action::Interact
        } else {
            self.step_towards(from, target)
        }
    }

    /// The counter a soup of duration `td` goes to (the family's rule).
    fn delivery_kind(&self, td: u32) -> ObjectKind {
        crate::task::family::of_params(&self.params).delivery_kind(&self.params, td)
    }

    /// Timer (at action time) of the earliest rewarded pickup, `None` if never.
    fn pickup_timer(&self, td: u32) -> Option<i32> {
        crate::task::family::of_params(&self.params).paid_pickup_timer(&self.params, td)
    }

    /// Dual task: the oven neighbour closest to a sink neighbour. Putting the onion in
    /// and taking the soup out there maximises the time left for the sink.
    fn dual_post(&self) -> Option<usize> {
        if !matches!(self.rules, Rules::Dual { .. }) {
            return None;
        }
        let sinks = self.adjacent_to(ObjectKind::RewardSink);
        self.adjacent_to(ObjectKind::Oven)
            .iter()
            .copied()
            .min_by_key(|&y| {
                sinks
                    .iter()
                    .map(|&k| self.d(y, k))
                    .min()
                    .unwrap_or(u32::MAX)
            })
    }

    /// The oracle's action in `state`.
    pub fn act(&self, state: &KitchenState) -> Action {
        if let Some(mo) = &state.multi_oven {
            return self.act_multi_oven(state, mo);
        }
        if let Some(rsg) = &state.reproduction {
            return self.act_reproduction(state, rsg);
        }
        let a = self.layout.index(state.agent.0, state.agent.1);
        let oven_adj = self.adjacent_to(ObjectKind::Oven);
        let counter_adj = self.adjacent_to(self.delivery_kind(state.td));
        match state.carry {
            Carry::Soup => self.go_and_interact(a, self.nearest(a, counter_adj)),
            Carry::Onion => {
                if state.timer < 0 {
                    let target = self
                        .dual_post()
                        .unwrap_or_else(|| self.nearest(a, oven_adj));
                    self.go_and_interact(a, target)
                } else {
                    Action::Wait // deadlock: cannot happen under the oracle
                }
            }
            Carry::Nothing if state.timer < 0 => {
                let onion_adj = self.adjacent_to(ObjectKind::OnionDispenser);
                let to_oven = |x: usize| match self.dual_post() {
                    Some(y) => self.d(x, y),
                    None => oven_adj.iter().map(|&y| self.d(x, y)).min().unwrap_or(0),
                };
                let best = *onion_adj
                    .iter()
                    .min_by_key(|&&x| self.d(a, x) + to_oven(x))
                    .expect("validated layouts have an onion dispenser");
                self.go_and_interact(a, best)
            }
            Carry::Nothing => self.wait_and_pickup(a, state, oven_adj, counter_adj),
        }
    }

    fn wait_and_pickup(
        &self,
        a: usize,
        s: &KitchenState,
        oven_adj: &[usize],
        counter_adj: &[usize],
    ) -> Action {
        // Wait at the oven neighbour closest to the delivery counter (dual: to the sink).
        let post = self.dual_post().unwrap_or_else(|| {
            *oven_adj
                .iter()
                .min_by_key(|&&y| {
                    (
                        counter_adj.iter().map(|&c| self.d(y, c)).min().unwrap_or(0),
                        self.d(a, y),
                    )
                })
                .expect("validated layouts have an oven")
        });
        let t = s.timer;
        let pick = self.pickup_timer(s.td).unwrap_or(i32::MAX);
        match self.rules {
            Rules::Bisection { .. } | Rules::Categories { .. } => {
                if s.ready && a == post {
                    Action::Interact
                } else {
                    self.step_towards(a, post)
                }
            }
            Rules::Uncertainty { .. } => {
                if s.ready {
                    self.go_and_interact(a, post)
                } else if t >= pick {
                    let button = self.nearest(a, self.adjacent_to(ObjectKind::OvenButton));
                    self.go_and_interact(a, button)
                } else {
                    self.step_towards(a, post)
                }
            }
            Rules::Dual { .. } => {
                let sinks = self.adjacent_to(ObjectKind::RewardSink);
                let sink = *sinks
                    .iter()
                    .min_by_key(|&&k| self.d(k, post) + self.d(a, k))
                    .expect("dual layouts have a sink");
                let at_sink = sinks.contains(&a);
                if at_sink && t + (self.d(a, post) as i32) < pick {
                    Action::Interact
                } else if !at_sink && t + (self.d(a, sink) + 1 + self.d(sink, post)) as i32 <= pick
                {
                    self.step_towards(a, sink)
                } else if a == post {
                    if t >= pick {
                        Action::Interact
                    } else {
                        Action::Wait
                    }
                } else {
                    self.step_towards(a, post)
                }
            }
            _ => {
                if a == post && t >= pick {
                    Action::Interact
                } else if a == post {
                    Action::Wait
                } else {
                    self.step_towards(a, post)
                }
            }
        }
    }
}

impl Oracle {
    fn act_reproduction(&self, s: &KitchenState, rsg: &RsgState) -> Action {
        let a = self.layout.index(s.agent.0, s.agent.1);
        let counter = self.adjacent_to(ObjectKind::DeliveryCounter);
        if s.carry == Carry::Soup {
            return self.go_and_interact(a, self.nearest(a, counter));
        }
        let gain = self
            .rsg
            .as_ref()
            .and_then(|r| r.gains.get(rsg.gain as usize).copied())
            .unwrap_or(1.0);
        let target = ((f64::from(gain) * f64::from(s.td)).round() as i32).max(1);
        let post = *self
            .adjacent_to(ObjectKind::Oven)
            .iter()
            .min_by_key(|&&y| counter.iter().map(|&c| self.d(y, c)).min().unwrap_or(0))
            .expect("validated layouts have an oven");
        if a != post {
            return self.step_towards(a, post);
        }
        // The response `k` steps after Set is taken while the timer reads `k − 1`.
        if s.timer >= 0 && s.timer + 1 >= target {
            Action::Interact
        } else {
            Action::Wait
        }
    }

    /// Multi-oven: the free cells next to oven `i`.
    fn oven_neighbours(&self, i: usize) -> &[usize] {
        self.adjacent_to([ObjectKind::Oven, ObjectKind::Oven2, ObjectKind::Oven3][i])
    }

    fn act_multi_oven(&self, s: &KitchenState, mo: &MultiOvenState) -> Action {
        let a = self.layout.index(s.agent.0, s.agent.1);
        let n = self.rules.extended_ovens().unwrap_or(1);
        match s.carry {
            Carry::Soup => {
                let kind = self.delivery_kind(mo.td[mo.soup_from as usize]);
                self.go_and_interact(a, self.nearest(a, self.adjacent_to(kind)))
            }
            Carry::Onion => self.go_and_interact(a, self.nearest(a, self.oven_neighbours(0))),
            Carry::Nothing => {
                // Any ready oven: the nearest one.
                if let Some(cell) = (0..n)
                    .filter(|&i| mo.ready[i])
                    .map(|i| self.nearest(a, self.oven_neighbours(i)))
                    .min_by_key(|&c| self.d(a, c))
                {
                    return self.go_and_interact(a, cell);
                }
                if !mo.used && mo.timer[0] < 0 {
                    let onion = self.nearest(a, self.adjacent_to(ObjectKind::OnionDispenser));
                    return self.go_and_interact(a, onion);
                }
                // Wait next to the oven that will be ready first (a started oven: its
                // remaining time; one still to start: its on-time plus its duration).
                let remaining = |i: usize| -> Option<i64> {
                    if mo.timer[i] >= 0 {
                        Some(mo.td[i] as i64 - mo.timer[i] as i64)
                    } else if mo.off_time[i] < 0 && mo.on_time[i] >= s.timestep as i32 {
                        Some(mo.on_time[i] as i64 - s.timestep as i64 + mo.td[i] as i64)
                    } else {
                        None
                    }
                };
                match (0..n).filter_map(|i| remaining(i).map(|r| (r, i))).min() {
                    Some((_, i)) => self.step_towards(a, self.nearest(a, self.oven_neighbours(i))),
                    None => Action::Wait,
                }
            }
        }
    }
}

/// Brute-force maximum undiscounted return from `env`'s current state (exhaustive
/// search over all action sequences with memoisation on the hidden state).
///
/// Cost grows with `cells × timer × steps`: use small `max_timesteps` (tests use ≤ 60).
pub fn optimal_return(env: &ChronoEnv) -> f64 {
    fn search(k: &Kitchen, obs: &mut Vec<u8>, memo: &mut HashMap<KitchenState, f64>) -> f64 {
        let key = k.state();
        if key.done {
            return 0.0;
        }
        if let Some(&v) = memo.get(&key) {
            return v;
        }
        let mut best = f64::NEG_INFINITY;
        for a in Action::ALL {
            let mut next = k.clone();
            let t = next.step_unchecked(a, obs);
            let v = t.reward as f64 + search(&next, obs, memo);
            if v > best {
                best = v;
            }
        }
        memo.insert(key, best);
        best
    }
    let mut obs = env.obs_codes().to_vec();
    search(env.kitchen(), &mut obs, &mut HashMap::new())
}
