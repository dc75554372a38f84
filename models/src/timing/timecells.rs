//! Temporal representations of a stimulus for TD learning (Ludvig, Sutton & Kehoe 2008)
//! and scale-invariant time cells (Shankar & Howard 2012).
//!
//! After stimulus onset (time 0, unit = one step):
//! * **presence** — one unit, 1 while the stimulus is on;
//! * **complete serial compound (CSC)** — one unit per step since onset (a tapped delay
//!   line), the last unit standing for "that long or longer";
//! * **microstimuli** — a memory trace `y = dᵗ` read by `m` Gaussian basis functions,
//!   exactly Ludvig, Sutton & Kehoe (2008, eqs. 1–2): `xᵢ = y · exp(−(y − i/m)²/(2σ²)) / √(2π)`,
//!   `i = 1 … m` (defaults `d` 0.95 per step, `σ` 0.08, `m` 20 — see
//!   [`Representation::microstimulus`]; no `1/σ` factor: the basis function
//!   is `f(y, μ, σ) = exp(−(y − μ)²/(2σ²))/√(2π)`, so a unit at `y = μ` is `μ/√(2π)` high).
//!   Unit `i` peaks where `y² − μy − σ² = 0` (`μ = i/m`): `y* = (μ + √(μ² + 4σ²))/2`,
//!   `t* = ln y* / ln d` (at `t = 0` if `y* ≥ 1`). The TD agent reads the units divided by
//!   their peak heights ([`TimeCells::normalised_units_into`]); recordings hold the raw `xᵢ`;
//! * **Laplace time cells** — leaky integrators `dF/dt = −s F + f(t)` at log-spaced rates
//!   `s = k/τ*`, inverted with Post's formula `f̃ = (−1)ᵏ/k! · s^{k+1} ∂ᵏF/∂sᵏ`. For an
//!   impulse at 0, `f̃(τ*, t) = s^{k+1} tᵏ e^{−st}/k!`: a bump peaking at `t = τ*` whose
//!   shape is a Gamma(k+1, s) density, CV `1/√(k+1)` (scale invariance). The derivatives
//!   `Gₙ = ∂ⁿF/∂sⁿ` obey `dGₙ/dt = −s Gₙ − n Gₙ₋₁` and are propagated exactly over each
//!   step: `Gₙ(t+h) = e^{−sh} Σⱼ C(n,j) (−h)^{n−j} Gⱼ(t)`.

use serde::{Deserialize, Serialize};

/// Which temporal representation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Representation {
    /// One unit on while the stimulus is present.
    Presence,
    /// Tapped delay line with `units` units (the last absorbs longer times).
    Csc {
        /// Number of units.
        units: usize,
    },
    /// Microstimuli of a decaying trace.
    Microstimulus {
        /// Trace decay per step `d`.
        decay: f64,
        /// Basis width `σ` (trace units).
        sigma: f64,
        /// Number of microstimuli `m`.
        count: usize,
    },
    /// Scale-invariant Laplace/inverse-Laplace time cells.
    Laplace {
        /// Number of cells (log-spaced peak times).
        cells: usize,
        /// Smallest peak time τ* (steps).
        tau_min: f64,
        /// Largest peak time τ* (steps).
        tau_max: f64,
        /// Order `k` of Post's inversion (CV `1/√(k+1)`).
        order: usize,
    },
}

impl Representation {
    /// Microstimuli with Ludvig, Sutton & Kehoe's (2008) basis width `σ` 0.08, a trace decay
    /// of 0.95 per env step and `m` 20 microstimuli. The decay sets the representation's
    /// time unit: Ludvig et al.'s 0.985 is per step of their simulations, and per env step it
    /// left the trace above 0.7 over the paper's 24-step intervals, so only 6–7 of 10
    /// microstimuli peaked within 2 × TD. At 0.95 the trace falls to 0.09 by step 48 (2 × the
    /// longest paper TD), so every microstimulus peaks within the task's range and the 20
    /// units tile it as a population (peak times 0–43 steps).
    pub fn microstimulus() -> Self {
        Representation::Microstimulus {
            decay: 0.95,
            sigma: 0.08,
            count: 20,
        }
    }

    /// CSC with 64 units.
    pub fn csc() -> Self {
        Representation::Csc { units: 64 }
    }

