//! A Bayesian observer as an agent of the reproduction task (`eval --agent bls:WM,WP`).
//!
//! The agent sees what any agent sees: the oven's Ready and Set flashes (channel 4 = 2) and
//! the context cue on the counter. From the flashes it takes the sample interval `ts`
//! (steps between the two), measures it with scalar noise (`tm ~ N(ts, (wm·ts)²)`),
//! estimates `te = f(tm)` with its observer (BLS, MAP or ML) under the cued prior (the
//! union of the task's priors when the cue does not name one), and produces
//! `tp ~ N(g·te, (wp·g·te)²)`, rounded to whole steps (at least 1): it takes the soup out
//! `tp` steps after Set and delivers it. It walks with the task's oracle (reading only its
//! own cell and what it carries, both visible in the observation), so its productions are
//! exactly the observer's.
//!
//! Jazayeri & Shadlen 2010's subjects: `wm` about 0.1, `wp` about 0.06 (their Fig. 4 range);
//! those are the defaults.

use super::{Observer, ObserverError, Prior};
use crate::Agent;
use chronocooked_env::{Action, ChronoEnv, KitchenState, Oracle};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_xoshiro::Xoshiro256PlusPlus;

/// Default measurement Weber fraction (J&S 2010's subjects, about 0.1).
pub const DEFAULT_WM: f64 = 0.1;
/// Default production Weber fraction (J&S 2010's subjects, about 0.06).
pub const DEFAULT_WP: f64 = 0.06;

/// A Bayesian observer playing the reproduction task.
#[derive(Debug, Clone)]
pub struct ObserverAgent {
    observer: Observer,
    wm: f64,
    wp: f64,
    /// The task's priors, then their union (used when no prior is cued).
    priors: Vec<Prior>,
    gains: Vec<f64>,
    prior_cue: bool,
    oven: usize,
    counter: usize,
    /// An oracle of the same layout with gain 1: it walks, and takes the soup out at the
    /// production the agent hands it.
    nav: Oracle,
    rng: Xoshiro256PlusPlus,
    steps: u32,
    ready: Option<u32>,
    set: Option<u32>,
    production: Option<u32>,
    context: (usize, usize),
    state: Option<KitchenState>,
}

impl ObserverAgent {
    /// The observer on `env`'s task (reproduction only) with noise `wm`, `wp`.
    pub fn new(
        env: &ChronoEnv,
        observer: Observer,
        wm: f64,
        wp: f64,
    ) -> Result<Self, ObserverError> {
        for (field, w) in [("wm", wm), ("wp", wp)] {
            if !(super::W_MIN..=super::W_MAX).contains(&w) {
                return Err(ObserverError::OutOfRange {
                    field,
                    value: w,
                    min: super::W_MIN,
                    max: super::W_MAX,
                });
            }
        }
        let Some(rsg) = env.ready_set_go() else {
            return Err(ObserverError::Task(format!(
                "task {} has no Ready-Set-Go mechanics (no prior of sample intervals to reproduce)",
                env.config().id
            )));
        };
        let mut all = Vec::new();
        let mut out = Vec::new();
        for &(lo, hi) in &rsg.priors {
            let values: Vec<f64> = (lo..=hi).map(f64::from).collect();
            all.extend(values.iter().copied());
            out.push(Prior::new(&values)?);
        }
        all.sort_by(f64::total_cmp);
        all.dedup();
        out.push(Prior::new(&all)?);
        let gain_values: Vec<f64> = rsg.gains.iter().map(|&g| f64::from(g)).collect();
        let cue = rsg.prior_cue;
        let layout = env.layout();
        let cell = |kind| layout.cells_of(kind)[0];
        Ok(ObserverAgent {
            observer,
            wm,
            wp,
            priors: out,
            gains: gain_values,
            prior_cue: cue,
            oven: cell(chronocooked_env::ObjectKind::Oven),
            counter: cell(chronocooked_env::ObjectKind::DeliveryCounter),
            nav: Oracle::new(env).producing_td(),
            rng: Xoshiro256PlusPlus::seed_from_u64(0),
            steps: 0,
            ready: None,
            set: None,
            production: None,
            context: (0, 0),
            state: None,
        })
    }

    /// The prior and gain the counter's cue names (`v − 1 = prior · gains + gain`).
    fn decode(&self, cue: u8) -> (usize, usize) {
        let n_gains = self.gains.len();
        let n_priors = self.priors.len() - 1;
        if cue == 0 {
            return (if n_priors == 1 { 0 } else { n_priors }, 0);
        }
        let v = cue as usize - 1;
        if self.prior_cue {
            ((v / n_gains).min(n_priors - 1), v % n_gains)
        } else {
            (if n_priors == 1 { 0 } else { n_priors }, v % n_gains)
        }
    }

    fn produce(&mut self, ts: f64) -> u32 {
        let (p, g) = self.context;
        let gain = self.gains[g];
        let z1: f64 = StandardNormal.sample(&mut self.rng);
        let z2: f64 = StandardNormal.sample(&mut self.rng);
        let tm = ts + self.wm * ts * z1;
        let te = self
            .observer
            .estimate(tm, self.wm, &self.priors[p])
            .unwrap_or(ts);
        let target = gain * te;
        let tp = target + self.wp * target.abs() * z2;
        tp.round().max(1.0) as u32
    }
}

impl Agent for ObserverAgent {
    fn name(&self) -> String {
        self.observer.name().to_ascii_lowercase()
    }

    fn begin_episode(&mut self, obs: &[u8], seed: u64) {
        self.rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        self.steps = 0;
        self.ready = None;
        self.set = None;
        self.production = None;
        self.context = self.decode(obs[self.counter * chronocooked_env::CODE_CHANNELS + 4]);
    }

    fn act(&mut self, obs: &[u8]) -> Action {
        if obs[self.oven * chronocooked_env::CODE_CHANNELS + 4] == 2 {
            match (self.ready, self.set) {
                (None, _) => self.ready = Some(self.steps),
                (Some(r), None) if self.steps > r => {
                    self.set = Some(self.steps);
                    let k = self.produce(f64::from(self.steps - r));
                    self.production = Some(k);
                }
                _ => {}
            }
        }
        let action = match self.state {
            Some(mut s) => {
                // The oracle (gain 1) takes the soup out when `timer + 1 ≥ td`: hand it the
                // agent's own production and the steps since the Set it saw.
                s.td = self.production.unwrap_or(u32::MAX / 2);
                s.timer = match (self.set, s.carry) {
                    (Some(set), chronocooked_env::Carry::Nothing) => (self.steps - set) as i32,
                    _ => -1,
                };
                if let Some(r) = s.reproduction.as_mut() {
                    r.gain = 0;
                }
                self.nav.act(&s)
            }
            None => Action::Wait,
        };
        self.steps += 1;
        action
    }

    fn noise_draws(&self) -> usize {
        crate::timing::agent::NOISE_DRAWS
    }

    /// Only the agent's cell and what it carries are read (both visible in the
    /// observation); the timing comes from the cues it saw.
    fn observe_state(&mut self, state: &KitchenState) {
        self.state = Some(*state);
    }
}
