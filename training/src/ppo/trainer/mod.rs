//! The PPO training loop: rollouts on a [`VecEnv`], GAE, minibatch epochs with BPTT
//! over stored chunks, curricula, and exact checkpoint/restore of the whole state.

use crate::error::TrainError;
use crate::ppo::act::{Actor, FlatState, sample};
use crate::ppo::adam::{Adam, AdamParams, clip_global_norm};
use crate::ppo::config::{Curriculum, Engine, LrSchedule, RecurrentBatches, TrainConfig};
use crate::ppo::gae::{compute_gae, explained_variance};
use crate::ppo::loss::LossCoefs;
use crate::ppo::minibatch::{Minibatch, burn_gradient};
use crate::ppo::obs::ObsEncoder;
use crate::ppo::params::{flat_params, param_shapes, write_params};
use crate::ppo::rollout::{Chunk, Rollout, chunks, sequence_batches};
pub use crate::ppo::state::{EpisodeStat, TrainerState, UpdateLog};
use burn::module::Module;
use burn::tensor::Device;
use chronocooked_env::{Action, Autoreset, TaskParams, VecEnv, make_config};
use chronocooked_models::deep::native::{Cache, NativePolicy};
use chronocooked_models::deep::spec::check_shapes;
use chronocooked_models::{ActorCritic, CoreKind, PolicyConfig};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::collections::VecDeque;
use std::time::Instant;

mod curriculum;
use curriculum::set_warmup;

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
    device: Device,
    model: ActorCritic,
    envs: VecEnv,
    encoder: ObsEncoder,
    rollout: Rollout,
    state: TrainerState,
    scratch_obs: Vec<f32>,
    native: NativePolicy,
    cache: Cache,
    grad: Vec<f32>,
}

impl Trainer {
    /// Builds a fresh trainer (weights, envs and RNG from `cfg.seed`).
    pub fn new(cfg: TrainConfig) -> Result<Self, TrainError> {
        cfg.validate()?;
        let task = make_config(&cfg.task, &cfg.env)?;
        let p = &cfg.ppo;
        let mut envs = VecEnv::new(&task, p.n_envs, Autoreset::SameStep)?;
        let encoder = ObsEncoder::new(cfg.obs, &envs);
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
            let (source, ..) = crate::run_dir::load_policy(std::path::Path::new(dir))?;
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
        let native = NativePolicy::new(&policy_cfg)
            .with_detached_critic(p.detach_critic)
            .with_frozen_core(cfg.model.reservoir && !p.reservoir_grad_in_norm);
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
        if let TaskParams::Uncertainty {
            never_ready_prob, ..
        } = &task.params
        {
            state.never_ready_prob = *never_ready_prob as f64;
        }
        let rollout = Rollout::new(p.n_envs, p.n_steps, encoder.len());
        let mut t = Trainer {
            scratch_obs: vec![0.0; p.n_envs * encoder.len()],
            grad: vec![0.0; native.num_params()],
            native,
            cache: Cache::default(),
            cfg,
            policy_cfg,
            device,
            model,
            envs,
            encoder,
            rollout,
            state,
        };
        t.apply_curriculum()?;
        Ok(t)
    }

