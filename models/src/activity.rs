//! Neural-activity recording: one API for every model.
//!
//! Per step an agent writes named populations of unit activities into a [`StepRecorder`];
//! the episode runner adds the step's event markers (onion in, oven ready, checks, pickup,
//! delivery, reward). Recorded trials form an [`ActivityDataset`]
//! (units × time × trials with metadata) which the analysis crate consumes.
//!
//! Recording is opt-in: an agent's `record` method is only called when a recorder is
//! attached, so switching it off costs nothing but a branch per step.

use chronocooked_env::Task;
use serde::{Deserialize, Serialize};

/// Name and unit names of one population (e.g. `"accumulator"`, `"oscillators"`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Population {
    /// Population name.
    pub name: String,
    /// Number of units.
    pub size: usize,
}

/// Kind of a per-step event marker (aligned to the step on which it happened).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Marker {
    /// The onion went in: the oven turned on (oven time 0 is the step after).
    OvenOn,
    /// The oven showed ready (tasks with a ready cue).
    OvenReady,
    /// An interact next to a running oven with empty hands.
    OvenCheck,
    /// The soup was taken out.
    Pickup,
    /// The soup was delivered.
    Delivery,
    /// A non-zero reward.
    Reward,
    /// A paid interaction with the reward sink (dual task).
    Sink,
    /// The manual oven button (uncertainty task).
    Button,
    /// Oven 2 of a multi-oven task turned on (with the put in synchronous mode, at its
    /// on-time in asynchronous mode; its oven time 0 is the step after).
    OvenOn2,
    /// Oven 3 of a multi-oven task turned on.
    OvenOn3,
    /// Ready-Set-Go: the oven flashed Ready (the measurement epoch begins).
    Ready,
    /// Ready-Set-Go: the oven flashed Set, `ts` steps after Ready (the production epoch
    /// begins; production time 0 is the step after).
    Set,
}

impl Marker {
    /// Markers of one step from its info (event flags), the multi-oven task's oven states
    /// after the step (`ovens`: each oven that turned on during the step; `None` in the
    /// other tasks) and its reward.
    pub fn of_step(
        info: &chronocooked_env::Info,
        ovens: Option<&chronocooked_env::OvenSet>,
        reward: f32,
    ) -> Vec<Marker> {
        use chronocooked_env::Events as E;
        let mut out = Vec::new();
        for (flag, m) in [
            (E::ONION_IN, Marker::OvenOn),
            (E::OVEN_READY, Marker::OvenReady),
            (E::OVEN_CHECK, Marker::OvenCheck),
            (E::PICKUP, Marker::Pickup),
            (E::DELIVERY, Marker::Delivery),
            (E::SINK, Marker::Sink),
            (E::BUTTON, Marker::Button),
        ] {
            if info.events.has(flag) {
                out.push(m);
            }
        }
        // Ready-Set-Go: the Set flash starts the production timer (0 at the end of its
        // step); Ready leaves it off.
        if info.events.has(E::CUE) {
            out.push(if info.oven_timer == 0 {
                Marker::Set
            } else {
                Marker::Ready
            });
        }
        // An oven's timer reads 1 at the end of the step on which it started (it is set to
        // 0 and counts the step), and never again: it only counts up, and once emptied it
        // stays off.
        if let Some(ovens) = ovens {
            for oven in 2..=(ovens.n as usize).min(3) {
                if ovens.timer[oven - 1] == 1 {
                    out.push(Marker::oven_on(oven));
                }
            }
        }
        if reward != 0.0 {
            out.push(Marker::Reward);
        }
        out
    }

    /// The marker of oven `oven` (1, 2 or 3) turning on; oven 1's is [`Marker::OvenOn`].
    pub fn oven_on(oven: usize) -> Marker {
        match oven {
            2 => Marker::OvenOn2,
            3 => Marker::OvenOn3,
            _ => Marker::OvenOn,
        }
    }
}

/// The population-name suffix of oven `oven` (1 …) of a multi-oven agent: oven 1 records
/// under the plain names, the others as `<name>_oven2`, `<name>_oven3`.
pub fn oven_suffix(oven: usize) -> String {
    if oven <= 1 {
        String::new()
    } else {
        format!("_oven{oven}")
    }
}

/// The oven (1, 2 or 3) whose clock population `name` records ([`oven_suffix`]); 1 for
/// every name without an oven suffix.
pub fn population_oven(name: &str) -> usize {
    match name.rsplit_once("_oven").map(|(_, k)| k) {
        Some("2") => 2,
        Some("3") => 3,
        _ => 1,
    }
}

