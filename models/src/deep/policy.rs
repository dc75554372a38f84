//! Actor–critic policies: the CNN trunk, an optional recurrent core shared by actor and
//! critic (as in the paper's recurrent agents), and SB3-style heads `pi=[64]`, `vf=[64]`.

use crate::deep::cores::{CoreConfig, CoreInit, CoreKind, CoreState, RecurrentCore};
use crate::deep::init::{InitRng, linear_orthogonal};
use crate::deep::trunk::{Trunk, TrunkConfig};
use crate::fast_tanh as tanh;
use burn::module::Module;
use burn::nn::Linear;
use burn::tensor::{Device, Tensor};
use rand::SeedableRng;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Hidden sizes the paper uses for recurrent cores.
pub const PAPER_SIZES: [usize; 3] = [8, 125, 256];

/// A deep-RL architecture by name: `cnn-mlp`, or a core kind with a hidden size
/// (`lstm125`, `ctrnn8`, `gru256`, `rnn125`; a bare kind means 125 units), optionally as a
/// fixed random reservoir (`ctrnn-reservoir125`), and optionally fed the last `k`
/// observations stacked along the channel axis (`cnn-mlp-stack4`: SB3's `VecFrameStack`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Architecture {
    /// Recurrent core, `None` for the feed-forward CNN-MLP.
    pub core: Option<CoreKind>,
    /// Hidden units of the core (0 for CNN-MLP).
    pub hidden: usize,
    /// The core's weights (input projection, recurrent weights, CTRNN τ) keep their random
    /// initial values: training updates only the trunk and the heads. This is what the
    /// paper's code does to its CTRNN (the cell is swapped into the policy after the
    /// optimiser was built, so the optimiser never sees it).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub reservoir: bool,
    /// Observations stacked along the channel axis (1: the current one only). With `k`
    /// frames the trunk sees the observations of steps `t−k+1 … t` (zeros before the
    /// episode's first), as Stable-Baselines3's `VecFrameStack(n_stack=k)` gives: a
    /// memoryless policy with a `k`-step window, the benchmark's control for memory.
    #[serde(default = "one_frame", skip_serializing_if = "is_one_frame")]
    pub frames: usize,
}

/// Largest frame stack an architecture may ask for (steps).
pub const MAX_FRAMES: usize = 64;

fn one_frame() -> usize {
    1
}

fn is_one_frame(k: &usize) -> bool {
    *k == 1
}

impl Architecture {
    /// The feed-forward CNN-MLP.
    pub const CNN_MLP: Architecture = Architecture {
        core: None,
        hidden: 0,
        reservoir: false,
        frames: 1,
    };

    /// A recurrent architecture with a trained core.
    pub fn recurrent(kind: CoreKind, hidden: usize) -> Self {
        Architecture {
            core: Some(kind),
            hidden,
            reservoir: false,
            frames: 1,
        }
    }

    /// This architecture fed the last `frames` observations stacked along the channel axis
    /// (see [`Architecture::frames`]).
    pub fn stacked(self, frames: usize) -> Self {
        Architecture { frames, ..self }
    }

    /// A recurrent architecture whose core stays at its random initialisation.
    pub fn reservoir(kind: CoreKind, hidden: usize) -> Self {
        Architecture {
            reservoir: true,
            ..Architecture::recurrent(kind, hidden)
        }
    }

    /// Every architecture of the zoo: CNN-MLP, each core × {8, 125, 256}, and the
    /// paper's untrained CTRNN (`ctrnn-reservoir`) × {8, 125, 256}.
    pub fn all() -> Vec<Architecture> {
        let mut v = vec![Architecture::CNN_MLP];
        for k in CoreKind::ALL {
            for h in PAPER_SIZES {
                v.push(Architecture::recurrent(k, h));
            }
        }
        for h in PAPER_SIZES {
            v.push(Architecture::reservoir(CoreKind::Ctrnn, h));
        }
        v
    }

