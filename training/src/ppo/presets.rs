//! Hyperparameter presets keyed by task and model (RL Zoo style), shipped as TOML files
//! in `training/presets/` and compiled into the binary.

use crate::error::TrainError;
use crate::ppo::config::TrainConfig;
use chronocooked_models::Architecture;

/// Preset files: `(name, TOML text)`, one per `training/presets/<name>.toml` (sorted by
/// name; listed by the crate's build script); `common` applies to every task, every other
/// file is named by a task's id.
pub const PRESET_FILES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/presets.rs"));

/// Preset names.
pub const PRESETS: [&str; 2] = ["reference", "fast"];

fn value_string(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        toml::Value::Array(a) => a.iter().map(value_string).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

fn section_pairs(
    file: &str,
    text: &str,
    path: &[&str],
) -> Result<Vec<(String, String)>, TrainError> {
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| TrainError::PresetFile {
            file: file.to_string(),
            message: e.to_string(),
        })?;
    let mut cur = &table;
    for key in path {
        match cur.get(*key) {
            Some(toml::Value::Table(t)) => cur = t,
            _ => return Ok(Vec::new()),
        }
    }
    Ok(cur
        .iter()
        .filter(|(_, v)| !v.is_table())
        .map(|(k, v)| (k.clone(), value_string(v)))
        .collect())
}

/// The presets shared by every task (`presets/common.toml`).
fn common_presets() -> &'static str {
    PRESET_FILES
        .iter()
        .find(|(n, _)| *n == "common")
        .map_or("", |(_, text)| text)
}

/// The presets of registered task `task` (its id): the training crate's file of that name,
/// or the presets its family declares
/// ([`chronocooked_env::task::family::Family::preset`]). A task with neither is an error
/// naming it, never trained on the common budget alone.
fn task_presets(task: &str) -> Result<&'static str, TrainError> {
    if let Some((_, text)) = PRESET_FILES.iter().find(|(n, _)| *n == task) {
        return Ok(text);
    }
    chronocooked_env::task::family::declared_preset(task).ok_or_else(|| TrainError::PresetFile {
        file: format!("{task}.toml"),
        message: format!(
            "task {task} has no presets: add training/presets/{task}.toml or declare them in its family (Family::preset)"
        ),
    })
}

/// The `key=value` settings of `preset` for `task` and `model`, in application order
/// (per file — common, then the task's: `[preset]`, `[preset.feedforward|recurrent]`,
/// `[preset.<core kind>]` (e.g. `[fast.ctrnn]`), `[preset.<model name>]` (e.g.
/// `[reference.lstm125]`)).
pub fn preset_settings(
    task: &str,
    model: Architecture,
    preset: &str,
) -> Result<Vec<(String, String)>, TrainError> {
    if !PRESETS.contains(&preset) {
        return Err(TrainError::UnknownPreset {
            name: preset.to_string(),
            allowed: PRESETS.join(", "),
        });
    }
    let kind = if model.is_recurrent() {
        "recurrent"
    } else {
        "feedforward"
    };
    let name = model.name();
    let mut out = Vec::new();
    for (f, text) in [("common", common_presets()), (task, task_presets(task)?)] {
        let core = model.core.map(|k| k.name());
        for path in [
            vec![preset],
            vec![preset, kind],
            core.map_or_else(Vec::new, |k| vec![preset, k]),
            vec![preset, name.as_str()],
        ] {
            if path.is_empty() {
                continue;
            }
            out.extend(section_pairs(f, text, &path)?);
        }
    }
    Ok(out)
}

/// A resolved configuration: base defaults, then the preset, then `sets` (`key=value`).
pub fn resolve<S: AsRef<str>>(
    task: &str,
    model: Architecture,
    preset: &str,
    seed: u64,
    sets: &[S],
) -> Result<TrainConfig, TrainError> {
    let mut cfg = TrainConfig::base(chronocooked_env::Task::new(task)?, model);
    cfg.preset = preset.to_string();
    for (k, v) in preset_settings(task, model, preset)? {
        cfg.set(&k, &v)?;
    }
    cfg.seed = seed;
    cfg.apply_overrides(sets)?;
    cfg.validate()?;
    Ok(cfg)
}