/// One marker of one trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Step index within the trial (0 = the first action).
    pub step: u32,
    /// What happened.
    pub marker: Marker,
}

/// Collects the populations an agent writes during one step.
#[derive(Debug, Clone, Default)]
pub struct StepRecorder {
    populations: Vec<Population>,
    values: Vec<f32>,
    cursor: usize,
    locked: bool,
}

impl StepRecorder {
    /// Writes population `name`. Agents must write the same populations, in the same
    /// order and sizes, at every step of a dataset.
    pub fn record(&mut self, name: &str, values: &[f32]) {
        if self.locked {
            let p = &self.populations[self.cursor];
            debug_assert_eq!(p.name, name, "populations written in a different order");
            debug_assert_eq!(p.size, values.len(), "population size changed");
        } else {
            self.populations.push(Population {
                name: name.to_string(),
                size: values.len(),
            });
        }
        self.cursor += 1;
        self.values.extend_from_slice(values);
    }

    /// Writes one scalar unit.
    pub fn scalar(&mut self, name: &str, value: f32) {
        self.record(name, &[value]);
    }

    /// The values population `name` was given at this step (its units in order), if it
    /// was written.
    pub fn population(&self, name: &str) -> Option<&[f32]> {
        let mut start = 0;
        for p in &self.populations[..self.cursor.min(self.populations.len())] {
            if p.name == name {
                return self.values.get(start..start + p.size);
            }
            start += p.size;
        }
        None
    }

    fn begin(&mut self) {
        self.values.clear();
        self.cursor = 0;
    }
}

/// One recorded trial (episode): activity `[T, N]` row-major, T steps × N units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Trial {
    /// Target duration of the episode (steps).
    pub td: u32,
    /// Start cell `(row, col)`.
    pub start: (usize, usize),
    /// Number of recorded steps `T`.
    pub steps: usize,
    /// Activity, `[T, N]` row-major (`N` = [`ActivityMeta::n_units`]).
    pub activity: Vec<f32>,
    /// Event markers in step order.
    pub events: Vec<Event>,
    /// Total reward of the episode.
    pub reward: f32,
    /// Whether the episode ended in a success (`agent::is_success`).
    pub success: bool,
    /// Multi-oven tasks: every oven's duration (steps; oven 1's is `td`); empty otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub oven_tds: Vec<u32>,
    /// Ready-Set-Go: the episode's prior and gain (indices into the task's lists) and
    /// foreperiod (`td` is its sample interval `ts`); absent for the other tasks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reproduction: Option<chronocooked_env::RsgState>,
}

impl Trial {
    /// What a recorded trial's outcome must be: a positive TD, markers in step order, a
    /// return of 0..=1 per step (every task pays at most 1 per step), a reward marker
    /// exactly when the trial was paid, success only in a paid trial and, where only
    /// deliveries pay (`only_deliveries_pay`), a full return only with success. The error
    /// names the field.
    fn validate_outcome(&self, only_deliveries_pay: bool) -> Result<(), String> {
        if self.td == 0 {
            return Err("td: 0 (allowed: a positive number of steps)".into());
        }
        if self.events.windows(2).any(|w| w[1].step < w[0].step) {
            return Err("events: markers out of step order".into());
        }
        let steps = self.steps as f32;
        if !(self.reward.is_finite() && (-1e-4..=steps + 1e-4).contains(&self.reward)) {
            return Err(format!(
                "reward: {} (allowed: 0..={steps}, at most 1 per step of the trial)",
                self.reward
            ));
        }
        let rewarded = self.events.iter().any(|e| e.marker == Marker::Reward);
        let full_without_success = only_deliveries_pay && self.reward >= 0.999 && !self.success;
        if rewarded != (self.reward > 0.0) || (self.success && !rewarded) || full_without_success {
            return Err(format!(
                "reward: {} and success {} do not agree with the trial's reward markers",
                self.reward, self.success
            ));
        }
        Ok(())
    }
    /// The duration of oven `oven` (1 …): `td` for oven 1 and for single-oven tasks,
    /// `None` for an oven the trial does not have.
    pub fn oven_td(&self, oven: usize) -> Option<u32> {
        match oven {
            0 | 1 => Some(self.td),
            k => self.oven_tds.get(k - 1).copied(),
        }
    }

    /// Step of the first `marker`, if any.
    pub fn first(&self, marker: Marker) -> Option<u32> {
        self.events
            .iter()
            .find(|e| e.marker == marker)
            .map(|e| e.step)
    }
}

