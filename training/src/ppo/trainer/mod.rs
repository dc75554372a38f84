//! The PPO training loop: rollouts on a [`VecEnv`], GAE, minibatch epochs with BPTT
//! over stored chunks, curricula, and exact checkpoint/restore of the whole state.
//!
//! [`Trainer::update`] reads top-down; the network runs behind a [`PolicyEngine`]
//! (native or burn). Around it: [`collect`] (the rollout), [`batches`] (minibatch orders),
//! [`curriculum`] (curricula), [`log`] (the learning-curve row).

use crate::checked::Checked;
use crate::error::TrainError;
use crate::ppo::adam::{Adam, AdamParams, clip_global_norm};
use crate::ppo::config::{Curriculum, LrSchedule, TrainConfig};
use crate::ppo::engine::{PolicyEngine, new_engine};
use crate::ppo::gae::compute_gae;
use crate::ppo::loss::LossCoefs;
use crate::ppo::minibatch::Minibatch;
use crate::ppo::obs::ObsEncoder;
use crate::ppo::params::{flat_params, param_shapes, write_params};
use crate::ppo::rollout::{Rollout, chunks};
pub use crate::ppo::state::{EpisodeStat, TrainerState, UpdateLog};
use burn::module::Module;
use chronocooked_env::{Action, Autoreset, TaskParams, VecEnv};
use chronocooked_models::deep::native::NativePolicy;
use chronocooked_models::deep::spec::check_shapes;
use chronocooked_models::{ActorCritic, CoreKind, PolicyConfig};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::VecDeque;
use std::ops::Range;
use std::time::Instant;

mod batches;
mod collect;
mod curriculum;
mod log;
use curriculum::set_warmup;
use log::LossSums;

/// An env error about a checkpoint's field as a [`crate::ppo::state::StateError`].
fn state_field(field: &str, e: chronocooked_env::EnvError) -> crate::ppo::state::StateError {
    match e {
        chronocooked_env::EnvError::InvalidParam {
            field: f,
            value,
            allowed,
        } if f.starts_with("envs") => crate::ppo::state::StateError {
            field: f,
            reason: format!("{value} (allowed: {allowed})"),
        },
        other => crate::ppo::state::StateError {
            field: field.into(),
            reason: other.to_string(),
        },
    }
}

/// A PPO trainer for one configuration and seed.
pub struct Trainer {
    cfg: TrainConfig,
    policy_cfg: PolicyConfig,
    /// The policy's burn module; [`Trainer::policy`] writes θ into it.
    model: ActorCritic,
    /// The network: acting, loss and gradient.
    engine: Box<dyn PolicyEngine>,
    envs: VecEnv,
    encoder: ObsEncoder,
    rollout: Rollout,
    state: TrainerState,
    scratch_obs: Vec<f32>,
    /// The minibatch gradient `[P]` (flat layout).
    grad: Vec<f32>,
    /// Reservoir cores: the core's parameter range in θ (its weights never change).
    reservoir_core: Option<Range<usize>>,
    /// The multi-timer curriculum level the last update left and θ as it left it (the
    /// policy whose episodes passed the level's threshold), until taken.
    left_level: Option<(usize, Vec<f32>)>,
}