    /// Canonical name (`cnn-mlp`, `lstm125`, `ctrnn-reservoir125`, `cnn-mlp-stack4`, …).
    pub fn name(&self) -> String {
        let base = match (self.core, self.reservoir) {
            (None, _) => "cnn-mlp".to_string(),
            (Some(k), false) => format!("{}{}", k.name(), self.hidden),
            (Some(k), true) => format!("{}-reservoir{}", k.name(), self.hidden),
        };
        if self.frames == 1 {
            base
        } else {
            format!("{base}-stack{}", self.frames)
        }
    }

    /// Whether the policy carries a recurrent state.
    pub fn is_recurrent(&self) -> bool {
        self.core.is_some()
    }
}

impl fmt::Display for Architecture {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

impl FromStr for Architecture {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        if let Some((base, k)) = lower.rsplit_once("-stack") {
            let frames = k
                .parse::<usize>()
                .ok()
                .filter(|k| (1..=MAX_FRAMES).contains(k))
                .ok_or_else(|| {
                    format!("bad frame stack in `{s}` (allowed: -stack1 … -stack{MAX_FRAMES})")
                })?;
            return Ok(base.parse::<Architecture>()?.stacked(frames));
        }
        if matches!(lower.as_str(), "cnn-mlp" | "cnn_mlp" | "cnn" | "mlp") {
            return Ok(Architecture::CNN_MLP);
        }
        let digits =
            lower.trim_start_matches(|c: char| c.is_ascii_alphabetic() || c == '-' || c == '_');
        let kind_part = lower[..lower.len() - digits.len()].trim_end_matches(['-', '_']);
        let kind_part = kind_part.strip_prefix("cnn-").unwrap_or(kind_part);
        let (kind_part, reservoir) = match kind_part.strip_suffix("-reservoir") {
            Some(k) => (k, true),
            None => (kind_part, false),
        };
        let allowed = "cnn-mlp, or lstm|gru|rnn|ctrnn (optionally with -reservoir: an untrained \
             core) followed by a hidden size (e.g. lstm125, ctrnn8, ctrnn-reservoir125); \
             any of them may end in -stack<k> (k stacked frames, e.g. cnn-mlp-stack4)";
        let kind: CoreKind = kind_part
            .parse()
            .map_err(|_| format!("unknown model `{s}` (allowed: {allowed})"))?;
        let hidden = if digits.is_empty() {
            125
        } else {
            digits
                .parse::<usize>()
                .ok()
                .filter(|h| (1..=4096).contains(h))
                .ok_or_else(|| format!("bad hidden size in `{s}` (allowed: 1..=4096)"))?
        };
        Ok(Architecture {
            reservoir,
            ..Architecture::recurrent(kind, hidden)
        })
    }
}

/// Everything needed to build an [`ActorCritic`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PolicyConfig {
    /// Architecture (CNN-MLP or a recurrent core).
    pub arch: Architecture,
    /// Trunk shape (grid cells and input channels).
    pub trunk: TrunkConfig,
    /// Width of the policy and value hidden layers (reference 64).
    pub head_hidden: usize,
    /// Number of discrete actions.
    pub actions: usize,
    /// CTRNN `dt` (reference 0.1).
    pub ctrnn_dt: f32,
    /// CTRNN initial raw τ (reference 1.0).
    pub ctrnn_tau_init: f32,
    /// Initial weight distribution of the recurrent core.
    #[serde(default)]
    pub core_init: CoreInit,
}

/// Largest size of any one dimension of a policy (hidden units, trunk widths, grid cells):
/// the zoo's largest core has 4096 units.
pub const MAX_POLICY_DIM: usize = 4096;

/// A [`PolicyConfig`] (read from `policy.json`) outside what a policy can be.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("field `{field}`: {value} (allowed: {allowed})")]
pub struct PolicyConfigError {
    /// The field (`arch.hidden`, `trunk.cells`, …).
    pub field: String,
    /// The value found.
    pub value: String,
    /// What it may be.
    pub allowed: String,
}