/// What a dataset is: model, task, seed, time step and the unit layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ActivityMeta {
    /// Model name (zoo name, e.g. `ddm`, `lstm125`).
    pub model: String,
    /// The task and its parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Seed of the recording.
    pub seed: u64,
    /// Duration of one step in the model's own time unit (1.0 = one env step).
    pub dt: f64,
    /// Populations in unit order; unit `j` of population `p` is column
    /// `offset(p) + j` of every trial's activity.
    pub populations: Vec<Population>,
}

impl ActivityMeta {
    /// Metadata of a recording of `model` on `task` with `seed`, one env step per unit of
    /// time (`dt` 1); populations are filled in by the first recorded step.
    pub fn new(model: &str, task: &Task, seed: u64) -> Self {
        ActivityMeta {
            model: model.to_string(),
            task: task.clone(),
            seed,
            dt: 1.0,
            populations: Vec::new(),
        }
    }

    /// Total number of units `N`.
    pub fn n_units(&self) -> usize {
        self.populations.iter().map(|p| p.size).sum()
    }

    /// Column range of population `name`.
    pub fn range(&self, name: &str) -> Option<std::ops::Range<usize>> {
        let mut start = 0;
        for p in &self.populations {
            if p.name == name {
                return Some(start..start + p.size);
            }
            start += p.size;
        }
        None
    }

    /// Unit names `population[j]`, in column order.
    pub fn unit_names(&self) -> Vec<String> {
        self.populations
            .iter()
            .flat_map(|p| (0..p.size).map(move |j| format!("{}[{j}]", p.name)))
            .collect()
    }
}

/// Recorded trials of one model: units × time × trials, trials of varying length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ActivityDataset {
    /// Metadata.
    pub meta: ActivityMeta,
    /// Trials in recording order.
    pub trials: Vec<Trial>,
}

/// Most units a recording may have (all populations together).
pub const MAX_UNITS: usize = 1 << 20;

impl ActivityDataset {
    /// Checks a dataset read from a file before use: populations of `1..=`[`MAX_UNITS`]
    /// units in all, a finite `dt` > 0, and every trial's activity exactly `steps × units`
    /// values with its events inside the trial. The error names the field.
    pub fn validate(&self) -> Result<(), String> {
        let mut units: usize = 0;
        for (i, p) in self.meta.populations.iter().enumerate() {
            units = units
                .checked_add(p.size)
                .filter(|&u| u <= MAX_UNITS)
                .ok_or_else(|| {
                    format!(
                        "meta.populations[{i}].size: {} (at most {MAX_UNITS} units in all)",
                        p.size
                    )
                })?;
        }
        if !(self.meta.dt.is_finite() && self.meta.dt > 0.0) {
            return Err(format!(
                "meta.dt: {} (allowed: a finite number > 0)",
                self.meta.dt
            ));
        }
        // Outside the dual task (whose sink pays during the interval) every reward is a
        // delivery's: a full return is a success.
        let only_deliveries_pay = self.meta.task.family() != chronocooked_env::TaskFamily::Dual;
        for (i, t) in self.trials.iter().enumerate() {
            let want = t.steps.checked_mul(units);
            if want != Some(t.activity.len()) {
                return Err(format!(
                    "trials[{i}].activity: {} values (allowed: steps × units = {} × {units})",
                    t.activity.len(),
                    t.steps
                ));
            }
            if let Some(e) = t.events.iter().find(|e| e.step as usize >= t.steps.max(1)) {
                return Err(format!(
                    "trials[{i}].events: a marker at step {} of a {}-step trial",
                    e.step, t.steps
                ));
            }
            t.validate_outcome(only_deliveries_pay)
                .map_err(|e| format!("trials[{i}].{e}"))?;
        }
        Ok(())
    }

    /// Parses and checks ([`ActivityDataset::validate`]) an `activity.json`.
    pub fn from_json(bytes: &[u8]) -> Result<Self, String> {
        let ds: ActivityDataset = serde_json::from_slice(bytes).map_err(|e| e.to_string())?;
        ds.validate()?;
        Ok(ds)
    }

    /// Activity aligned to the first `marker` of every trial that has it:
    /// `[trials, window, N]` row-major with `window = after + 1` steps starting at the
    /// step after the marker (oven time 0 … `after` when aligned to [`Marker::OvenOn`]);
    /// steps past a trial's end are NaN. Also returns the indices of the trials used.
    pub fn aligned(&self, marker: Marker, after: usize) -> (Vec<f32>, Vec<usize>) {
        let n = self.meta.n_units();
        let window = after + 1;
        let mut out = Vec::new();
        let mut used = Vec::new();
        for (i, trial) in self.trials.iter().enumerate() {
            let Some(at) = trial.first(marker) else {
                continue;
            };
            used.push(i);
            for k in 0..window {
                let step = at as usize + 1 + k;
                if step < trial.steps {
                    out.extend_from_slice(&trial.activity[step * n..(step + 1) * n]);
                } else {
                    out.extend(std::iter::repeat_n(f32::NAN, n));
                }
            }
        }
        (out, used)
    }
}