    /// Laplace time cells: 24 cells, τ* from 1 to 64 steps, `k` = 8.
    pub fn laplace() -> Self {
        Representation::Laplace {
            cells: 24,
            tau_min: 1.0,
            tau_max: 64.0,
            order: 8,
        }
    }

    /// Number of units.
    pub fn size(&self) -> usize {
        match self {
            Representation::Presence => 1,
            Representation::Csc { units } => *units,
            Representation::Microstimulus { count, .. } => *count,
            Representation::Laplace { cells, .. } => *cells,
        }
    }

    /// Short name (`presence`, `csc`, `microstimulus`, `laplace`).
    pub fn name(&self) -> &'static str {
        match self {
            Representation::Presence => "presence",
            Representation::Csc { .. } => "csc",
            Representation::Microstimulus { .. } => "microstimulus",
            Representation::Laplace { .. } => "laplace",
        }
    }
}

/// Microstimulus `i` (1-based) of `m` at trace height `y` (Ludvig et al. 2008):
/// `y · exp(−(y − i/m)²/(2σ²)) / √(2π)`.
pub fn microstimulus(y: f64, i: usize, m: usize, sigma: f64) -> f64 {
    let mu = i as f64 / m as f64;
    let z = (y - mu) / sigma;
    y * (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt()
}

/// Closed-form peak `(time in steps, height)` of microstimulus `i` of `m`.
pub fn microstimulus_peak(i: usize, m: usize, sigma: f64, decay: f64) -> (f64, f64) {
    let mu = i as f64 / m as f64;
    let y = 0.5 * (mu + (mu * mu + 4.0 * sigma * sigma).sqrt());
    if y >= 1.0 {
        return (0.0, microstimulus(1.0, i, m, sigma));
    }
    (y.ln() / decay.ln(), microstimulus(y, i, m, sigma))
}

/// Peak times τ* of Laplace time cells, log-spaced from `tau_min` to `tau_max`.
pub fn laplace_peak_times(cells: usize, tau_min: f64, tau_max: f64) -> Vec<f64> {
    if cells == 1 {
        return vec![tau_min];
    }
    let ratio = (tau_max / tau_min).ln() / (cells - 1) as f64;
    (0..cells)
        .map(|j| tau_min * (ratio * j as f64).exp())
        .collect()
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|j| j as f64).product()
}

/// A temporal representation running in time: `onset`, `tick` once per step, read `units`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimeCells {
    /// The representation.
    pub repr: Representation,
    /// Steps since onset (`None` before the stimulus).
    pub elapsed: Option<u32>,
    /// Clock-speed noise: SD of the log of a per-trial factor `r` that scales the
    /// representation's time (`y = d^{r t}`, delay-line index `r t`, Laplace decay rates
    /// `r s`); 0 = deterministic. Trial-to-trial variance of the internal clock's speed is
    /// the scalar-variability source of scalar expectancy theory (Gibbon 1977; Gibbon,
    /// Church & Meck 1984); applied to a trace it makes every time cell's peak time vary
    /// in proportion to itself.
    /// (The `--set` key `clock_noise`; agents saved before the rename spell it
    /// `speed_noise`.)
    #[serde(default, alias = "speed_noise")]
    pub clock_noise: f64,
    /// This trial's clock-speed factor `r` (1 without noise).
    #[serde(skip, default = "unit_speed")]
    speed: f64,
    /// Laplace: `G[j][n] = ∂ⁿF/∂sⁿ` of cell `j`.
    derivatives: Vec<Vec<f64>>,
    /// Laplace: one-step propagators `P[j][n][m] = e^{−s_j} C(n,m) (−1)^{n−m}` (cached).
    #[serde(skip)]
    propagators: Vec<Vec<f64>>,
    /// Peak height of every unit (cached; normalises the units to a maximum of ~1).
    #[serde(skip)]
    peaks: Vec<f64>,
}

fn unit_speed() -> f64 {
    1.0
}

impl TimeCells {
    /// A representation at rest (no stimulus yet).
    pub fn new(repr: Representation) -> Self {
        let derivatives = match &repr {
            Representation::Laplace { cells, order, .. } => vec![vec![0.0; order + 1]; *cells],
            _ => Vec::new(),
        };
        TimeCells {
            repr,
            elapsed: None,
            clock_noise: 0.0,
            speed: 1.0,
            derivatives,
            propagators: Vec::new(),
            peaks: Vec::new(),
        }
    }

