//! Curricula during training: the uncertainty task's never-ready ramp, the multi-timer
//! levels (with the paper's warm-up level), the growing multi-anchor / multi-oven tasks and
//! the reproduction task's narrowing reward window.

use super::Trainer;
use crate::error::TrainError;
use crate::ppo::config::Curriculum;
use chronocooked_env::{TaskParams, VecEnv};

impl Trainer {
    pub(super) fn apply_curriculum(&mut self) -> Result<(), TrainError> {
        if let Curriculum::Uncertainty {
            start,
            end,
            ramp_fraction,
        } = self.cfg.curriculum
        {
            let frac = if ramp_fraction <= 0.0 {
                1.0
            } else {
                (self.state.steps as f64 / (ramp_fraction * self.cfg.total_steps as f64)).min(1.0)
            };
            // Quantised to 0.005 so the spec is rebuilt rarely.
            let p = ((start + (end - start) * frac) * 200.0).round() / 200.0;
            if (p - self.state.never_ready_prob).abs() > 1e-9 || self.state.updates == 0 {
                let mut config = self.envs.config().clone();
                config.set_never_ready_prob(p as f32);
                self.envs.set_config(&config)?;
                self.state.never_ready_prob = p;
            }
        }
        Ok(())
    }

    pub(super) fn advance_multi_timer(&mut self) -> Result<(), TrainError> {
        let Curriculum::MultiTimer {
            thresholds,
            window,
            warmup,
        } = &self.cfg.curriculum
        else {
            return Ok(());
        };
        let n_tds = match &self.envs.config().params {
            TaskParams::MultiTimer { tds, .. } => tds.len(),
            _ => return Ok(()),
        };
        if *warmup {
            return self.advance_level(thresholds.clone(), *window, n_tds);
        }
        let k = self.state.num_timers;
        if k >= n_tds || self.state.since_change < *window {
            return Ok(());
        }
        let threshold = thresholds
            .get(k - 1)
            .or(thresholds.last())
            .copied()
            .unwrap_or(0.9);
        let recent: Vec<f32> = self
            .state
            .recent
            .iter()
            .rev()
            .take(*window)
            .map(|e| e.ret)
            .collect();
        let mean = recent.iter().sum::<f32>() / recent.len() as f32;
        if mean >= threshold {
            self.state.num_timers = k + 1;
            self.state.curriculum_level = k + 1;
            self.envs.set_num_timers(k + 1)?;
            self.state.since_change = 0;
        }
        Ok(())
    }

    /// The paper's curriculum with its warm-up level: leave level `L` once the mean reward
    /// of the last `window` episodes (all finished since the last change) reaches
    /// `thresholds[L]`; level 0 → 1 switches the warm-up rules off, later levels add a TD.
    fn advance_level(
        &mut self,
        thresholds: Vec<f32>,
        window: usize,
        n_tds: usize,
    ) -> Result<(), TrainError> {
        let level = self.state.curriculum_level;
        if level >= n_tds || self.state.since_change < window {
            return Ok(());
        }
        let threshold = thresholds
            .get(level)
            .or(thresholds.last())
            .copied()
            .unwrap_or(0.9);
        let recent = self.state.recent.iter().rev().take(window);
        let mean = recent.map(|e| e.ret).sum::<f32>() / window as f32;
        if mean < threshold {
            return Ok(());
        }
        if level == 0 {
            let task = self.cfg.task.config()?;
            set_warmup(&mut self.envs, &task, false)?;
        } else {
            self.envs.set_num_timers(level + 1)?;
            self.state.num_timers = level + 1;
        }
        self.state.curriculum_level = level + 1;
        self.state.since_change = 0;
        Ok(())
    }
}

impl Trainer {
    /// Tolerance curriculum: sets the envs' reward window to the current level's (a spec
    /// rebuild only when it differs from the envs' own). Called where the level is set: at
    /// construction, at a restore and at a level change — not every update.
    pub(super) fn apply_tolerance(&mut self) -> Result<(), TrainError> {
        let task = self.cfg.reward_window()?;
        let Some((tol, steps)) = self
            .cfg
            .curriculum
            .tolerance_at(self.state.curriculum_level, task)
        else {
            return Ok(());
        };
        let Some(now) = self.envs.config().reward_window() else {
            return Ok(());
        };
        let level = (tol as f32, steps as f32);
        if now != level {
            let config = self.envs.config().with_reward_window(level.0, level.1)?;
            self.envs.set_config(&config)?;
        }
        Ok(())
    }

    /// Tolerance curriculum, checked at the rollout's end once `window` episodes have
    /// finished since the last change, on the share of them that delivered inside the
    /// window: the next (narrower) level once it reaches the level's threshold, the
    /// previous (wider) one when it falls below `fallback`. Episodes under way keep
    /// running; their deliveries are paid on the new window.
    pub(super) fn advance_tolerance(&mut self) -> Result<(), TrainError> {
        let Curriculum::Tolerance {
            thresholds,
            fallback,
            window,
            levels,
            ..
        } = &self.cfg.curriculum
        else {
            return Ok(());
        };
        let level = self.state.curriculum_level;
        if self.state.since_change < *window {
            return Ok(());
        }
        let threshold = thresholds
            .get(level)
            .or(thresholds.last())
            .copied()
            .unwrap_or(0.8);
        let recent = self.state.recent.iter().rev().take(*window);
        let share = recent.filter(|e| e.success).count() as f32 / *window as f32;
        let next = if level + 1 < *levels && share >= threshold {
            level + 1
        } else if level > 0 && share < *fallback {
            level - 1
        } else {
            return Ok(());
        };
        self.state.curriculum_level = next;
        self.state.since_change = 0;
        self.apply_tolerance()
    }
}

