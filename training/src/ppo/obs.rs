//! Observation encoding for the trunk: codes `[R, C, 6]` (u8) → `[cells, channels]` (f32).

use crate::ppo::config::ObsEncoding;
use chronocooked_env::{CODE_CHANNELS, OneHotEncoder, TaskConfig, VecEnv};

/// Turns codes observations into the trunk's float input `[cells, channels]`.
#[derive(Debug, Clone)]
pub struct ObsEncoder {
    encoding: ObsEncoding,
    cells: usize,
    onehot: OneHotEncoder,
    scratch: Vec<f32>,
}

impl ObsEncoder {
    /// Encoder for the envs' task.
    pub fn new(encoding: ObsEncoding, envs: &VecEnv) -> Self {
        let onehot = envs.onehot_encoder().clone();
        let [_, r, c] = onehot.shape();
        ObsEncoder {
            encoding,
            cells: r * c,
            scratch: vec![0.0; onehot.len()],
            onehot,
        }
    }

    /// Encoder for a task configuration.
    pub fn for_config(
        encoding: ObsEncoding,
        config: &TaskConfig,
    ) -> Result<Self, chronocooked_env::EnvError> {
        let envs = VecEnv::new(config, 1, chronocooked_env::Autoreset::Disabled)?;
        Ok(Self::new(encoding, &envs))
    }

    /// Grid cells `R·C`.
    pub fn cells(&self) -> usize {
        self.cells
    }

    /// Channels per cell (6 for codes, the one-hot channel count otherwise).
    pub fn channels(&self) -> usize {
        match self.encoding {
            ObsEncoding::Codes => CODE_CHANNELS,
            ObsEncoding::Onehot => self.onehot.shape()[0],
        }
    }

    /// Floats per observation (`cells · channels`).
    pub fn len(&self) -> usize {
        self.cells * self.channels()
    }

    /// Whether an observation encodes to nothing (never for a valid layout).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Encodes one codes observation into `out` (`[cells, channels]`).
    pub fn encode(&mut self, codes: &[u8], out: &mut [f32]) {
        match self.encoding {
            ObsEncoding::Codes => out.iter_mut().zip(codes).for_each(|(o, &c)| *o = c as f32),
            ObsEncoding::Onehot => {
                // The env's one-hot layout is channel-major `[C, R, W]`; transpose to cell-major.
                self.onehot.encode(codes, &mut self.scratch);
                let ch = self.onehot.shape()[0];
                for cell in 0..self.cells {
                    for k in 0..ch {
                        out[cell * ch + k] = self.scratch[k * self.cells + cell];
                    }
                }
            }
        }
    }

    /// Encodes all `N` observations of a vec-env codes buffer into `out` (`[N, cells, channels]`).
    pub fn encode_batch(&mut self, codes: &[u8], out: &mut [f32]) {
        let per_in = self.cells * CODE_CHANNELS;
        let per_out = self.len();
        for (i, chunk) in codes.chunks_exact(per_in).enumerate() {
            self.encode(chunk, &mut out[i * per_out..(i + 1) * per_out]);
        }
    }
}
