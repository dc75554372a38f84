//! Observation encodings and spaces.
//!
//! * **codes** — the reference layout: `u8`, `[R, C, 6]`, channel-last.
//!   ch0 object code, ch1 agent, ch2 carrying onion, ch3 carrying soup,
//!   ch4 oven state (0 off, 1 on, 2 ready; multi-timer: the cue), ch5 always 0
//!   (unless the debug timer channel is switched on).
//! * **one-hot** — `f32`, `[C_onehot, R, C]`, channel-first, for networks:
//!   channels 0–6 object kinds (see [`ObjectKind::ALL`]), 7 agent, 8 carrying onion,
//!   9 carrying soup, 10 oven off, 11 oven on, 12 oven ready, then the cue channels
//!   (multi-timer value cue: one channel holding the TD value at the oven while on;
//!   categorical cue: one channel per trained TD), then the debug timer channel if enabled.
//!   The multi-anchor and multi-oven tasks use one fixed set of [`EXTENDED_CHANNELS`]
//!   channels at every curriculum level: 0–10 object kinds (see [`ObjectKind::EVERY`]),
//!   11 agent, 12 carrying onion, 13 carrying soup, 14 oven off, 15 oven on, 16 oven ready
//!   (at each oven's cell), 17–19 the held soup came from oven 1, 2, 3 (at the agent's
//!   cell), then the debug timer channel if enabled. The reproduction task adds one channel
//!   per cued context (prior × gain) after the base channels, set at the counter.
//!
//! Both are views of the same state; the one-hot view is computed from the codes
//! view plus the layout, so neither can leak the hidden timer.

use crate::kitchen::{CODE_CHANNELS, Spec};
use crate::layout::ObjectKind;
use crate::task::{CueMode, TaskFamily};
use rand::Rng;
use serde::Serialize;

/// Base one-hot channels before the cue channels.
pub const ONEHOT_BASE_CHANNELS: usize = 13;
/// One-hot channels of the multi-anchor and multi-oven tasks (before the debug channel).
pub const EXTENDED_CHANNELS: usize = 20;

/// A discrete space `{0, …, n−1}`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Discrete {
    /// Number of values.
    pub n: usize,
}

impl Discrete {
    /// Whether `x` is in the space.
    pub fn contains(&self, x: i64) -> bool {
        x >= 0 && (x as usize) < self.n
    }

    /// A uniform sample.
    pub fn sample<R: Rng>(&self, rng: &mut R) -> usize {
        rng.random_range(0..self.n)
    }
}

/// A box space of `shape` with elementwise bounds `[low, high]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxSpace<T> {
    /// Shape, outermost first.
    pub shape: Vec<usize>,
    /// Lower bound of every element.
    pub low: T,
    /// Upper bound of every element.
    pub high: T,
}

impl<T: PartialOrd + Copy> BoxSpace<T> {
    /// Number of elements.
    pub fn len(&self) -> usize {
        self.shape.iter().product()
    }

    /// Whether the space has no elements.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether `x` has the right length and every element is within bounds.
    pub fn contains(&self, x: &[T]) -> bool {
        x.len() == self.len() && x.iter().all(|v| *v >= self.low && *v <= self.high)
    }
}

impl BoxSpace<u8> {
    /// A uniform sample of every element.
    pub fn sample<R: Rng>(&self, rng: &mut R) -> Vec<u8> {
        (0..self.len())
            .map(|_| rng.random_range(self.low..=self.high))
            .collect()
    }
}

impl BoxSpace<f32> {
    /// A uniform sample of every element.
    pub fn sample<R: Rng>(&self, rng: &mut R) -> Vec<f32> {
        (0..self.len())
            .map(|_| rng.random_range(self.low..=self.high))
            .collect()
    }
}

/// Upper bound of the codes observation for a task.
pub(crate) fn codes_high(spec: &Spec) -> u8 {
    if spec.config.debug_timer_channel {
        return 255;
    }
    if spec.rules.extended_ovens().is_some() {
        // The reference's observation space for these tasks: Box(0, 20).
        return 20;
    }
    match spec.cue {
        Some(CueMode::Value) => 255,
        Some(CueMode::Categorical) => (spec.tds.len() as u8).max(8),
        None => 8,
    }
}

/// Converts a codes observation to the one-hot view of one task.
#[derive(Debug, Clone)]
pub struct OneHotEncoder {
    rows: usize,
    cols: usize,
    channels: usize,
    family: TaskFamily,
    cue: Option<CueMode>,
    tds: Vec<u32>,
    debug_channel: Option<usize>,
    /// Multi-anchor / multi-oven: the oven cells and each one's channel-0 code.
    extended: Option<Vec<(usize, u8)>>,
    /// Ready-Set-Go: the counter cell and the number of cued contexts (one channel each,
    /// after the base channels).
    context: Option<(usize, usize)>,
    /// Static object channels, `[C_onehot, R, C]`.
    template: Vec<f32>,
}