impl Trainer {
    /// Builds a fresh trainer (weights, envs and RNG from `cfg.seed`) from a checked
    /// configuration ([`crate::checked::Check::check`]).
    pub fn new(cfg: Checked<TrainConfig>) -> Result<Self, TrainError> {
        let cfg = cfg.into_inner();
        let task = cfg.task.config()?;
        let p = &cfg.ppo;
        let mut envs = VecEnv::new(&task, p.n_envs, Autoreset::SameStep)?;
        let mut encoder = ObsEncoder::new(cfg.obs, &envs).stacked(cfg.model.frames);
        if cfg.model.frames > 1 {
            encoder.set_history(&vec![0.0; p.n_envs * encoder.len()]);
        }
        let mut policy_cfg = PolicyConfig::new(
            cfg.model,
            encoder.cells(),
            encoder.channels(),
            Action::COUNT,
        );
        policy_cfg.core_init = cfg.core_init;
        let device = chronocooked_models::cpu_autodiff();
        let mut model = policy_cfg.init(cfg.seed, &device);
        let spec = chronocooked_models::deep::spec::param_spec(&policy_cfg);
        if let Some(dir) = &cfg.init_from {
            let (source, ..) = crate::ppo::run_dir::load_policy(std::path::Path::new(dir))?;
            check_shapes(&spec, &param_shapes(&source)).map_err(|why| {
                TrainError::InvalidParam {
                    field: "init_from".into(),
                    value: dir.clone(),
                    allowed: format!("a run of the same architecture ({why})"),
                }
            })?;
            model = write_params(model, &flat_params(&source));
        }
        // The native engine reads the module's parameters through the same specification.
        check_shapes(&spec, &param_shapes(&model)).map_err(TrainError::SpecMismatch)?;
        let theta = flat_params(&model);
        let engine = new_engine(
            p.engine,
            &policy_cfg,
            &model,
            p.detach_critic,
            cfg.model.reservoir && !p.reservoir_grad_in_norm,
        );
        let layout = NativePolicy::new(&policy_cfg).layout().clone();
        let adam = Adam::new(
            theta.len(),
            AdamParams {
                eps: p.adam_eps,
                ..AdamParams::default()
            },
        );
        envs.reset(chronocooked_env::derive_seed(cfg.seed, 0x5EED));
        let num_timers = match &task.params {
            TaskParams::MultiTimer { num_timers, .. } => *num_timers,
            _ => 1,
        };
        let mut state = TrainerState {
            steps: 0,
            updates: 0,
            theta,
            adam,
            envs: envs.snapshot(),
            keep: vec![0.0; p.n_envs],
            core_state: None,
            frame_history: encoder.history(),
            rng: Xoshiro256PlusPlus::seed_from_u64(chronocooked_env::derive_seed(cfg.seed, 0xAC7)),
            ep_return: vec![0.0; p.n_envs],
            ep_len: vec![0; p.n_envs],
            recent: VecDeque::new(),
            since_change: 0,
            episodes: 0,
            num_timers,
            curriculum_level: 0,
            never_ready_prob: 0.0,
            wall_s: 0.0,
            curve: Vec::new(),
            reservoir_grad: Vec::new(),
        };
        if let Curriculum::MultiTimer { warmup, .. } = cfg.curriculum {
            state.num_timers = 1;
            state.curriculum_level = usize::from(!warmup);
            envs.set_num_timers(1)?;
            if warmup {
                set_warmup(&mut envs, &task, true)?;
            }
            envs.reset(chronocooked_env::derive_seed(cfg.seed, 0x5EED));
            state.envs = envs.snapshot();
        }
        state.never_ready_prob = f64::from(task.never_ready_prob());
        // Growing curricula start with the fewest counters / ovens.
        let grows = cfg.curriculum.growth().is_some();
        curriculum::growth_last_level(&cfg)?;
        let rollout = Rollout::new(p.n_envs, p.n_steps, encoder.len());
        let mut t = Trainer {
            scratch_obs: vec![0.0; p.n_envs * encoder.len()],
            grad: vec![0.0; layout.total],
            reservoir_core: layout.core_range().filter(|_| cfg.model.reservoir),
            engine,
            cfg,
            policy_cfg,
            model,
            envs,
            encoder,
            rollout,
            state,
            left_level: None,
        };
        if grows {
            t.set_growth_level(0)?;
        }
        t.apply_curriculum()?;
        t.apply_tolerance()?;
        Ok(t)
    }