    /// Peak height of every unit over time (1 for presence and CSC).
    pub fn peak_heights(&self) -> Vec<f64> {
        match &self.repr {
            Representation::Microstimulus {
                decay,
                sigma,
                count,
            } => (1..=*count)
                .map(|i| microstimulus_peak(i, *count, *sigma, *decay).1.max(1e-9))
                .collect(),
            Representation::Laplace {
                cells,
                tau_min,
                tau_max,
                order,
            } => laplace_peak_times(*cells, *tau_min, *tau_max)
                .iter()
                .map(|&tau| {
                    // f̃(τ*, τ*) = s^{k+1} τ*^k e^{−k} / k!, s = k/τ*.
                    let k = *order as f64;
                    let log =
                        (k + 1.0) * (k / tau).ln() + k * tau.ln() - k - factorial(*order).ln();
                    log.exp().max(1e-12)
                })
                .collect(),
            _ => vec![1.0; self.repr.size()],
        }
    }

    /// Unit activities divided by their peak heights (each peaks at ~1).
    pub fn normalised_units_into(&self, out: &mut Vec<f64>) {
        self.units_into(out);
        if self.peaks.len() == out.len() {
            out.iter_mut().zip(&self.peaks).for_each(|(v, p)| *v /= p);
        } else {
            out.iter_mut()
                .zip(self.peak_heights())
                .for_each(|(v, p)| *v /= p);
        }
    }

    /// Clears the stimulus.
    pub fn clear(&mut self) {
        self.elapsed = None;
        for g in &mut self.derivatives {
            g.iter_mut().for_each(|v| *v = 0.0);
        }
    }

    /// Stimulus onset (time 0) at clock speed 1: an impulse into the Laplace integrators.
    pub fn onset(&mut self) {
        self.onset_with_speed(1.0);
    }

    /// Stimulus onset with this trial's clock-speed factor `speed` (> 0).
    pub fn onset_with_speed(&mut self, speed: f64) {
        if speed != self.speed {
            self.propagators.clear();
            self.speed = speed;
        }
        self.clear();
        if self.peaks.len() != self.repr.size() {
            self.peaks = self.peak_heights();
        }
        self.elapsed = Some(0);
        for g in &mut self.derivatives {
            g[0] = 1.0;
        }
    }

    /// Advances one step.
    pub fn tick(&mut self) {
        let Some(t) = self.elapsed else {
            return;
        };
        self.elapsed = Some(t + 1);
        if let Representation::Laplace {
            cells,
            tau_min,
            tau_max,
            order,
        } = &self.repr
        {
            let k1 = order + 1;
            if self.propagators.len() != *cells {
                self.propagators = laplace_peak_times(*cells, *tau_min, *tau_max)
                    .into_iter()
                    .map(|tau| {
                        // One step of real time is `h = speed` steps of represented time:
                        // `Gₙ(t+h) = e^{−sh} Σₘ C(n,m) (−h)^{n−m} Gₘ(t)`. (Until session 15
                        // the `h^{n−m}` factor was missing, which scaled every cell's
                        // amplitude by `speed^{−k}` on a noisy trial.)
                        let h = self.speed;
                        let decay = (-(*order as f64) * h / tau).exp();
                        let mut p = vec![0.0; k1 * k1];
                        for n in 0..k1 {
                            for m in 0..=n {
                                let power = (-h).powi((n - m) as i32);
                                p[n * k1 + m] = decay * binomial(n, m) * power;
                            }
                        }
                        p
                    })
                    .collect();
            }
            let mut old = vec![0.0; k1];
            for (g, p) in self.derivatives.iter_mut().zip(&self.propagators) {
                old.copy_from_slice(g);
                for (n, gn) in g.iter_mut().enumerate() {
                    *gn = (0..=n).map(|m| p[n * k1 + m] * old[m]).sum();
                }
            }
        }
    }