impl PolicyConfig {
    /// Checks every size and constant before anything is allocated: sizes in
    /// `1..=`[`MAX_POLICY_DIM`] (a CNN-MLP has `arch.hidden = 0`), actions in `1..=64`,
    /// CTRNN `dt` in (0, 1] and `τ_init` finite and > 0.
    pub fn validate(&self) -> Result<(), PolicyConfigError> {
        let err = |field: &str, value: String, allowed: &str| PolicyConfigError {
            field: field.into(),
            value,
            allowed: allowed.into(),
        };
        let dim = format!("1..={MAX_POLICY_DIM}");
        let t = &self.trunk;
        for (field, v) in [
            ("trunk.cells", t.cells),
            ("trunk.channels", t.channels),
            ("trunk.conv1", t.conv1),
            ("trunk.conv2", t.conv2),
            ("trunk.features", t.features),
            ("head_hidden", self.head_hidden),
        ] {
            if !(1..=MAX_POLICY_DIM).contains(&v) {
                return Err(err(field, v.to_string(), &dim));
            }
        }
        if !(1..=MAX_FRAMES).contains(&self.arch.frames) {
            return Err(err(
                "arch.frames",
                self.arch.frames.to_string(),
                &format!("1..={MAX_FRAMES}"),
            ));
        }
        if !t.channels.is_multiple_of(self.arch.frames) {
            return Err(err(
                "trunk.channels",
                t.channels.to_string(),
                &format!(
                    "a multiple of arch.frames = {} (the frames' channels side by side)",
                    self.arch.frames
                ),
            ));
        }
        match self.arch.core {
            None if self.arch.hidden != 0 => {
                return Err(err(
                    "arch.hidden",
                    self.arch.hidden.to_string(),
                    "0 for the CNN-MLP",
                ));
            }
            Some(_) if !(1..=MAX_POLICY_DIM).contains(&self.arch.hidden) => {
                return Err(err("arch.hidden", self.arch.hidden.to_string(), &dim));
            }
            _ => {}
        }
        if self.arch.reservoir && self.arch.core.is_none() {
            return Err(err(
                "arch.reservoir",
                "true".into(),
                "false for the CNN-MLP",
            ));
        }
        if !(1..=64).contains(&self.actions) {
            return Err(err("actions", self.actions.to_string(), "1..=64"));
        }
        if !(self.ctrnn_dt > 0.0 && self.ctrnn_dt <= 1.0) {
            return Err(err(
                "ctrnn_dt",
                self.ctrnn_dt.to_string(),
                "a number in (0, 1]",
            ));
        }
        if !(self.ctrnn_tau_init.is_finite() && self.ctrnn_tau_init > 0.0) {
            return Err(err(
                "ctrnn_tau_init",
                self.ctrnn_tau_init.to_string(),
                "a finite number > 0",
            ));
        }
        Ok(())
    }

    /// Reference configuration for `arch` on a grid of `cells` cells with `channels` inputs
    /// per observation (the trunk reads `channels · arch.frames` channels per cell).
    pub fn new(arch: Architecture, cells: usize, channels: usize, actions: usize) -> Self {
        PolicyConfig {
            arch,
            trunk: TrunkConfig::reference(cells, channels * arch.frames),
            head_hidden: 64,
            actions,
            ctrnn_dt: 0.1,
            ctrnn_tau_init: 1.0,
            core_init: CoreInit::Lab,
        }
    }

    /// Builds the policy with weights drawn from `seed` (SB3 initialisation: orthogonal,
    /// gain √2 in trunk and heads, 0.01 for the action layer, 1 for the value layer).
    pub fn init(&self, seed: u64, device: &Device) -> ActorCritic {
        let mut rng = InitRng::seed_from_u64(seed);
        let trunk = self.trunk.init(&mut rng, device);
        let feat = self.trunk.features;
        let core = self.arch.core.map(|kind| {
            let mut c = CoreConfig::new(kind, feat, self.arch.hidden);
            c.dt = self.ctrnn_dt;
            c.tau_init = self.ctrnn_tau_init;
            c.init = self.core_init;
            c.init(&mut rng, device)
        });
        let latent = if self.arch.is_recurrent() {
            self.arch.hidden
        } else {
            feat
        };
        let g = std::f64::consts::SQRT_2;
        let hh = self.head_hidden;
        ActorCritic {
            trunk,
            core,
            hidden: {
                // Policy and value hidden layers side by side: W = [W_pi | W_vf], each
                // orthogonal with gain √2 (one matmul and one tanh for both heads).
                let pi = crate::deep::init::orthogonal(latent, hh, g, &mut rng);
                let vf = crate::deep::init::orthogonal(latent, hh, g, &mut rng);
                let mut w = Vec::with_capacity(latent * 2 * hh);
                for r in 0..latent {
                    w.extend_from_slice(&pi[r * hh..(r + 1) * hh]);
                    w.extend_from_slice(&vf[r * hh..(r + 1) * hh]);
                }
                Linear {
                    weight: crate::deep::init::param(w, [latent, 2 * hh], device),
                    bias: Some(crate::deep::init::param(
                        vec![0.0; 2 * hh],
                        [2 * hh],
                        device,
                    )),
                }
            },
            pi_out: linear_orthogonal(hh, self.actions, 0.01, &mut rng, device),
            vf_out: linear_orthogonal(hh, 1, 1.0, &mut rng, device),
        }
    }
}