    /// Rebuilds a trainer from a configuration and a checkpointed state. The state is
    /// checked first ([`TrainerState::validate`], then the env snapshot): a state that does
    /// not fit the configuration is an error naming the field, never a panic later.
    pub fn restore(cfg: Checked<TrainConfig>, state: TrainerState) -> Result<Self, TrainError> {
        let mut t = Trainer::new(cfg)?;
        let arch = t.cfg.model;
        let batch = (t.cfg.ppo.n_envs * t.cfg.ppo.n_steps) as u64;
        state
            .validate(
                &t.state,
                arch.hidden,
                arch.core == Some(CoreKind::Lstm),
                arch.is_recurrent(),
                batch,
            )
            .map_err(TrainError::BadState)?;
        if let Curriculum::MultiTimer { warmup, .. } = t.cfg.curriculum {
            t.envs
                .set_num_timers(state.num_timers)
                .map_err(|e| TrainError::BadState(state_field("num_timers", e)))?;
            if warmup {
                let task = t.cfg.task.config()?;
                set_warmup(&mut t.envs, &task, state.curriculum_level == 0)?;
            }
        }
        if t.cfg.curriculum.growth().is_some() {
            let last = curriculum::growth_last_level(&t.cfg)?;
            if state.curriculum_level > last {
                return Err(TrainError::BadState(crate::ppo::state::StateError {
                    field: "curriculum_level".into(),
                    reason: format!(
                        "{} (allowed: 0..={last}, the levels of this curriculum)",
                        state.curriculum_level
                    ),
                }));
            }
            t.set_growth_level(state.curriculum_level)?;
        }
        if let Curriculum::Tolerance { levels, .. } = t.cfg.curriculum
            && state.curriculum_level >= levels
        {
            return Err(TrainError::BadState(crate::ppo::state::StateError {
                field: "curriculum_level".into(),
                reason: format!(
                    "{} (allowed: 0..={}, the levels of this curriculum)",
                    state.curriculum_level,
                    levels - 1
                ),
            }));
        }
        t.envs
            .restore(&state.envs)
            .map_err(|e| TrainError::BadState(state_field("envs", e)))?;
        t.engine.sync(&state.theta);
        t.state = state;
        t.apply_curriculum()?;
        t.apply_tolerance()?;
        Ok(t)
    }

    /// The configuration.
    pub fn config(&self) -> &TrainConfig {
        &self.cfg
    }

    /// The task the envs play now (a curriculum may have changed it from the configured
    /// one: timers, counters, ovens, reward window).
    pub fn task(&self) -> &chronocooked_env::TaskConfig {
        self.envs.config()
    }

    /// The policy's architecture description.
    pub fn policy_config(&self) -> &PolicyConfig {
        &self.policy_cfg
    }

    /// The full state (a checkpoint: pair it with the config).
    pub fn state(&self) -> &TrainerState {
        &self.state
    }

    /// A copy of the current policy without autodiff (for acting and saving).
    pub fn policy(&self) -> ActorCritic {
        write_params(self.model.clone(), &self.state.theta).valid()
    }

    /// The multi-timer curriculum level the last update left, with the policy as it left
    /// it (`None` when the last update changed no level or it was taken already).
    pub fn take_left_level(&mut self) -> Option<(usize, ActorCritic)> {
        let (level, theta) = self.left_level.take()?;
        Some((level, write_params(self.model.clone(), &theta).valid()))
    }

    /// Whether the step budget is spent.
    pub fn finished(&self) -> bool {
        self.state.steps >= self.cfg.total_steps
    }

    /// Reservoir cores: zeroes the core's gradient (its weights never change) — after
    /// adding it to the accumulated reservoir gradient that the paper's code carries into
    /// its gradient-norm clip when `reservoir_grad_in_norm` is set — then clips the global
    /// norm. Returns the norm before clipping.
    fn clip_gradient(&mut self) -> f64 {
        let max = self.cfg.ppo.max_grad_norm as f64;
        let Some(range) = self.reservoir_core.clone() else {
            return clip_global_norm(&mut self.grad, max);
        };
        if !self.cfg.ppo.reservoir_grad_in_norm {
            self.grad[range].fill(0.0);
            return clip_global_norm(&mut self.grad, max);
        }
        let acc = &mut self.state.reservoir_grad;
        if acc.len() != range.len() {
            acc.clear();
            acc.resize(range.len(), 0.0);
        }
        for (g, a) in self.grad[range.clone()].iter_mut().zip(acc.iter()) {
            *g += *a;
        }
        let norm = clip_global_norm(&mut self.grad, max);
        acc.copy_from_slice(&self.grad[range.clone()]);
        self.grad[range].fill(0.0);
        norm
    }

