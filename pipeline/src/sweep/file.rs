//! The sweep file (TOML): models × sizes × tasks × seeds × override variants, expanded into
//! [`Job`]s with their ids, families and settings.

use chronocooked_env::Task;
use chronocooked_training::TrainError;
use chronocooked_training::zoo::{Family, family_of};
use serde::{Deserialize, Serialize};

/// A sweep file (TOML). Every list is crossed with every other.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// Name (Slurm job name, report title).
    #[serde(default = "default_name")]
    pub name: String,
    /// Task ids.
    pub tasks: Vec<String>,
    /// Zoo names; a bare recurrent kind (`lstm`, `gru`, `rnn`, `ctrnn`, `ctrnn-reservoir`) is
    /// crossed with `sizes`.
    pub models: Vec<String>,
    /// Hidden sizes for bare recurrent kinds (default `[125]`).
    #[serde(default = "default_sizes")]
    pub sizes: Vec<usize>,
    /// Seeds (default `[0]`).
    #[serde(default = "default_seeds")]
    pub seeds: Vec<u64>,
    /// PPO preset (`reference` or `fast`; default `reference`).
    #[serde(default = "default_preset")]
    pub preset: String,
    /// PPO env-step budget (default: the preset's).
    #[serde(default)]
    pub steps: Option<u64>,
    /// Timing-model training episodes (default: the model's).
    #[serde(default)]
    pub episodes: Option<usize>,
    /// `key=value` settings for every PPO run (`env.<param>` settings also reach timing
    /// models and evaluation).
    #[serde(default)]
    pub set: Vec<String>,
    /// Override variants: each inner list of `key=value` settings is one variant; jobs are
    /// crossed with them (default: one variant without settings).
    #[serde(default)]
    pub variants: Vec<Vec<String>>,
    /// Variants of one task only, keyed by task id (e.g. FI at several TDs:
    /// `"FixedInterval-v0" = [["env.td=6"], ["env.td=12"]]`), crossed with `variants`.
    #[serde(default)]
    pub task_variants: std::collections::BTreeMap<String, Vec<Vec<String>>>,
    /// Record neural activity (+ neural summary, heat maps) of trained models (default true).
    #[serde(default = "yes")]
    pub record: bool,
    /// Repetitions of the recording's every-start-cell protocol (1–100, default 1; each a
    /// new draw of the model's noise), as `record --repeats`.
    #[serde(default)]
    pub record_repeats: Option<u64>,
    /// Export activity and records to NPZ/CSV (default true).
    #[serde(default = "yes")]
    pub export: bool,
    /// Uncertainty adaptation (`adapt` stage; default false) of every trained agent of an
    /// `Uncertainty-v0` job whose oven always readies (`env.never_ready_prob=0`): it keeps
    /// learning with the task's default never-ready probability.
    #[serde(default)]
    pub adapt: bool,
    /// Adaptation budget of timing agents (episodes; default 3000).
    #[serde(default)]
    pub adapt_episodes: Option<usize>,
    /// Adaptation budget of PPO agents (env steps; default 100k).
    #[serde(default)]
    pub adapt_steps: Option<u64>,
    /// Stochastic evaluation with N episodes per condition instead of the reference protocol.
    #[serde(default)]
    pub stochastic: Option<usize>,
}

fn default_name() -> String {
    "sweep".into()
}
fn default_sizes() -> Vec<usize> {
    vec![125]
}
fn default_seeds() -> Vec<u64> {
    vec![0]
}
fn default_preset() -> String {
    "reference".into()
}
fn yes() -> bool {
    true
}

/// One unit of work of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Job {
    /// Stable id, also the job folder relative to the sweep output (`task/model/seedN`).
    pub id: String,
    /// The task, with the job's parameters (serialised as `task` and `env`).
    #[serde(flatten)]
    pub task: Task,
    /// Zoo name.
    pub model: String,
    /// Model family (decides the training command).
    pub family: Family,
    /// Seed.
    pub seed: u64,
    /// Training settings (`--set`), variant settings included.
    pub sets: Vec<String>,
    /// Leaderboard row: the model plus its variant's non-task settings (runs of one model
    /// on different task settings, e.g. FI TDs, share a row).
    pub row: String,
}

/// The first job id that occurs twice in `jobs`.
fn repeated_id(jobs: &[Job]) -> Option<&str> {
    let mut seen = std::collections::HashSet::new();
    jobs.iter()
        .map(|j| j.id.as_str())
        .find(|id| !seen.insert(*id))
}

fn bad(field: &str, value: impl ToString, allowed: &str) -> TrainError {
    TrainError::InvalidParam {
        field: field.into(),
        value: value.to_string(),
        allowed: allowed.into(),
    }
}