    /// Unit activities now (zeros before onset).
    pub fn units_into(&self, out: &mut Vec<f64>) {
        out.clear();
        let n = self.repr.size();
        let Some(t) = self.elapsed else {
            out.resize(n, 0.0);
            return;
        };
        match &self.repr {
            Representation::Presence => out.push(1.0),
            Representation::Csc { units } => {
                out.resize(*units, 0.0);
                out[self.csc_index(t).min(units - 1)] = 1.0;
            }
            Representation::Microstimulus {
                decay,
                sigma,
                count,
            } => {
                let y = self.trace(*decay, t);
                out.extend((1..=*count).map(|i| microstimulus(y, i, *count, *sigma)));
            }
            Representation::Laplace {
                cells,
                tau_min,
                tau_max,
                order,
            } => {
                let k = *order;
                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                let norm = sign / factorial(k);
                let ratio = (tau_max / tau_min).powf(1.0 / (*cells as f64 - 1.0).max(1.0));
                let mut tau = *tau_min;
                for g in &self.derivatives {
                    let s = k as f64 / tau;
                    out.push(norm * s.powi(k as i32 + 1) * g[k]);
                    tau *= ratio;
                }
            }
        }
    }

    /// Delay-line unit active `t` steps after onset (`r t` rounded with clock noise).
    fn csc_index(&self, t: u32) -> usize {
        if self.speed == 1.0 {
            t as usize
        } else {
            (t as f64 * self.speed).round() as usize
        }
    }

    /// Trace height `d^{r t}` `t` steps after onset.
    fn trace(&self, decay: f64, t: u32) -> f64 {
        if self.speed == 1.0 {
            decay.powi(t as i32)
        } else {
            decay.powf(t as f64 * self.speed)
        }
    }

    /// The population's estimate of the elapsed time (steps): the centre of mass of the
    /// active units' preferred times — delay line: the active unit; microstimuli: the
    /// trace height `ŷ = Σ xᵢ (i/m) / Σ xᵢ` read as `ln ŷ / ln d`; Laplace: `exp` of the
    /// activity-weighted mean `ln τ*` over the peak-normalised cells (each a function of
    /// `t/τ*` only, so the estimate moves with `ln t`). `None` for presence (no time) and
    /// before onset.
    pub fn decoded_time(&self) -> Option<f64> {
        let t = self.elapsed?;
        match &self.repr {
            Representation::Presence => None,
            Representation::Csc { units } => {
                Some((self.csc_index(t).min(units - 1) as f64).max(0.5))
            }
            Representation::Microstimulus { decay, count, .. } => {
                let mut units = Vec::new();
                self.units_into(&mut units);
                let (mut num, mut den) = (0.0, 0.0);
                for (i, x) in units.iter().enumerate() {
                    num += x * (i + 1) as f64 / *count as f64;
                    den += x;
                }
                let y_hat = (den > 1e-300).then(|| (num / den).clamp(1e-12, 1.0 - 1e-12))?;
                Some(y_hat.ln() / decay.ln())
            }
            Representation::Laplace {
                cells,
                tau_min,
                tau_max,
                ..
            } => {
                let mut units = Vec::new();
                self.normalised_units_into(&mut units);
                let (mut num, mut den) = (0.0, 0.0);
                for (a, tau) in units
                    .iter()
                    .zip(laplace_peak_times(*cells, *tau_min, *tau_max))
                {
                    let a = a.max(0.0);
                    num += a * tau.ln();
                    den += a;
                }
                (den > 1e-300).then(|| (num / den).exp())
            }
        }
    }

    /// The Laplace integrators `F(s)` (empty for other representations).
    pub fn laplace_integrators(&self) -> Vec<f64> {
        self.derivatives.iter().map(|g| g[0]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::{Representation, TimeCells};

    /// Agents saved before the field took its `--set` key's name (`clock_noise`) spell it
    /// `speed_noise`; they load with their noise.
    #[test]
    fn an_agent_saved_with_the_old_field_name_keeps_its_clock_noise() {
        let mut cells = TimeCells::new(Representation::microstimulus());
        cells.clock_noise = 0.15;
        let mut json = serde_json::to_value(&cells).unwrap();
        let map = json.as_object_mut().unwrap();
        let v = map
            .remove("clock_noise")
            .expect("serialised as clock_noise");
        map.insert("speed_noise".into(), v);
        let old: TimeCells = serde_json::from_value(json).unwrap();
        assert_eq!(old.clock_noise, 0.15);
    }
}