    /// One PPO update, top-down as CleanRL writes it (with SB3's semantics): a rollout with
    /// the current policy, GAE, then `n_epochs` passes over shuffled minibatches, each a
    /// loss with its gradient, a clip of the gradient's global norm and an Adam step.
    /// Returns the learning-curve row (already appended to the state's curve).
    pub fn update(&mut self) -> Result<UpdateLog, TrainError> {
        let started = Instant::now();
        let p = self.cfg.ppo.clone();
        self.apply_curriculum()?;

        // Rollout, then advantages and returns.
        let last_values = self.collect()?;
        (self.rollout.advantages, self.rollout.returns) = compute_gae(
            &self.rollout.rewards,
            &self.rollout.values,
            &self.rollout.dones,
            &last_values,
            p.gamma,
            p.gae_lambda,
        );
        self.state.steps += (p.n_envs * p.n_steps) as u64;
        let rollout_s = started.elapsed().as_secs_f64();

        // The multi-timer curriculum is checked at the rollout's end, as the paper's
        // callback does: a level left keeps the policy that collected the passing episodes
        // (the environments change now; the optimisation below does not use them).
        let level = self.state.curriculum_level;
        self.advance_multi_timer()?;
        self.advance_growth()?;
        self.advance_tolerance()?;
        if self.state.curriculum_level != level && self.cfg.curriculum.has_levels() {
            self.left_level = Some((level, self.state.theta.clone()));
        }

        // Epochs × minibatches: loss and gradient, clip, optimiser step.
        let lr = self.learning_rate();
        let coefs = LossCoefs {
            clip_range: p.clip_range,
            clip_range_vf: p.clip_range_vf,
            ent_coef: p.ent_coef,
            vf_coef: p.vf_coef,
        };
        let mut sums = LossSums::default();
        let mut all = chunks(p.n_envs, p.n_steps, self.chunk_len());
        'epochs: for _ in 0..p.n_epochs {
            for (mb, l) in self.epoch_batches(&mut all) {
                let hidden = self.cfg.model.hidden;
                let batch = Minibatch::gather(&self.rollout, &mb, l, hidden, p.normalize_advantage);
                let theta = &self.state.theta;
                let loss = self
                    .engine
                    .loss_and_grad(theta, &batch, coefs, &mut self.grad);
                // SB3's early stop: this minibatch's gradient is not applied.
                if p.target_kl.is_some_and(|t| loss.approx_kl > 1.5 * t as f64) {
                    break 'epochs;
                }
                if !loss.loss.is_finite() {
                    return Err(self.diverged(format!(
                        "non-finite loss (policy {}, value {}, entropy {})",
                        loss.policy_loss, loss.value_loss, loss.entropy_loss
                    )));
                }
                let norm = self.clip_gradient();
                if !norm.is_finite() {
                    return Err(self.diverged("non-finite gradient norm".into()));
                }
                self.state.adam.step(&mut self.state.theta, &self.grad, lr);
                self.engine.sync(&self.state.theta);
                sums.add(&loss, norm);
            }
        }
        if self.state.theta.iter().any(|x| !x.is_finite()) {
            return Err(self.diverged("non-finite parameters after the update".into()));
        }

        // The learning-curve row.
        self.state.updates += 1;
        let secs = started.elapsed().as_secs_f64();
        self.state.wall_s += secs;
        let row = self.curve_row(&sums, lr, rollout_s, secs);
        self.state.envs = self.envs.snapshot();
        self.state.curve.push(row.clone());
        Ok(row)
    }

    /// The learning rate of the update whose rollout was just collected (constant, or
    /// decayed linearly over the step budget from the rollout's first step).
    fn learning_rate(&self) -> f64 {
        let p = &self.cfg.ppo;
        match p.lr_schedule {
            LrSchedule::Constant => p.learning_rate,
            LrSchedule::Linear => {
                let done = (self.state.steps - (p.n_envs * p.n_steps) as u64) as f64;
                p.learning_rate * (1.0 - done / self.cfg.total_steps as f64).max(0.0)
            }
        }
    }

    /// Records a deterministic-evaluation result on the last curve row.
    pub fn set_last_eval(&mut self, success: f64) {
        if let Some(r) = self.state.curve.last_mut() {
            r.eval_success = Some(success);
        }
    }

    fn diverged(&self, what: String) -> TrainError {
        TrainError::Diverged {
            step: self.state.steps,
            what,
            checkpoint: "the run folder's checkpoints/".into(),
        }
    }
}
