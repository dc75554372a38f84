//! Observation encoding for the trunk: codes `[R, C, 6]` (u8) → `[cells, channels]` (f32),
//! optionally with the last `k` observations side by side (`[cells, k · channels]`, see
//! [`crate::ppo::frames`]).

use crate::ppo::config::ObsEncoding;
use crate::ppo::frames::FrameStack;
use chronocooked_env::{CODE_CHANNELS, OneHotEncoder, TaskConfig, VecEnv};

/// Turns codes observations into the trunk's float input `[cells, frames · channels]`.
#[derive(Debug, Clone)]
pub struct ObsEncoder {
    encoding: ObsEncoding,
    cells: usize,
    onehot: OneHotEncoder,
    scratch: Vec<f32>,
    /// The last observations of each env when more than one frame is stacked.
    stack: Option<FrameStack>,
    /// One encoded frame `[cells, channels]` (stacking only).
    frame: Vec<f32>,
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
            stack: None,
            frame: Vec::new(),
        }
    }

    /// This encoder with the last `frames` observations of each env stacked along the
    /// channel axis (1: none). Histories start empty (zeros) and grow to the envs
    /// encoded.
    pub fn stacked(mut self, frames: usize) -> Self {
        let frame = self.cells * self.channels();
        self.stack = (frames > 1).then(|| FrameStack::new(frames, self.cells, self.channels()));
        self.frame = vec![0.0; if frames > 1 { frame } else { 0 }];
        self
    }

    /// This encoder stacked to feed a trunk with `input_channels` channels per cell: an
    /// error when that is not a whole number of observations.
    pub fn for_input(self, input_channels: usize) -> Result<Self, String> {
        let ch = self.channels();
        if input_channels == 0 || !input_channels.is_multiple_of(ch) {
            return Err(format!(
                "the policy reads {input_channels} channels per cell, not a multiple of the \
                 observation's {ch}"
            ));
        }
        Ok(self.stacked(input_channels / ch))
    }

    /// Observations stacked per input (1: the current one only).
    pub fn frames(&self) -> usize {
        self.stack.as_ref().map_or(1, FrameStack::frames)
    }

    /// Every env's stacked history, `[N, frames, cells, channels]` (empty without
    /// stacking): what a checkpoint keeps to continue exactly.
    pub fn history(&self) -> Vec<f32> {
        self.stack
            .as_ref()
            .map_or_else(Vec::new, |s| s.history().to_vec())
    }

    /// Restores histories saved by [`ObsEncoder::history`] (ignored without stacking).
    pub fn set_history(&mut self, history: &[f32]) {
        if let Some(s) = &mut self.stack {
            s.set_history(history);
        }
    }

    /// Forgets env `e`'s past observations (its episode ended): the next input it encodes
    /// has zeros in place of the frames before it.
    pub fn reset_env(&mut self, e: usize) {
        if let Some(s) = &mut self.stack {
            s.reset(e);
        }
    }

    /// Forgets every env's past observations.
    pub fn reset_all(&mut self) {
        if let Some(s) = &mut self.stack {
            s.reset_all();
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

    /// Channels per cell of one observation (6 for codes, the one-hot channel count
    /// otherwise).
    pub fn channels(&self) -> usize {
        match self.encoding {
            ObsEncoding::Codes => CODE_CHANNELS,
            ObsEncoding::Onehot => self.onehot.shape()[0],
        }
    }

    /// Channels per cell of the trunk's input (`frames · channels`).
    pub fn input_channels(&self) -> usize {
        self.frames() * self.channels()
    }

    /// Floats per input (`cells · frames · channels`).
    pub fn len(&self) -> usize {
        self.cells * self.input_channels()
    }

    /// Whether an observation encodes to nothing (never for a valid layout).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Encodes env 0's next codes observation into `out` (`[cells, frames · channels]`),
    /// appending it to env 0's history when frames are stacked (one env: an agent).
    pub fn encode(&mut self, codes: &[u8], out: &mut [f32]) {
        self.encode_env(0, codes, out);
    }

    /// Encodes env `e`'s next observation into `out`, appending it to its history.
    fn encode_env(&mut self, e: usize, codes: &[u8], out: &mut [f32]) {
        self.encode_stacked(codes, out, |stack, frame, out| stack.push(e, frame, out));
    }

    /// Encodes `codes` as the observation after env `e`'s last one without appending it
    /// (a truncated episode's final observation, valued for the bootstrap).
    pub fn encode_final(&mut self, e: usize, codes: &[u8], out: &mut [f32]) {
        self.encode_stacked(codes, out, |stack, frame, out| stack.peek(e, frame, out));
    }

    /// Encodes `codes` alone into `out` without stacking; with stacking, into the frame
    /// buffer, then `write` puts the stacked input into `out`.
    fn encode_stacked(
        &mut self,
        codes: &[u8],
        out: &mut [f32],
        write: impl FnOnce(&mut FrameStack, &[f32], &mut [f32]),
    ) {
        let Some(mut stack) = self.stack.take() else {
            return self.encode_frame(codes, out);
        };
        let mut frame = std::mem::take(&mut self.frame);
        self.encode_frame(codes, &mut frame);
        write(&mut stack, &frame, out);
        self.frame = frame;
        self.stack = Some(stack);
    }

    /// Encodes one codes observation alone into `out` (`[cells, channels]`).
    fn encode_frame(&mut self, codes: &[u8], out: &mut [f32]) {
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

    /// Encodes all `N` observations of a vec-env codes buffer into `out`
    /// (`[N, cells, frames · channels]`), appending each to its env's history.
    pub fn encode_batch(&mut self, codes: &[u8], out: &mut [f32]) {
        let per_in = self.cells * CODE_CHANNELS;
        let per_out = self.len();
        for (i, chunk) in codes.chunks_exact(per_in).enumerate() {
            self.encode_env(i, chunk, &mut out[i * per_out..(i + 1) * per_out]);
        }
    }
}
