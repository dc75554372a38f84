//! Drift-diffusion timer (Simen, Balci, deSouza, Cohen & Holmes 2011).
//!
//! An accumulator `dx = A dt + c dW` with `c = m √A` starts at 0 at the timed event and
//! responds when `x ≥ z`. Its first-passage time is inverse Gaussian with mean `z/A`,
//! shape `z²/c²`, so `CV = m/√z` whatever `A` (the scalar property) and skewness `3·CV`.
//! Timing a new interval `T` means learning the drift `A = z/T`.
//!
//! Simulation is exact at the sampled times: the increment over a step `h` is
//! `A h + c √h N(0, 1)` (the Wiener process has Gaussian increments), and a threshold
//! crossing *inside* a step is detected with the Brownian-bridge probability
//! `exp(−2 (z − x₀)(z − x₁) / (c² h))`, so first passages are not biased late by the step.
//! [`DriftDiffusion::sample_first_passage`] draws first-passage times directly from the
//! inverse Gaussian.

use rand::Rng;
use rand_distr::{Distribution, InverseGaussian, StandardNormal};
use serde::{Deserialize, Serialize};

/// Parameters and state of one drift-diffusion accumulator. Time is in the caller's unit
/// (env steps for the agents).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DriftDiffusion {
    /// Drift `A` (threshold units per time unit), > 0.
    pub drift: f64,
    /// Response threshold `z` (> 0).
    pub threshold: f64,
    /// Noise coefficient `m` (`c = m √A`); 0 makes the timer deterministic.
    pub noise: f64,
    /// Accumulator value `x`.
    pub x: f64,
    /// Elapsed time since the start.
    pub t: f64,
    /// Time of the first threshold crossing of this trial, if it happened.
    pub crossed_at: Option<f64>,
}

impl DriftDiffusion {
    /// A timer with drift `drift`, threshold `threshold` and noise coefficient `noise`,
    /// reset to `x = 0`.
    pub fn new(drift: f64, threshold: f64, noise: f64) -> Self {
        DriftDiffusion {
            drift,
            threshold,
            noise,
            x: 0.0,
            t: 0.0,
            crossed_at: None,
        }
    }

    /// Diffusion coefficient `c = m √A`.
    pub fn diffusion(&self) -> f64 {
        self.noise * self.drift.max(0.0).sqrt()
    }

    /// Mean first-passage time `z/A`.
    pub fn mean_first_passage(&self) -> f64 {
        self.threshold / self.drift
    }

    /// Restarts the accumulator at 0 (the timed event).
    pub fn reset(&mut self) {
        self.x = 0.0;
        self.t = 0.0;
        self.crossed_at = None;
    }

    /// Advances by `h` time units; returns whether the threshold was crossed during this
    /// step for the first time in the trial.
    pub fn step<R: Rng + ?Sized>(&mut self, h: f64, rng: &mut R) -> bool {
        let c = self.diffusion();
        let x0 = self.x;
        let noise: f64 = if c > 0.0 {
            rng.sample::<f64, _>(StandardNormal)
        } else {
            0.0
        };
        let x1 = x0 + self.drift * h + c * h.sqrt() * noise;
        self.x = x1;
        self.t += h;
        if self.crossed_at.is_some() {
            return false;
        }
        let z = self.threshold;
        let crossed = if x1 >= z {
            true
        } else if c > 0.0 && x0 < z {
            // Brownian bridge: did the path touch z between the two samples?
            let p = (-2.0 * (z - x0) * (z - x1) / (c * c * h)).exp();
            rng.random::<f64>() < p
        } else {
            false
        };
        if crossed {
            self.crossed_at = Some(self.t);
        }
        crossed
    }

    /// Simulates one trial with step `h` until the first crossing (or `max_t`) and returns
    /// the first-passage time (`None` if not crossed by `max_t`).
    pub fn simulate_first_passage<R: Rng + ?Sized>(
        &mut self,
        h: f64,
        max_t: f64,
        rng: &mut R,
    ) -> Option<f64> {
        self.reset();
        while self.t < max_t {
            if self.step(h, rng) {
                // The crossing happened inside (t − h, t]: take the step's midpoint
                // when it was detected by the bridge, the end otherwise.
                let t = if self.x >= self.threshold {
                    self.t
                } else {
                    self.t - 0.5 * h
                };
                return Some(t);
            }
        }
        None
    }

    /// Draws a first-passage time from its exact law, the inverse Gaussian
    /// `IG(mean z/A, shape z²/c²)`; `z/A` exactly when noise is 0.
    pub fn sample_first_passage<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        let mean = self.mean_first_passage();
        let c = self.diffusion();
        if c <= 0.0 {
            return mean;
        }
        let shape = self.threshold * self.threshold / (c * c);
        match InverseGaussian::new(mean, shape) {
            Ok(d) => d.sample(rng),
            Err(_) => mean,
        }
    }

    /// Drift learning at the reinforced time `T`, learning-rate form
    /// `A ← A·[1 + α (z − x(T)) / x(T)]`, with `x(T)` the accumulator value at the
    /// reward. At `α = 1` this is the one-shot rule of both trial types: a late trial
    /// (`x(T) < z`) scales the drift up by `z/x(T)`; an early trial (crossed before the
    /// reward, the accumulator kept rising to `x(T) > z`) scales it down so that
    /// `A = z/T` at the reward. Without noise both give `A = z/T` in one trial.
    pub fn learn(&mut self, x_at_reward: f64, rate: f64) {
        if x_at_reward <= 1e-9 || !x_at_reward.is_finite() {
            return;
        }
        let factor = 1.0 + rate * (self.threshold - x_at_reward) / x_at_reward;
        self.drift = (self.drift * factor).clamp(1e-6, 1e6);
    }

    /// Drift learning from a reward time alone (noise-free accumulator value `A·T`):
    /// `A ← A·[1 + α (z − A T)/(A T)]`, i.e. `A ← z/T` at `α = 1`.
    pub fn learn_interval(&mut self, interval: f64, rate: f64) {
        let x = self.drift * interval;
        self.learn(x, rate);
    }
}