/// Switches the multi-timer warm-up rules on (one timer, soup only at `timer ≥ TD`, reduced
/// reward 0.1, no buffers) or back to the configured `task`.
pub(super) fn set_warmup(
    envs: &mut VecEnv,
    task: &chronocooked_env::TaskConfig,
    on: bool,
) -> Result<(), TrainError> {
    let TaskParams::MultiTimer {
        mode,
        under_buffer,
        over_buffer,
        reduced_reward,
        ..
    } = &task.params
    else {
        return Ok(());
    };
    let rules = if on {
        (chronocooked_env::RewardMode::LowerBounded, 0.1, 0, 0)
    } else {
        (*mode, *reduced_reward, *under_buffer, *over_buffer)
    };
    let mut config = envs.config().clone();
    if let TaskParams::MultiTimer {
        mode,
        reduced_reward,
        under_buffer,
        over_buffer,
        ..
    } = &mut config.params
    {
        (*mode, *reduced_reward, *under_buffer, *over_buffer) = rules;
    }
    envs.set_config(&config)?;
    Ok(())
}

/// The task of growth level `level` (multi-anchor: `2 + level` counters; multi-oven:
/// `1 + level` ovens, as the family declares its growth); `None` when the curriculum does
/// not grow the task.
pub(super) fn growth_task(
    cfg: &crate::ppo::config::TrainConfig,
    level: usize,
) -> Result<Option<chronocooked_env::TaskConfig>, TrainError> {
    if cfg.curriculum.growth().is_none() {
        return Ok(None);
    }
    let task = cfg.task.config()?;
    let first = growth_of(cfg, &task)?.first;
    Ok(Some(task.at_growth_size(first + level)?))
}

/// The task's growth, checked against the curriculum's family. Errors when the task does
/// not grow that way.
fn growth_of(
    cfg: &crate::ppo::config::TrainConfig,
    task: &chronocooked_env::TaskConfig,
) -> Result<chronocooked_env::Growth, TrainError> {
    let Some(g) = cfg.curriculum.growth() else {
        return Err(TrainError::InvalidParam {
            field: "curriculum".into(),
            value: format!("{:?}", cfg.curriculum),
            allowed: "a curriculum that grows the task (multi_anchor, multi_oven)".into(),
        });
    };
    match task.growth() {
        Some(growth) if task.family() == g.family => Ok(growth),
        _ => {
            let key = chronocooked_env::all_tasks()
                .iter()
                .find(|t| t.family == g.family)
                .and_then(|t| t.default_config().growth())
                .map_or("?", |growth| growth.key);
            Err(TrainError::InvalidParam {
                field: "curriculum".into(),
                value: format!("{:?}", g.family),
                allowed: format!(
                    "a curriculum of the task's family (task {} has no growing `{key}`)",
                    cfg.task
                ),
            })
        }
    }
}

/// The last level of a growing curriculum: the configured task's counters (multi-anchor)
/// or ovens (multi-oven) less the first level's. Errors when the task does not grow that way.
pub(super) fn growth_last_level(
    cfg: &crate::ppo::config::TrainConfig,
) -> Result<usize, TrainError> {
    if cfg.curriculum.growth().is_none() {
        return Ok(0);
    }
    let growth = growth_of(cfg, &cfg.task.config()?)?;
    Ok(growth.last.saturating_sub(growth.first))
}

impl Trainer {
    /// Multi-anchor / multi-oven curricula: checked at the rollout's end, as the
    /// reference's callback. A level is left once the mean reward of the last `window`
    /// episodes, all finished since the last change, reaches `thresholds[level]`; then the
    /// envs are rebuilt with one more counter or oven and reset (every episode starts
    /// anew, recurrent states at zero), and Adam is cleared where the curriculum says so.
    pub(super) fn advance_growth(&mut self) -> Result<(), TrainError> {
        let Some(g) = self.cfg.curriculum.growth() else {
            return Ok(());
        };
        let (window, clear_adam) = (g.window, g.clear_adam);
        let level = self.state.curriculum_level;
        let threshold = g
            .thresholds
            .get(level)
            .or(g.thresholds.last())
            .copied()
            .unwrap_or(0.9);
        if level >= growth_last_level(&self.cfg)? || self.state.since_change < window {
            return Ok(());
        }
        let recent = self.state.recent.iter().rev().take(window);
        let mean = recent.map(|e| e.ret).sum::<f32>() / window as f32;
        if mean < threshold {
            return Ok(());
        }
        self.set_growth_level(level + 1)?;
        if clear_adam {
            let params = self.state.adam.params;
            self.state.adam = crate::ppo::adam::Adam::new(self.state.theta.len(), params);
        }
        Ok(())
    }

    /// Rebuilds the envs at growth level `level` and starts every episode anew.
    pub(super) fn set_growth_level(&mut self, level: usize) -> Result<(), TrainError> {
        let Some(task) = growth_task(&self.cfg, level)? else {
            return Ok(());
        };
        let n = self.cfg.ppo.n_envs;
        self.envs = VecEnv::new(&task, n, chronocooked_env::Autoreset::SameStep)?;
        self.envs.reset(chronocooked_env::derive_seed(
            self.cfg.seed,
            0x5EED + level as u64,
        ));
        self.state.curriculum_level = level;
        self.state.since_change = 0;
        self.state.keep.fill(0.0);
        self.state.ep_return.fill(0.0);
        self.state.ep_len.fill(0);
        self.state.core_state = None;
        self.state.frame_history.fill(0.0);
        self.state.envs = self.envs.snapshot();
        Ok(())
    }
}