impl OneHotEncoder {
    pub(crate) fn new(spec: &Spec) -> Self {
        let (rows, cols) = (spec.layout.rows(), spec.layout.cols());
        let cue_channels = match spec.cue {
            Some(CueMode::Value) => 1,
            Some(CueMode::Categorical) => spec.tds.len(),
            None => 0,
        };
        let debug = spec.config.debug_timer_channel;
        let extended = spec.rules.extended_ovens().map(|n| {
            spec.ovens[..n]
                .iter()
                .map(|&cell| (cell, spec.background[cell * CODE_CHANNELS]))
                .collect::<Vec<_>>()
        });
        let context = spec
            .rsg
            .as_ref()
            .map(|r| (r.counter, r.cued_contexts()))
            .filter(|&(_, n)| n > 0);
        let context_channels = context.map_or(0, |(_, n)| n);
        let channels = if extended.is_some() {
            EXTENDED_CHANNELS + debug as usize
        } else {
            ONEHOT_BASE_CHANNELS + cue_channels + context_channels + debug as usize
        };
        let plane = rows * cols;
        let mut template = vec![0.0; channels * plane];
        for cell in 0..plane {
            if let Some(kind) = spec.layout.object_at(cell) {
                template[kind.onehot_index() * plane + cell] = 1.0;
            }
        }
        OneHotEncoder {
            rows,
            cols,
            channels,
            family: spec.family,
            cue: spec.cue,
            tds: spec.tds.clone(),
            debug_channel: debug.then_some(channels - 1),
            extended,
            context,
            template,
        }
    }

    /// The channel that marks the agent's cell (7; 11 in the multi-anchor and multi-oven
    /// encoding).
    pub fn agent_channel(&self) -> usize {
        if self.extended.is_some() { 11 } else { 7 }
    }

    /// Shape `[C_onehot, R, C]`.
    pub fn shape(&self) -> [usize; 3] {
        [self.channels, self.rows, self.cols]
    }

    /// Number of floats of one encoded observation.
    pub fn len(&self) -> usize {
        self.template.len()
    }

    /// Whether the encoding is empty (never, for a valid layout).
    pub fn is_empty(&self) -> bool {
        self.template.is_empty()
    }

    /// Encodes one codes observation (`[R, C, 6]`) into `out` (`[C_onehot, R, C]`).
    pub fn encode(&self, codes: &[u8], out: &mut [f32]) {
        if let Some(ovens) = &self.extended {
            return self.encode_extended(ovens, codes, out);
        }
        out.copy_from_slice(&self.template);
        if let Some((cell, n)) = self.context {
            let v = codes[cell * CODE_CHANNELS + 4] as usize;
            if (1..=n).contains(&v) {
                let plane = self.rows * self.cols;
                out[(ONEHOT_BASE_CHANNELS + v - 1) * plane + cell] = 1.0;
            }
        }
        let plane = self.rows * self.cols;
        for cell in 0..plane {
            let px = &codes[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            if px[1] != 0 {
                out[7 * plane + cell] = 1.0;
                out[8 * plane + cell] = px[2] as f32;
                out[9 * plane + cell] = px[3] as f32;
            }
            if px[0] == ObjectKind::Oven.code() {
                let state = px[4];
                let (off, on, ready) = match (self.family, state) {
                    (_, 0) => (1.0, 0.0, 0.0),
                    (TaskFamily::MultiTimer, _) => (0.0, 1.0, 0.0),
                    (_, 2) => (0.0, 0.0, 1.0),
                    _ => (0.0, 1.0, 0.0),
                };
                out[10 * plane + cell] = off;
                out[11 * plane + cell] = on;
                out[12 * plane + cell] = ready;
                if state != 0 {
                    match self.cue {
                        Some(CueMode::Value) => {
                            out[ONEHOT_BASE_CHANNELS * plane + cell] = state as f32
                        }
                        Some(CueMode::Categorical) => {
                            let k = (state as usize).saturating_sub(1).min(self.tds.len() - 1);
                            out[(ONEHOT_BASE_CHANNELS + k) * plane + cell] = 1.0;
                        }
                        None => {}
                    }
                }
                if let Some(ch) = self.debug_channel {
                    out[ch * plane + cell] = px[5] as f32;
                }
            }
        }
    }

    fn encode_extended(&self, ovens: &[(usize, u8)], codes: &[u8], out: &mut [f32]) {
        out.copy_from_slice(&self.template);
        let plane = self.rows * self.cols;
        for cell in 0..plane {
            let px = &codes[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            if px[1] != 0 {
                out[11 * plane + cell] = 1.0;
                out[12 * plane + cell] = px[2] as f32;
                if px[3] != 0 {
                    out[13 * plane + cell] = 1.0;
                    // Multi-oven soup carries its oven's code; multi-anchor soup is 1.
                    let from = ovens
                        .iter()
                        .position(|&(_, code)| code == px[3])
                        .unwrap_or(0);
                    out[(17 + from) * plane + cell] = 1.0;
                }
            }
        }
        for &(cell, _) in ovens {
            let px = &codes[cell * CODE_CHANNELS..(cell + 1) * CODE_CHANNELS];
            let state = (px[4] as usize).min(2);
            out[(14 + state) * plane + cell] = 1.0;
            if let Some(ch) = self.debug_channel {
                out[ch * plane + cell] = px[5] as f32;
            }
        }
    }

    /// Upper bound of any one-hot element.
    pub fn high(&self) -> f32 {
        match self.cue {
            Some(CueMode::Value) => 255.0,
            _ if self.debug_channel.is_some() => 255.0,
            _ => 1.0,
        }
    }
}

/// Converts a flat codes observation into nested `[row][col][channel]` integers (for JSON).
pub fn codes_to_nested(codes: &[u8], rows: usize, cols: usize) -> Vec<Vec<Vec<u8>>> {
    (0..rows)
        .map(|r| {
            (0..cols)
                .map(|c| {
                    let o = (r * cols + c) * CODE_CHANNELS;
                    codes[o..o + CODE_CHANNELS].to_vec()
                })
                .collect()
        })
        .collect()
}