    /// Rebuilds a trainer from a configuration and a checkpointed state. The state is
    /// checked first ([`TrainerState::validate`], then the env snapshot): a state that does
    /// not fit the configuration is an error naming the field, never a panic later.
    pub fn restore(cfg: TrainConfig, state: TrainerState) -> Result<Self, TrainError> {
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
                let task = make_config(&t.cfg.task, &t.cfg.env)?;
                set_warmup(&mut t.envs, &task, state.curriculum_level == 0)?;
            }
        }
        t.envs
            .restore(&state.envs)
            .map_err(|e| TrainError::BadState(state_field("envs", e)))?;
        t.model = write_params(t.model, &state.theta);
        t.state = state;
        t.apply_curriculum()?;
        Ok(t)
    }

    /// The configuration.
    pub fn config(&self) -> &TrainConfig {
        &self.cfg
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
        self.model.valid()
    }

    /// Whether the step budget is spent.
    pub fn finished(&self) -> bool {
        self.state.steps >= self.cfg.total_steps
    }

    fn chunk_len(&self) -> usize {
        match (self.cfg.model.is_recurrent(), self.cfg.ppo.bptt_len) {
            (false, _) => 1,
            (true, 0) => self.cfg.ppo.n_steps,
            (true, l) => l.min(self.cfg.ppo.n_steps),
        }
    }

    /// Whether recurrent minibatches are sb3-contrib sequences (else fixed chunks).
    fn sequence_batches(&self) -> bool {
        self.cfg.model.is_recurrent()
            && self.cfg.ppo.recurrent_batches == RecurrentBatches::Sequences
    }

    /// Rollout steps between stored recurrent states (every step for sequence batches,
    /// whose sequences may start anywhere).
    fn state_stride(&self) -> usize {
        if self.sequence_batches() {
            1
        } else {
            self.chunk_len()
        }
    }

    /// One epoch's minibatches: each a list of chunks and the padded chunk length.
    fn epoch_batches(&mut self, all: &mut [Chunk]) -> Vec<(Vec<Chunk>, usize)> {
        let p = &self.cfg.ppo;
        if self.sequence_batches() {
            let m = p.n_envs * p.n_steps;
            let split = self.state.rng.random_range(0..m);
            sequence_batches(&self.rollout.keep, p.n_envs, p.n_steps, p.batch_size, split)
                .into_iter()
                .map(|mb| {
                    let l = mb.iter().map(|c| c.len).max().unwrap_or(1);
                    (mb, l)
                })
                .collect()
        } else {
            let l = self.chunk_len();
            let per_mb = (p.batch_size / l).max(1);
            all.shuffle(&mut self.state.rng);
            all.chunks(per_mb).map(|mb| (mb.to_vec(), l)).collect()
        }
    }

    /// Reservoir cores: zeroes the core's gradient (its weights never change) — after
    /// adding it to the accumulated reservoir gradient that the paper's code carries into
    /// its gradient-norm clip when `reservoir_grad_in_norm` is set — then clips the global
    /// norm. Returns the norm before clipping.
    fn clip_gradient(&mut self) -> f64 {
        let max = self.cfg.ppo.max_grad_norm as f64;
        let range = match self.native.layout().core_range() {
            Some(r) if self.cfg.model.reservoir => r,
            _ => return clip_global_norm(&mut self.grad, max),
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

    /// Collects one rollout with the current policy.
    fn collect(&mut self, actor: &mut Actor) -> Result<(), TrainError> {
        let (n, t_len) = (self.cfg.ppo.n_envs, self.cfg.ppo.n_steps);
        let gamma = self.cfg.ppo.gamma;
        let (cells, ch, olen) = (
            self.encoder.cells(),
            self.encoder.channels(),
            self.encoder.len(),
        );
        let l = self.state_stride();
        let arch = self.cfg.model;
        let recurrent = arch.is_recurrent();
        let mut core: FlatState = match self.state.core_state.take() {
            Some(st) => st,
            None if recurrent => (
                vec![0.0; n * arch.hidden],
                (arch.core == Some(CoreKind::Lstm)).then(|| vec![0.0; n * arch.hidden]),
            ),
            None => (Vec::new(), None),
        };
        self.rollout.chunk_states.clear();
        let obs_tensor_len = n * olen;
        let mut final_buf = vec![0f32; olen];
        for t in 0..t_len {
            if recurrent && t % l == 0 {
                self.rollout.chunk_states.push(core.clone());
            }
            self.encoder
                .encode_batch(&self.envs.obs, &mut self.scratch_obs);
            let keep = self.state.keep.clone();
            let (logits, values, new_core) = actor.step(&self.scratch_obs, cells, ch, &keep, &core);
            core = new_core;
            let base = t * n;
            self.rollout.obs[base * olen..base * olen + obs_tensor_len]
                .copy_from_slice(&self.scratch_obs);
            let mut actions = vec![0u8; n];
            for e in 0..n {
                let na = Action::COUNT;
                let (a, lp) = sample(&logits[e * na..(e + 1) * na], &mut self.state.rng);
                actions[e] = a as u8;
                self.rollout.actions[base + e] = a as i64;
                self.rollout.log_probs[base + e] = lp;
                self.rollout.values[base + e] = values[e];
                self.rollout.keep[base + e] = keep[e];
            }
            self.envs.step(&actions)?;
            for e in 0..n {
                let mut r = self.envs.rewards[e];
                let term = self.envs.terminated[e];
                let trunc = self.envs.truncated[e];
                self.state.ep_return[e] += r;
                self.state.ep_len[e] += 1;
                if trunc && !term {
                    // Time-limit bootstrap: r += γ V(final obs), with the state after this step.
                    self.encoder.encode(
                        &self.envs.final_obs
                            [e * self.envs.obs_len()..(e + 1) * self.envs.obs_len()],
                        &mut final_buf,
                    );
                    let h = arch.hidden;
                    let st: FlatState = (
                        core.0.get(e * h..(e + 1) * h).unwrap_or(&[]).to_vec(),
                        core.1.as_ref().map(|c| c[e * h..(e + 1) * h].to_vec()),
                    );
                    let (_, v, _) = actor.step(&final_buf, cells, ch, &[1.0], &st);
                    r += gamma * v[0];
                }
                self.rollout.rewards[base + e] = r;
                self.rollout.dones[base + e] = term || trunc;
                self.state.keep[e] = if term || trunc { 0.0 } else { 1.0 };
                if term || trunc {
                    let info = &self.envs.final_infos[e];
                    let success =
                        chronocooked_models::agent::is_success(info, self.envs.rewards[e]);
                    self.state.recent.push_back(EpisodeStat {
                        ret: self.state.ep_return[e],
                        len: self.state.ep_len[e],
                        success,
                        never_ready: info.never_ready,
                    });
                    while self.state.recent.len() > self.cfg.stats_window.max(1) {
                        self.state.recent.pop_front();
                    }
                    self.state.episodes += 1;
                    self.state.since_change += 1;
                    self.state.ep_return[e] = 0.0;
                    self.state.ep_len[e] = 0;
                }
            }
        }
        // Values of the observations after the last step (GAE bootstrap).
        self.encoder
            .encode_batch(&self.envs.obs, &mut self.scratch_obs);
        let keep = self.state.keep.clone();
        let (_, last_values, _) = actor.step(&self.scratch_obs, cells, ch, &keep, &core);
        self.state.core_state = recurrent.then_some(core);
        let (adv, ret) = compute_gae(
            &self.rollout.rewards,
            &self.rollout.values,
            &self.rollout.dones,
            &last_values,
            gamma,
            self.cfg.ppo.gae_lambda,
        );
        self.rollout.advantages = adv;
        self.rollout.returns = ret;
        self.state.steps += (n * t_len) as u64;
        Ok(())
    }

    /// One PPO update: a rollout, then `n_epochs` passes of minibatch steps.
    /// Returns the learning-curve row (already appended to the state's curve).
    pub fn update(&mut self) -> Result<UpdateLog, TrainError> {
        let started = Instant::now();
        self.apply_curriculum()?;
        let engine = self.cfg.ppo.engine;
        let mut actor = match engine {
            Engine::Native => Actor::Native {
                net: self.native.clone(),
                theta: self.state.theta.clone(),
                cache: std::mem::take(&mut self.cache),
            },
            Engine::Burn => Actor::Burn {
                model: self.model.valid(),
                device: chronocooked_models::cpu(),
            },
        };
        self.collect(&mut actor)?;
        if let Actor::Native { cache, .. } = actor {
            self.cache = cache;
        }
        let rollout_s = started.elapsed().as_secs_f64();
        let p = self.cfg.ppo.clone();
        let lr = match p.lr_schedule {
            LrSchedule::Constant => p.learning_rate,
            LrSchedule::Linear => {
                let done = (self.state.steps - (p.n_envs * p.n_steps) as u64) as f64;
                p.learning_rate * (1.0 - done / self.cfg.total_steps as f64).max(0.0)
            }
        };
        let mut all = chunks(p.n_envs, p.n_steps, self.chunk_len());
        let (mut pl, mut vl, mut el, mut kl, mut cf, mut gn, mut count) =
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0usize);
        let coefs = LossCoefs {
            clip_range: p.clip_range,
            clip_range_vf: p.clip_range_vf,
            ent_coef: p.ent_coef,
            vf_coef: p.vf_coef,
        };
        'epochs: for _ in 0..p.n_epochs {
            for (mb, l) in self.epoch_batches(&mut all) {
                let batch = Minibatch::gather(
                    &self.rollout,
                    &mb,
                    l,
                    self.cfg.model.hidden,
                    p.normalize_advantage,
                );
                let (out, pending) = match engine {
                    Engine::Native => {
                        let (out, dl, dv) = batch.loss_native(
                            &self.native,
                            &self.state.theta,
                            &mut self.cache,
                            coefs,
                        );
                        (out, Pending::Native(dl, dv))
                    }
                    Engine::Burn => {
                        let shape = (self.encoder.cells(), self.encoder.channels());
                        let detach = p.detach_critic;
                        let (out, sur, aux) = batch.loss_burn(
                            &self.model,
                            &self.device,
                            shape,
                            Action::COUNT,
                            coefs,
                            detach,
                        );
                        (out, Pending::Burn(Box::new((sur, aux))))
                    }
                };
                if let Some(target) = p.target_kl
                    && out.approx_kl > 1.5 * target as f64
                {
                    break 'epochs;
                }
                if !out.loss.is_finite() {
                    return Err(self.diverged(format!(
                        "non-finite loss (policy {}, value {}, entropy {})",
                        out.policy_loss, out.value_loss, out.entropy_loss
                    )));
                }
                match pending {
                    Pending::Native(dl, dv) => {
                        let theta = &self.state.theta;
                        self.native
                            .backward(theta, &mut self.cache, &dl, &dv, &mut self.grad);
                    }
                    Pending::Burn(b) => {
                        let (sur, aux) = *b;
                        self.grad = burn_gradient(&self.model, sur, aux);
                    }
                }
                let norm = self.clip_gradient();
                if !norm.is_finite() {
                    return Err(self.diverged("non-finite gradient norm".into()));
                }
                self.state.adam.step(&mut self.state.theta, &self.grad, lr);
                if engine == Engine::Burn {
                    self.sync_model();
                }
                pl += out.policy_loss;
                vl += out.value_loss;
                el += out.entropy_loss;
                kl += out.approx_kl;
                cf += out.clip_fraction;
                gn += norm;
                count += 1;
            }
        }
        if self.state.theta.iter().any(|x| !x.is_finite()) {
            return Err(self.diverged("non-finite parameters after the update".into()));
        }
        if engine == Engine::Native {
            self.sync_model();
        }
        self.state.updates += 1;
        self.advance_multi_timer()?;
        let secs = started.elapsed().as_secs_f64();
        self.state.wall_s += secs;
        let c = count.max(1) as f64;
        let recent = &self.state.recent;
        let k = recent.len().max(1) as f64;
        let row = UpdateLog {
            update: self.state.updates,
            env_steps: self.state.steps,
            wall_s: self.state.wall_s,
            steps_per_s: (p.n_envs * p.n_steps) as f64 / secs.max(1e-9),
            rollout_s,
            optimize_s: secs - rollout_s,
            ep_return_mean: if recent.is_empty() {
                f64::NAN
            } else {
                recent.iter().map(|e| e.ret as f64).sum::<f64>() / k
            },
            ep_len_mean: if recent.is_empty() {
                f64::NAN
            } else {
                recent.iter().map(|e| e.len as f64).sum::<f64>() / k
            },
            success_rate: if recent.is_empty() {
                f64::NAN
            } else {
                recent.iter().filter(|e| e.success).count() as f64 / k
            },
            never_ready_success: {
                let nr: Vec<&EpisodeStat> = recent.iter().filter(|e| e.never_ready).collect();
                if nr.is_empty() {
                    f64::NAN
                } else {
                    nr.iter().filter(|e| e.success).count() as f64 / nr.len() as f64
                }
            },
            episodes: self.state.episodes,
            policy_loss: pl / c,
            value_loss: vl / c,
            entropy: -el / c,
            approx_kl: kl / c,
            clip_fraction: cf / c,
            explained_variance: explained_variance(&self.rollout.values, &self.rollout.returns),
            grad_norm: gn / c,
            learning_rate: lr,
            num_timers: self.state.num_timers,
            curriculum_level: self.state.curriculum_level,
            never_ready_prob: self.state.never_ready_prob,
            eval_success: None,
        };
        self.state.envs = self.envs.snapshot();
        self.state.curve.push(row.clone());
        Ok(row)
    }

    /// Records a deterministic-evaluation result on the last curve row.
    pub fn set_last_eval(&mut self, success: f64) {
        if let Some(r) = self.state.curve.last_mut() {
            r.eval_success = Some(success);
        }
    }

    /// Writes the flat parameters into the burn module.
    fn sync_model(&mut self) {
        self.model = write_params(self.model.clone(), &self.state.theta);
    }

    fn diverged(&self, what: String) -> TrainError {
        TrainError::Diverged {
            step: self.state.steps,
            what,
            checkpoint: "the run folder's checkpoints/".into(),
        }
    }
}

/// A minibatch's gradient still to be computed, per engine.
enum Pending {
    /// `∂L/∂logits [M, A]`, `∂L/∂values [M]`.
    Native(Vec<f32>, Vec<f32>),
    /// burn surrogate and the split-BPTT auxiliary data.
    Burn(
        Box<(
            burn::tensor::Tensor<1>,
            Option<chronocooked_models::deep::cores::SeqAux>,
        )>,
    ),
}