/// Output of a policy forward pass.
#[derive(Debug, Clone)]
pub struct PolicyOutput {
    /// Action logits `[N, A]` (N = B for a step, T·B time-major for a sequence).
    pub logits: Tensor<2>,
    /// State values `[N, 1]`.
    pub values: Tensor<2>,
    /// Recurrent latent fed to the heads `[N, H]` (the recorded "neural activity").
    pub latent: Tensor<2>,
    /// State after the last step (`None` for CNN-MLP).
    pub state: Option<CoreState>,
    /// Training forwards ([`ActorCritic::forward_seq_train`]): what the recurrent weight
    /// gradient needs after `backward`.
    pub aux: Option<crate::deep::cores::SeqAux>,
}

/// Actor–critic network (burn module).
#[derive(Module, Debug)]
pub struct ActorCritic {
    /// CNN trunk, shared by actor and critic.
    pub trunk: Trunk,
    /// Recurrent core, shared by actor and critic (`None`: CNN-MLP).
    pub core: Option<RecurrentCore>,
    /// Policy and value hidden layers, fused: `latent → [pi 64 | vf 64]`, tanh.
    pub hidden: Linear,
    /// Action logits layer.
    pub pi_out: Linear,
    /// Value output layer.
    pub vf_out: Linear,
}

impl ActorCritic {
    /// Input channels per grid cell the trunk reads (an observation's channels times the
    /// stacked frames).
    pub fn input_channels(&self) -> usize {
        self.trunk.conv1.weight.dims()[0]
    }

    /// Zero recurrent state for `batch` envs (`None` for CNN-MLP).
    pub fn zero_state(&self, batch: usize, device: &Device) -> Option<CoreState> {
        self.core.as_ref().map(|c| c.zero_state(batch, device))
    }

    /// Heads on `latent`; with `detach_critic` the critic reads a detached copy of it (the
    /// value loss then trains the value head only).
    fn heads_with(
        &self,
        latent: Tensor<2>,
        state: Option<CoreState>,
        detach_critic: bool,
    ) -> PolicyOutput {
        let hh = self.pi_out.weight.dims()[0];
        let z = tanh(self.hidden.forward(latent.clone()));
        let z_vf = if detach_critic {
            tanh(self.hidden.forward(latent.clone().detach()))
        } else {
            z.clone()
        };
        let logits = self.pi_out.forward(z.narrow(1, 0, hh));
        let values = self.vf_out.forward(z_vf.narrow(1, hh, hh));
        PolicyOutput {
            logits,
            values,
            latent,
            state,
            aux: None,
        }
    }

    fn heads(&self, latent: Tensor<2>, state: Option<CoreState>) -> PolicyOutput {
        self.heads_with(latent, state, false)
    }

    /// One step for `B` envs: `obs [B, cells, C]`, state, `keep [B, 1]` (0 where an episode
    /// starts; `None` when none does).
    pub fn forward_step(
        &self,
        obs: Tensor<3>,
        state: Option<CoreState>,
        keep: Option<&Tensor<2>>,
    ) -> PolicyOutput {
        let feat = self.trunk.forward(obs);
        match (&self.core, state) {
            (Some(core), Some(st)) => {
                let (h, st) = core.step(feat, st, keep);
                self.heads(h, Some(st))
            }
            (Some(core), None) => {
                let st = core.zero_state(feat.dims()[0], &feat.device());
                let (h, st) = core.step(feat, st, keep);
                self.heads(h, Some(st))
            }
            (None, _) => self.heads(feat, None),
        }
    }