/// Whether a `key=value` setting applies to `model` (of `family`) on `task`: task settings
/// (`env.*`) apply to every model; others to a model whose settings have the key (PPO
/// settings to deep-RL models, a timing model's family's settings to it, none to
/// baselines). Values are checked with each job's resolved settings.
pub fn applies(family: Family, task: &str, model: &str, kv: &str) -> bool {
    if kv.starts_with("env.") {
        return true;
    }
    let key = kv.split_once('=').map_or(kv, |(k, _)| k).trim();
    match family {
        Family::DeepRl => chronocooked_training::settings::find(
            chronocooked_training::settings::ppo::PPO_SETTINGS,
            key,
        )
        .is_some(),
        Family::Timing => Task::new(task).is_ok_and(|t| {
            chronocooked_training::timing_run::TimingRunConfig::new(&t, model, 0).has_setting(key)
        }),
        Family::Baseline => false,
    }
}

/// A folder-safe label of a variant (`learning_rate=1e-3,ent_coef=0.01` →
/// `learning_rate-1e-3_ent_coef-0.01`).
pub fn variant_label(sets: &[String]) -> String {
    sets.iter()
        .map(|s| {
            s.chars()
                .map(|c| match c {
                    '=' => '-',
                    c if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') => c,
                    _ => '_',
                })
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("_")
}

/// Most jobs one sweep may expand to: 40 times the paper's whole grid (≈ 2,500 jobs); a
/// larger study is several sweeps.
pub const MAX_JOBS: usize = 100_000;

impl SweepFile {
    /// Checks every list and name (typed errors name the field and allowed values).
    pub fn validate(&self) -> Result<(), TrainError> {
        for (field, empty) in [
            ("tasks", self.tasks.is_empty()),
            ("models", self.models.is_empty()),
            ("sizes", self.sizes.is_empty()),
            ("seeds", self.seeds.is_empty()),
        ] {
            if empty {
                return Err(bad(field, "[]", "a non-empty list"));
            }
        }
        // A value listed twice would give two jobs with one folder (two writers).
        fn repeated<T: PartialEq + ToString>(list: &[T]) -> Option<String> {
            list.iter()
                .enumerate()
                .find(|(i, v)| list[..*i].contains(v))
                .map(|(_, v)| v.to_string())
        }
        for (field, twice) in [
            ("tasks", repeated(&self.tasks)),
            ("models", repeated(&self.models)),
            ("sizes", repeated(&self.sizes)),
            ("seeds", repeated(&self.seeds)),
        ] {
            if let Some(v) = twice {
                return Err(bad(field, v, "each value once (this one is listed twice)"));
            }
        }
        // The name is the default output folder's last part (`lab-out/<name>`).
        let plain = !self.name.is_empty()
            && self.name != "."
            && self.name != ".."
            && !self.name.contains(['/', '\\'])
            && !self.name.chars().any(char::is_control);
        if !plain {
            return Err(bad(
                "name",
                &self.name,
                "a plain folder name (no path separators, not . or ..)",
            ));
        }
        let tasks: Vec<&str> = chronocooked_env::all_tasks().iter().map(|t| t.id).collect();
        for t in &self.tasks {
            if !tasks.contains(&t.as_str()) {
                return Err(bad("tasks", t, &tasks.join(", ")));
            }
        }
        if !chronocooked_training::ppo::presets::PRESETS.contains(&self.preset.as_str()) {
            return Err(bad(
                "preset",
                &self.preset,
                &chronocooked_training::ppo::presets::PRESETS.join(", "),
            ));
        }
        // Every budget within what the lab can run (the same bounds as the CLI and the
        // settings tables), so that no job of the sweep can run without end.
        let max_steps = chronocooked_training::settings::ppo::MAX_TOTAL_STEPS;
        let max_episodes = chronocooked_training::settings::timing::MAX_EPISODES as u64;
        let max_stochastic =
            chronocooked_analysis::evaluation::protocol::MAX_STOCHASTIC_EPISODES as u64;
        for (field, value, max, what) in [
            ("steps", self.steps, max_steps, "env steps"),
            (
                "episodes",
                self.episodes.map(|e| e as u64),
                max_episodes,
                "episodes",
            ),
            (
                "stochastic",
                self.stochastic.map(|e| e as u64),
                max_stochastic,
                "episodes per condition",
            ),
            (
                "adapt_episodes",
                self.adapt_episodes.map(|e| e as u64),
                max_episodes,
                "episodes",
            ),
            ("adapt_steps", self.adapt_steps, max_steps, "env steps"),
        ] {
            if let Some(v) = value
                && !(1..=max).contains(&v)
            {
                return Err(bad(field, v, &format!("1..={max} {what}")));
            }
        }
        for m in self.expanded_models() {
            family_of(&m)?;
        }
        for t in self.task_variants.keys() {
            if !self.tasks.contains(t) {
                return Err(bad("task_variants", t, &self.tasks.join(", ")));
            }
        }
        let task_sets = self.task_variants.values().flatten().flatten();
        for s in self
            .set
            .iter()
            .chain(self.variants.iter().flatten())
            .chain(task_sets)
        {
            if !s.contains('=') {
                return Err(TrainError::BadOverride(s.clone()));
            }
        }
        // One key twice in one list: the later value would silently replace the earlier.
        fn key_twice(list: &[String]) -> Option<&str> {
            fn key(s: &str) -> &str {
                s.split_once('=').map_or("", |(k, _)| k.trim())
            }
            list.iter()
                .enumerate()
                .find(|(i, s)| list[..*i].iter().any(|t| key(t) == key(s)))
                .map(|(_, s)| s.as_str())
        }
        let lists = std::iter::once(("set", &self.set))
            .chain(self.variants.iter().map(|v| ("variants", v)))
            .chain(
                self.task_variants
                    .values()
                    .flatten()
                    .map(|v| ("task_variants", v)),
            );
        for (field, list) in lists {
            if let Some(s) = key_twice(list) {
                return Err(bad(
                    field,
                    s,
                    "each key once per list (this key is set twice; the later value would replace the earlier)",
                ));
            }
        }
        // The same variant twice would run its jobs once under two entries.
        for (field, variants) in std::iter::once(("variants", &self.variants))
            .chain(self.task_variants.values().map(|v| ("task_variants", v)))
        {
            let twice = variants
                .iter()
                .enumerate()
                .find(|(i, v)| variants[..*i].contains(v));
            if let Some((_, v)) = twice {
                return Err(bad(
                    field,
                    format!("[{}]", v.join(", ")),
                    "each variant once (this one is listed twice)",
                ));
            }
        }
        // Every variant setting must apply to some model of the sweep.
        let models = self.expanded_models();
        for task in &self.tasks {
            for s in self.variants_of(task).into_iter().flatten() {
                let used = models
                    .iter()
                    .any(|m| family_of(m).is_ok_and(|f| applies(f, task, m, &s)));
                if !used {
                    return Err(refusal(self, "variants", &s));
                }
            }
        }
        Ok(())
    }

    /// Model names after crossing bare recurrent kinds with `sizes`.
    pub fn expanded_models(&self) -> Vec<String> {
        let mut out = Vec::new();
        for m in &self.models {
            if matches!(
                m.as_str(),
                "lstm" | "gru" | "rnn" | "ctrnn" | "ctrnn-reservoir"
            ) {
                out.extend(self.sizes.iter().map(|h| format!("{m}{h}")));
            } else {
                out.push(m.clone());
            }
        }
        out
    }

    /// Variants of `task`: its task variants crossed with the global variants (one empty
    /// variant when there are none).
    fn variants_of(&self, task: &str) -> Vec<Vec<String>> {
        self.variant_parts(task)
            .into_iter()
            .map(|(l, g)| [l, g].concat())
            .collect()
    }

    /// `(task variant, global variant)` pairs of `task`.
    fn variant_parts(&self, task: &str) -> Vec<(Vec<String>, Vec<String>)> {
        let global: Vec<Vec<String>> = if self.variants.is_empty() {
            vec![vec![]]
        } else {
            self.variants.clone()
        };
        let local: Vec<Vec<String>> = match self.task_variants.get(task) {
            Some(v) if !v.is_empty() => v.clone(),
            _ => vec![vec![]],
        };
        local
            .iter()
            .flat_map(|l| global.iter().map(move |g| (l.clone(), g.clone())))
            .collect()
    }

    /// Every job, in a stable order (task, model, variant, seed). Each model takes the
    /// variant settings that apply to its family ([`applies`]: baselines only the task
    /// settings); the deterministic oracle runs one seed only.
    pub fn jobs(&self) -> Result<Vec<Job>, TrainError> {
        let crossed = [
            self.tasks.len(),
            self.expanded_models().len(),
            self.seeds.len(),
            self.variants.len().max(1),
            self.task_variants
                .values()
                .map(Vec::len)
                .max()
                .unwrap_or(1)
                .max(1),
        ]
        .iter()
        .try_fold(1usize, |acc, &n| acc.checked_mul(n))
        .unwrap_or(usize::MAX);
        if crossed > MAX_JOBS {
            return Err(bad(
                "seeds × models × tasks × variants",
                format!("{crossed} jobs"),
                &format!("at most {MAX_JOBS} jobs per sweep (split it into several sweeps)"),
            ));
        }
        let mut jobs = Vec::new();
        for task in &self.tasks {
            let variants = self.variant_parts(task);
            for model in self.expanded_models() {
                let family = family_of(&model)?;
                // Each model takes the variant settings that apply to it; variants that then
                // coincide are run once.
                let mut vs: Vec<(Vec<String>, Vec<String>)> = Vec::new();
                for (l, g) in &variants {
                    let keep = |v: &[String]| -> Vec<String> {
                        v.iter()
                            .filter(|s| applies(family, task, &model, s))
                            .cloned()
                            .collect()
                    };
                    let kept = (keep(l), keep(g));
                    if !vs.contains(&kept) {
                        vs.push(kept);
                    }
                }
                let seeds: &[u64] = if model == "oracle" {
                    &self.seeds[..1]
                } else {
                    &self.seeds
                };
                for (local, global) in &vs {
                    for &seed in seeds {
                        jobs.push(self.job(task, &model, family, (local, global), seed)?);
                    }
                }
            }
        }
        // Two entries that name one model (`lstm` with size 125 and `lstm125`) give one job
        // folder twice.
        if let Some(twice) = repeated_id(&jobs) {
            return Err(bad(
                "models",
                twice,
                "each job once (two entries of the sweep name this job)",
            ));
        }
        Ok(jobs)
    }

    /// The job of `model` on `task` with a task variant and a model variant (both already
    /// filtered to the settings that apply). The row label carries only the model variant's
    /// non-task settings: task conditions (e.g. FI TDs) share a leaderboard row.
    fn job(
        &self,
        task: &str,
        model: &str,
        family: Family,
        (local, global): (&[String], &[String]),
        seed: u64,
    ) -> Result<Job, TrainError> {
        let variant: Vec<String> = [local, global].concat();
        let variant = &variant[..];
        let mut sets: Vec<String> = Vec::new();
        let env_only = |v: &[String]| -> Vec<String> {
            v.iter()
                .filter(|s| s.starts_with("env."))
                .cloned()
                .collect()
        };
        match family {
            Family::DeepRl => {
                if let Some(s) = self.steps {
                    sets.push(format!("total_steps={s}"));
                }
                sets.extend(self.set.iter().cloned());
            }
            Family::Timing => {
                if let Some(e) = self.episodes {
                    sets.push(format!("episodes={e}"));
                }
                sets.extend(env_only(&self.set));
            }
            Family::Baseline => sets.extend(env_only(&self.set)),
        }
        sets.extend(variant.iter().cloned());
        let task_params: Vec<&str> = sets.iter().filter_map(|s| s.strip_prefix("env.")).collect();
        let label = variant_label(variant);
        let folder = if label.is_empty() {
            model.to_string()
        } else {
            format!("{model}~{label}")
        };
        let model_sets: Vec<String> = global
            .iter()
            .filter(|s| !s.starts_with("env."))
            .cloned()
            .collect();
        let row = if model_sets.is_empty() {
            model.to_string()
        } else {
            format!("{model}~{}", variant_label(&model_sets))
        };
        let id = format!("{task}/{folder}/seed{seed}");
        let mut chosen = Task::new(task)?;
        chosen.set_all(&task_params).map_err(|e| TrainError::Job {
            id: id.clone(),
            message: e.to_string(),
        })?;
        Ok(Job {
            id,
            task: chosen,
            model: model.into(),
            family,
            seed,
            sets,
            row,
        })
    }
}

/// Why no model of `sweep` accepts the setting `kv` of `field` (`set` or `variants`): the
/// range error of a model that knows the key, or else "unknown setting".
pub(crate) fn refusal(sweep: &SweepFile, field: &str, kv: &str) -> TrainError {
    let (k, v) = kv.split_once('=').unwrap_or((kv, ""));
    let (k, v) = (k.trim(), v.trim());
    for task in &sweep.tasks {
        let Ok(task) = Task::new(task) else {
            continue;
        };
        for m in sweep.expanded_models() {
            let family = family_of(&m);
            if field == "set" && !matches!(family, Ok(Family::DeepRl)) {
                continue;
            }
            let err = match family {
                Ok(Family::DeepRl) => m.parse().ok().and_then(|arch| {
                    chronocooked_training::ppo::config::TrainConfig::base(task.clone(), arch)
                        .set(k, v)
                        .err()
                }),
                Ok(Family::Timing) => {
                    chronocooked_training::timing_run::TimingRunConfig::new(&task, &m, 0)
                        .set(kv)
                        .err()
                }
                _ => None,
            };
            if let Some(TrainError::InvalidParam { field: f, .. }) = &err
                && f == k
            {
                return err.unwrap_or(TrainError::BadOverride(kv.into()));
            }
        }
    }
    let allowed = if field == "set" {
        "PPO settings some PPO model of the sweep accepts, or env.<task parameter> (`set` reaches PPO runs only; timing models take `episodes` and `variants`)"
    } else {
        "settings some model of the sweep accepts (PPO or timing-model settings, or env.<task parameter>)"
    };
    TrainError::InvalidParam {
        field: field.into(),
        value: kv.into(),
        allowed: allowed.into(),
    }
}
