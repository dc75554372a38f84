//! A trained PPO network as an [`Agent`]: the same interface and activity recording as the
//! timing models. Greedy (argmax) when not training, sampled from the policy otherwise.
//!
//! Recorded populations: `latent` — what the heads read (the recurrent core's hidden state
//! `h`, or the CNN trunk's 64 features for CNN-MLP); `cell` — the LSTM cell state `c`
//! (LSTM only); `value` — the critic's estimate.

use crate::error::TrainError;
use crate::ppo::act::{argmax, sample};
use crate::ppo::config::ObsEncoding;
use crate::ppo::obs::ObsEncoder;
use burn::tensor::{Tensor, TensorData};
use chronocooked_env::{Action, TaskConfig};
use chronocooked_models::{ActorCritic, Agent, CoreState, StepRecorder, to_vec};
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use std::path::Path;

/// A PPO actor–critic playing through the [`Agent`] interface.
pub struct PpoAgent {
    name: String,
    policy: ActorCritic,
    encoder: ObsEncoder,
    state: Option<CoreState>,
    obs: Vec<f32>,
    sample: bool,
    rng: Xoshiro256PlusPlus,
    latent: Vec<f32>,
    cell: Option<Vec<f32>>,
    value: f32,
}

impl PpoAgent {
    /// Wraps `policy` (model name `name`) for `config`'s task with its observation encoding.
    pub fn new(
        name: &str,
        policy: ActorCritic,
        config: &TaskConfig,
        encoding: ObsEncoding,
    ) -> Result<Self, TrainError> {
        let encoder = ObsEncoder::for_config(encoding, config)?
            .for_input(policy.input_channels())
            .map_err(|why| TrainError::InvalidParam {
                field: "policy".into(),
                value: name.to_string(),
                allowed: why,
            })?;
        Ok(PpoAgent {
            name: name.to_string(),
            obs: vec![0.0; encoder.len()],
            encoder,
            policy,
            state: None,
            sample: false,
            rng: Xoshiro256PlusPlus::seed_from_u64(0),
            latent: Vec::new(),
            cell: None,
            value: 0.0,
        })
    }

    /// Loads the agent of a run folder (its final model or newest checkpoint) for `config`
    /// (the task to play; defaults to the run's own when `None`).
    pub fn load(dir: &Path, config: Option<&TaskConfig>) -> Result<Self, TrainError> {
        let (policy, pcfg, cfg) = crate::ppo::run_dir::load_policy(dir)?;
        let task = match config {
            Some(c) => c.clone(),
            None => cfg.task.config()?,
        };
        Self::new(&pcfg.arch.name(), policy, &task, cfg.obs)
    }

    /// The policy the run folder `dir` kept as it left multi-timer curriculum level `level`
    /// (`levels/level-<level>.bpk`), acting in `config`.
    pub fn load_level(dir: &Path, level: usize, config: &TaskConfig) -> Result<Self, TrainError> {
        let (policy, pcfg, cfg) = crate::ppo::run_dir::load_level_policy(dir, level)?;
        Self::new(&pcfg.arch.name(), policy, config, cfg.obs)
    }
}

impl Agent for PpoAgent {
    fn name(&self) -> String {
        self.name.clone()
    }

    fn begin_episode(&mut self, _obs: &[u8], seed: u64) {
        self.state = self.policy.zero_state(1, &chronocooked_models::cpu());
        self.encoder.reset_all();
        self.rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    }

    fn act(&mut self, obs: &[u8]) -> Action {
        let device = chronocooked_models::cpu();
        self.encoder.encode(obs, &mut self.obs);
        let (cells, ch) = (self.encoder.cells(), self.encoder.input_channels());
        let x: Tensor<3> =
            Tensor::from_data(TensorData::new(self.obs.clone(), [1, cells, ch]), &device);
        let out = self.policy.forward_step(x, self.state.take(), None);
        let logits = to_vec(&out.logits);
        self.value = to_vec(&out.values).first().copied().unwrap_or(0.0);
        self.latent = to_vec(&out.latent);
        self.cell = out.state.as_ref().and_then(|s| s.c.as_ref()).map(to_vec);
        self.state = out.state;
        let a = if self.sample {
            sample(&logits, &mut self.rng).0
        } else {
            argmax(&logits)
        };
        Action::ALL[a]
    }

    fn record(&self, rec: &mut StepRecorder) {
        rec.record("latent", &self.latent);
        if let Some(c) = &self.cell {
            rec.record("cell", c);
        }
        rec.scalar("value", self.value);
    }

    fn set_training(&mut self, on: bool) {
        self.sample = on;
    }

    fn set_sampling(&mut self, on: bool) {
        self.sample = on;
    }
}