    /// Trunk features of a sequence, flattened time-major: `([T·B, F], T, B)`.
    fn seq_features(&self, obs: Tensor<4>) -> (Tensor<2>, usize, usize) {
        let [t, b, cells, ch] = obs.dims();
        (self.trunk.forward(obs.reshape([t * b, cells, ch])), t, b)
    }

    /// Sequence forward for BPTT: `obs [T, B, cells, C]`, initial state, per-step
    /// `keep [B, 1]` (`None` where no sequence starts an episode).
    /// Outputs are time-major `[T·B, ·]` (row `t·B + b`).
    pub fn forward_seq(
        &self,
        obs: Tensor<4>,
        state: Option<CoreState>,
        keep: &[Option<Tensor<2>>],
    ) -> PolicyOutput {
        let (feat, t, b) = self.seq_features(obs);
        match &self.core {
            Some(core) => {
                let st = state.unwrap_or_else(|| core.zero_state(b, &feat.device()));
                let f = feat.dims()[1];
                let (h, st) = core.forward_seq(feat.reshape([t, b, f]), st, keep);
                self.heads(h.reshape([t * b, core.hidden]), Some(st))
            }
            None => self.heads(feat, None),
        }
    }

    /// [`ActorCritic::forward_seq`] for training: identical outputs, but the recurrent
    /// weight gradient is formed after `backward` from `out.aux` (see
    /// [`RecurrentCore::forward_seq_train`]). With `detach_critic` the critic reads a
    /// detached copy of the core output (sb3-contrib's `shared_lstm=True,
    /// enable_critic_lstm=False`), so the value loss does not train the core or the trunk.
    pub fn forward_seq_train(
        &self,
        obs: Tensor<4>,
        state: Option<CoreState>,
        keep: &[Option<Tensor<2>>],
        detach_critic: bool,
    ) -> PolicyOutput {
        let (feat, t, b) = self.seq_features(obs);
        match &self.core {
            Some(core) => {
                let st = state.unwrap_or_else(|| core.zero_state(b, &feat.device()));
                let f = feat.dims()[1];
                let xw = core.input.forward(feat.reshape([t, b, f]));
                let (h, st, aux) = core.forward_seq_train(xw, st, keep);
                let latent = h.reshape([t * b, core.hidden]);
                let mut out = self.heads_with(latent, Some(st), detach_critic);
                out.aux = Some(aux);
                out
            }
            None => self.heads(feat, None),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_stack_is_named_parsed_and_widens_only_the_trunk_input() {
        let a: Architecture = "cnn-mlp-stack4".parse().unwrap();
        assert_eq!((a.core, a.frames), (None, 4));
        assert_eq!(a.name(), "cnn-mlp-stack4");
        let l: Architecture = "lstm125-stack2".parse().unwrap();
        assert_eq!(
            (l.hidden, l.frames, l.name().as_str()),
            (125, 2, "lstm125-stack2")
        );
        assert_eq!(
            "cnn-mlp-stack1".parse::<Architecture>().unwrap(),
            Architecture::CNN_MLP
        );
        for bad in ["cnn-mlp-stack0", "cnn-mlp-stack65", "cnn-mlp-stackx"] {
            let e = bad.parse::<Architecture>().unwrap_err();
            assert!(e.contains("-stack64"), "{bad}: {e}");
        }
        let cfg = PolicyConfig::new(a, 15, 6, 6);
        assert_eq!(cfg.trunk.channels, 24);
        assert_eq!(
            PolicyConfig::new(Architecture::CNN_MLP, 15, 6, 6)
                .trunk
                .channels,
            6
        );
        assert!(cfg.validate().is_ok());
        let mut odd = cfg;
        odd.trunk.channels = 23;
        assert_eq!(odd.validate().unwrap_err().field, "trunk.channels");
        // One frame is not written, so the policy files of unstacked models do not change.
        let json = serde_json::to_string(&Architecture::CNN_MLP).unwrap();
        assert!(!json.contains("frames"), "{json}");
        let back: Architecture = serde_json::from_str(&json).unwrap();
        assert_eq!(back.frames, 1);
    }
}
