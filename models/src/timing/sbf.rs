//! Striatal beat-frequency timer (Matell & Meck 2004).
//!
//! `N` cortical oscillators `xᵢ(t) = cos(2π k fᵢ t)` (frequencies in `[f_min, f_max]` Hz,
//! random or evenly spaced; `k` the clock-speed factor) are phase-reset at the timed event.
//! A striatal coincidence detector stores the oscillator pattern at reinforcement,
//! `w ← w + η (x(T̃) − w)`, where the stored time is `T̃ = k_mem · T · (1 + κ ε)`, `ε ~ N(0,1)`
//! (trial-to-trial memory noise: the source of the scalar property, peak-time CV ≈ κ;
//! `k_mem` the memory manipulation). The output `S(t) = Σ wᵢ xᵢ(t)` peaks at the stored time.
//!
//! For uniformly spread frequencies `Σ cos(2π fᵢ τ) ≈ N·sinc(Δf τ)·cos(2π f̄ τ)`, so the
//! output's envelope has a full width at half maximum of `≈ 1.207/Δf` around `T`.
//! Evenly spaced frequencies (spacing `δf`) alias: spurious peaks at `T + j/δf`.
//!
//! Time here is in seconds; `seconds_per_step` converts env steps.

use rand::Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// How oscillator frequencies are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FrequencyLayout {
    /// Evenly spaced from `f_min` to `f_max` (aliases at `T + j/δf`).
    Even,
    /// Uniform random draws in `[f_min, f_max]` (seeded).
    Random,
}

/// The oscillators, the coincidence-detector weights and the manipulations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BeatFrequency {
    /// Oscillator frequencies (Hz).
    pub freqs: Vec<f64>,
    /// Clock-speed factor `k` applied to every frequency (1 = normal).
    pub clock_speed: f64,
    /// Memory-storage factor `k_mem` (1 = normal; 1.2 stores 20% longer times).
    pub memory_scale: f64,
    /// Memory noise `κ`: SD of the relative error of the stored time.
    pub memory_noise: f64,
    /// Learning rate `η` of the weights.
    pub learning_rate: f64,
}

impl BeatFrequency {
    /// `n` oscillators in `[f_min, f_max]` Hz, laid out as `layout` (random draws from `rng`).
    pub fn new<R: Rng + ?Sized>(
        n: usize,
        f_min: f64,
        f_max: f64,
        layout: FrequencyLayout,
        rng: &mut R,
    ) -> Self {
        let freqs = match layout {
            FrequencyLayout::Even if n > 1 => (0..n)
                .map(|i| f_min + (f_max - f_min) * i as f64 / (n - 1) as f64)
                .collect(),
            FrequencyLayout::Even => vec![0.5 * (f_min + f_max)],
            FrequencyLayout::Random => (0..n).map(|_| rng.random_range(f_min..=f_max)).collect(),
        };
        BeatFrequency {
            freqs,
            clock_speed: 1.0,
            memory_scale: 1.0,
            memory_noise: 0.0,
            learning_rate: 1.0,
        }
    }

    /// Number of oscillators.
    pub fn len(&self) -> usize {
        self.freqs.len()
    }

    /// Whether there are no oscillators.
    pub fn is_empty(&self) -> bool {
        self.freqs.is_empty()
    }

    /// Oscillator activities `xᵢ(t) = cos(2π k fᵢ t)` at `t` seconds after the reset.
    pub fn oscillators_into(&self, t: f64, out: &mut Vec<f64>) {
        out.clear();
        let w = 2.0 * std::f64::consts::PI * self.clock_speed * t;
        out.extend(self.freqs.iter().map(|f| (w * f).cos()));
    }

    /// Oscillator pattern at `t` seconds *as learned* (normal clock speed).
    fn pattern_at(&self, t: f64) -> impl Iterator<Item = f64> + '_ {
        let w = 2.0 * std::f64::consts::PI * t;
        self.freqs.iter().map(move |f| (w * f).cos())
    }

    /// Stores the pattern of reinforced time `t` (s) into `weights` (resized as needed):
    /// `w ← w + η (x(k_mem · t · (1 + κ ε)) − w)`. Returns the stored time.
    pub fn reinforce<R: Rng + ?Sized>(&self, weights: &mut Vec<f64>, t: f64, rng: &mut R) -> f64 {
        let stored = self.stored_time(t, rng);
        weights.resize(self.freqs.len(), 0.0);
        let eta = self.learning_rate;
        for (w, x) in weights.iter_mut().zip(self.pattern_at(stored)) {
            *w += eta * (x - *w);
        }
        stored
    }

    /// Striatal output `S(t) = Σ wᵢ xᵢ(t)`.
    pub fn output(&self, weights: &[f64], oscillators: &[f64]) -> f64 {
        weights.iter().zip(oscillators).map(|(w, x)| w * x).sum()
    }

    /// Stored time of a reinforcement at `t` (s): `k_mem · t · (1 + κ ε)`, `ε ~ N(0, 1)`.
    pub fn stored_time<R: Rng + ?Sized>(&self, t: f64, rng: &mut R) -> f64 {
        let eps: f64 = if self.memory_noise > 0.0 {
            rng.sample(StandardNormal)
        } else {
            0.0
        };
        (self.memory_scale * t * (1.0 + self.memory_noise * eps)).max(0.0)
    }

    /// Envelope of the detector output for a pattern stored at `stored` s, read at `t` s:
    /// `|Σᵢ exp(i·2π (k fᵢ t − fᵢ T))| / N` — the output of a quadrature pair of detectors
    /// (cosine and sine weights), i.e. the beat envelope without its ~f̄ carrier; 1 at
    /// `t = T/k`, `≈ |sinc(Δf (t − T))|` for uniform frequencies at `k = 1`.
    pub fn envelope(&self, t: f64, stored: f64) -> f64 {
        if self.freqs.is_empty() {
            return 0.0;
        }
        let two_pi = 2.0 * std::f64::consts::PI;
        let (mut re, mut im) = (0.0, 0.0);
        for f in &self.freqs {
            let phase = two_pi * f * (self.clock_speed * t - stored);
            re += phase.cos();
            im += phase.sin();
        }
        (re * re + im * im).sqrt() / self.freqs.len() as f64
    }

    /// Normalised output (cosine similarity of `w` and `x(t)`, in `[−1, 1]`; 0 without a
    /// memory): the readout compared with a response threshold.
    pub fn similarity(&self, weights: &[f64], oscillators: &[f64]) -> f64 {
        let ww: f64 = weights.iter().map(|w| w * w).sum();
        let xx: f64 = oscillators.iter().map(|x| x * x).sum();
        if ww <= 1e-12 || xx <= 1e-12 {
            return 0.0;
        }
        self.output(weights, oscillators) / (ww.sqrt() * xx.sqrt())
    }
}