/// Builds an [`ActivityDataset`] trial by trial while an episode runs.
#[derive(Debug, Clone)]
pub struct TrialRecorder {
    meta: ActivityMeta,
    step: StepRecorder,
    trials: Vec<Trial>,
    current: Option<Trial>,
}

impl TrialRecorder {
    /// A recorder for `meta` (its populations are filled from the first recorded step).
    pub fn new(mut meta: ActivityMeta) -> Self {
        meta.populations.clear();
        TrialRecorder {
            meta,
            step: StepRecorder::default(),
            trials: Vec::new(),
            current: None,
        }
    }

    /// Starts a trial.
    pub fn begin_trial(&mut self, td: u32, start: (usize, usize)) {
        self.current = Some(Trial {
            td,
            start,
            steps: 0,
            activity: Vec::new(),
            events: Vec::new(),
            reward: 0.0,
            success: false,
            oven_tds: Vec::new(),
            reproduction: None,
        });
    }

    /// Sets the current trial's task context from the env's state after the reset: every
    /// oven's duration (multi-oven tasks; steps), the prior and gain (reproduction).
    pub fn set_context(&mut self, state: &chronocooked_env::KitchenState) {
        if let Some(t) = self.current.as_mut() {
            if let Some(mo) = &state.multi_oven {
                let n = mo.td.iter().take_while(|&&td| td > 0).count();
                t.oven_tds = mo.td[..n].to_vec();
            }
            t.reproduction = state.reproduction;
        }
    }

    /// The per-step recorder to hand to the agent (cleared for the new step).
    pub fn step_recorder(&mut self) -> &mut StepRecorder {
        self.step.begin();
        &mut self.step
    }

    /// Closes the step: stores the activity the agent wrote and the step's markers.
    pub fn end_step(&mut self, markers: &[Marker], reward: f32) {
        if !self.step.locked {
            self.step.locked = true;
            self.meta.populations = self.step.populations.clone();
        }
        if let Some(t) = self.current.as_mut() {
            let n = self.meta.n_units();
            let mut row = self.step.values.clone();
            row.resize(n, f32::NAN);
            t.activity.extend_from_slice(&row);
            for &m in markers {
                t.events.push(Event {
                    step: t.steps as u32,
                    marker: m,
                });
            }
            t.reward += reward;
            t.steps += 1;
        }
    }

    /// Ends the trial.
    pub fn end_trial(&mut self, success: bool) {
        if let Some(mut t) = self.current.take() {
            t.success = success;
            self.trials.push(t);
        }
    }

    /// The finished dataset.
    pub fn finish(self) -> ActivityDataset {
        ActivityDataset {
            meta: self.meta,
            trials: self.trials,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One trial of `task` that was paid `reward` at its last step, marked `success`.
    fn paid(task: &str, reward: f32, success: bool) -> ActivityDataset {
        let mut ds = ActivityDataset {
            meta: ActivityMeta::new("m", &Task::new(task).unwrap(), 0),
            trials: Vec::new(),
        };
        ds.meta.populations.clear();
        ds.trials.push(Trial {
            td: 6,
            start: (1, 0),
            steps: 10,
            activity: Vec::new(),
            events: vec![Event {
                step: 9,
                marker: Marker::Reward,
            }],
            reward,
            success,
            oven_tds: Vec::new(),
            reproduction: None,
        });
        ds
    }

    #[test]
    fn a_trial_outcome_must_agree_with_its_reward_markers_and_its_task() {
        paid("FixedInterval-v0", 1.0, true).validate().unwrap();
        // A full return without success: only the dual task's sink pays without a delivery.
        let err = paid("FixedInterval-v0", 1.0, false).validate().unwrap_err();
        assert!(err.contains("trials[0].reward"), "{err}");
        paid("DualTask-v0", 1.0, false).validate().unwrap();
        // More than 1 per step, or a reward without its marker.
        assert!(paid("FixedInterval-v0", 11.0, true).validate().is_err());
        let mut unmarked = paid("FixedInterval-v0", 1.0, true);
        unmarked.trials[0].events.clear();
        assert!(unmarked.validate().is_err());
    }
}
