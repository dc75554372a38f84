//! [`Task`]: a registered task and its parameters as run configurations, sweep jobs,
//! evaluation conditions and recordings carry them — the task id and the typed values of
//! the parameters set on it, each checked by its entry in the family's table ([`params`]).
//!
//! `key=value` text is read once, where it enters (the CLI, sweep files, Python), by the
//! table ([`Task::set`]); from there on the task travels typed.

use super::{Task, TaskConfig, TaskFamily};
use crate::error::EnvError;
use crate::registry::find_task;
use crate::settings::{self, Spec};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::fmt;

impl Task {
    /// The registered task `id` (an id or its alias, e.g. `fixedinterval`) with its defaults.
    pub fn new(id: &str) -> Result<Self, EnvError> {
        Ok(Task {
            id: id.to_string(),
            config: find_task(id)?.default_config(),
            set: Vec::new(),
        })
    }

    /// `id` with `key=value` overrides applied in order (keys or the reference's aliases),
    /// then checked as a whole.
    pub fn parse<S: AsRef<str>>(id: &str, overrides: &[S]) -> Result<Self, EnvError> {
        let mut task = Self::new(id)?;
        task.set_all(overrides)?;
        task.config()?;
        Ok(task)
    }

    /// This task with more `key=value` overrides applied (a later value of a key replaces
    /// the earlier one), checked as a whole.
    pub fn with<S: AsRef<str>>(&self, overrides: &[S]) -> Result<Self, EnvError> {
        let mut task = self.clone();
        task.set_all(overrides)?;
        task.config()?;
        Ok(task)
    }

    /// This task with its growing parameter at `size` (a curriculum level; see
    /// [`TaskConfig::growth`]), recorded as set. Errors for a task that
    /// does not grow.
    pub fn at_growth_size(&self, size: usize) -> Result<Self, EnvError> {
        let growth = self.config()?.growth().ok_or_else(|| {
            EnvError::param(
                "curriculum",
                self.to_string(),
                "a task that grows (multi-anchor counters, multi-oven ovens)",
            )
        })?;
        self.with_values(&[(growth.key, Value::from(size))])
    }

    /// Applies `key=value` overrides in order; each is checked by its rule, the whole by
    /// [`Task::config`].
    pub fn set_all<S: AsRef<str>>(&mut self, overrides: &[S]) -> Result<(), EnvError> {
        for text in overrides {
            let text = text.as_ref();
            let (key, value) = text.split_once('=').ok_or_else(|| EnvError::BadOverride {
                text: text.to_string(),
                reason: "expected key=value".into(),
            })?;
            self.set(key, value)?;
        }
        Ok(())
    }

    /// Sets one parameter (key or alias) from its text, parsed and range-checked by its
    /// table entry (the edge where `key=value` text enters).
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), EnvError> {
        let table = self.table();
        let i = index_of(&table, key.trim()).ok_or_else(|| self.unknown(key, &table))?;
        let spec = &table[i];
        let parsed = spec
            .rule
            .parse(value)
            .ok_or_else(|| EnvError::param(spec.key, value, spec.rule.allowed()))?;
        self.set_value(key, parsed)
    }

    /// Sets one parameter (key or alias) to a typed value (as `env` maps hold them),
    /// checked by its rule. A field that the change moves too (a multi-timer's active count
    /// after a shorter TD list) is recorded as set, so the recorded values rebuild this task
    /// exactly.
    pub fn set_value(&mut self, key: &str, value: Value) -> Result<(), EnvError> {
        let table = self.table();
        let index = index_of(&table, key.trim()).ok_or_else(|| self.unknown(key, &table))?;
        let before = settings::values(&table, &self.config);
        self.config.set_value(key, value)?;
        let after = settings::values(&table, &self.config);
        for (i, (was, now)) in before.into_iter().zip(after).enumerate() {
            if let Some(now) = now
                && (i == index || was.as_ref() != Some(&now))
            {
                self.record(i, now);
            }
        }
        Ok(())
    }

    /// This task with typed parameter values applied in order (`[("ovens", json!(1))]`),
    /// checked as a whole: how probes, curricula and human play edit a task.
    pub fn with_values(&self, values: &[(&str, Value)]) -> Result<Self, EnvError> {
        let mut task = self.clone();
        for (key, value) in values {
            task.set_value(key, value.clone())?;
        }
        task.config()?;
        Ok(task)
    }

    /// The task a configuration plays, typed: its registry id with every table parameter
    /// whose value differs from the registered default recorded as set (so
    /// [`Task::overrides`] and the `env` map name exactly what was changed). A configuration
    /// with a difference no parameter expresses (a hand-edited layout, say) is refused,
    /// naming the task, rather than rebuilt as another one.
    pub fn from_config(config: &TaskConfig) -> Result<Self, EnvError> {
        let mut task = Self::new(&config.id)?;
        let table = task.table();
        let defaults = settings::values(&table, &task.config);
        let played = settings::values(&table, config);
        for (spec, (default, value)) in table.iter().zip(defaults.into_iter().zip(played)) {
            if let Some(value) = value
                && default.as_ref() != Some(&value)
            {
                task.set_value(spec.key, value)?;
            }
        }
        if &task.config != config {
            return Err(EnvError::BadOverride {
                text: config.id.clone(),
                reason: "the configuration differs from the registered task in a field that \
                         no task parameter sets (its layout or a derived field)"
                    .into(),
            });
        }
        task.config()?;
        Ok(task)
    }

    /// The task id as given.
    pub fn id(&self) -> &str {
        &self.id
    }

    /// The task family.
    pub fn family(&self) -> TaskFamily {
        self.config.family()
    }

    /// The configuration the env runs, checked as a whole (every range, the cross-field
    /// rules, the layout).
    pub fn config(&self) -> Result<TaskConfig, EnvError> {
        self.config.validate()?;
        Ok(self.config.clone())
    }

    /// The configuration before the whole is checked (for reading a parameter of a task
    /// that [`Task::config`] accepted).
    pub fn unchecked_config(&self) -> &TaskConfig {
        &self.config
    }

    /// Whether no parameter was set (the registered defaults).
    pub fn is_default(&self) -> bool {
        self.set.is_empty()
    }

    /// The parameters set, as `key=value` texts in table order (canonical keys): what the
    /// CLI and Python take, and what tables and job labels print.
    pub fn overrides(&self) -> Vec<String> {
        let table = self.table();
        self.set
            .iter()
            .map(|(i, v)| format!("{}={}", table[*i].key, settings::display(v)))
            .collect()
    }

    /// Every parameter set, as `(key, value)` in table order.
    pub fn values_set(&self) -> Vec<(&'static str, &Value)> {
        let table = self.table();
        self.set.iter().map(|(i, v)| (table[*i].key, v)).collect()
    }

    /// The value set for `key` (canonical key or alias), if it was set.
    pub fn value_set(&self, key: &str) -> Option<&Value> {
        let i = index_of(&self.table(), key)?;
        self.set.iter().find(|(j, _)| *j == i).map(|(_, v)| v)
    }

    fn table(&self) -> Vec<Spec> {
        self.config.params_table()
    }

    fn record(&mut self, index: usize, value: Value) {
        match self.set.binary_search_by_key(&index, |(i, _)| *i) {
            Ok(at) => self.set[at].1 = value,
            Err(at) => self.set.insert(at, (index, value)),
        }
    }

    fn unknown(&self, key: &str, table: &[Spec]) -> EnvError {
        EnvError::UnknownParam {
            key: key.to_string(),
            task: self.config.id.clone(),
            known: table.iter().map(|p| p.key).collect::<Vec<_>>().join(", "),
        }
    }
}

/// Default config of `id` with `key=value` overrides applied and validated (text where it
/// enters: [`Task::set_all`] then [`Task::config`]).
pub fn make_config<S: AsRef<str>>(id: &str, overrides: &[S]) -> Result<TaskConfig, EnvError> {
    let mut task = Task::new(id)?;
    task.set_all(overrides)?;
    task.config()
}

fn index_of(table: &[Spec], key: &str) -> Option<usize> {
    let spec = settings::find(table, key)?;
    table.iter().position(|s| s.key == spec.key)
}

impl fmt::Display for Task {
    /// `FixedInterval-v0` or `FixedInterval-v0 td=6 max_timesteps=300`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.id)?;
        for o in self.overrides() {
            write!(f, " {o}")?;
        }
        Ok(())
    }
}

/// The serialised form of a [`Task`].
#[derive(Serialize, Deserialize)]
pub(super) struct TaskFields {
    task: String,
    #[serde(default)]
    env: EnvFields,
}

/// A task's parameters on disk: a map of typed values, or (written before the map) a list
/// of `key=value` texts.
#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum EnvFields {
    Typed(Map<String, Value>),
    Texts(Vec<String>),
}

impl Default for EnvFields {
    fn default() -> Self {
        EnvFields::Typed(Map::new())
    }
}

impl TryFrom<TaskFields> for Task {
    type Error = EnvError;

    fn try_from(fields: TaskFields) -> Result<Self, EnvError> {
        let mut task = Task::new(&fields.task)?;
        match fields.env {
            EnvFields::Typed(map) => {
                for (key, value) in map {
                    task.set_value(&key, value)?;
                }
            }
            EnvFields::Texts(texts) => task.set_all(&texts)?,
        }
        Ok(task)
    }
}

impl From<Task> for TaskFields {
    fn from(task: Task) -> Self {
        let table = task.table();
        let env = task
            .set
            .into_iter()
            .map(|(i, v)| (table[i].key.to_string(), v))
            .collect();
        TaskFields {
            task: task.id,
            env: EnvFields::Typed(env),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_task_reads_back_equal_from_its_json_and_from_the_older_text_list() {
        let task = Task::parse("Bisection-v0", &["long=16", "short=5", "max_steps=300"]).unwrap();
        let json = serde_json::to_string(&task).unwrap();
        assert_eq!(
            json,
            r#"{"task":"Bisection-v0","env":{"long":16,"max_timesteps":300,"short":5}}"#
        );
        assert_eq!(serde_json::from_str::<Task>(&json).unwrap(), task);
        let old = r#"{"task":"Bisection-v0","env":["short=5","long=16","max_steps=300"]}"#;
        assert_eq!(serde_json::from_str::<Task>(old).unwrap(), task);
        assert_eq!(
            task.overrides(),
            ["short=5", "long=16", "max_timesteps=300"],
            "table order, canonical keys"
        );
    }

    #[test]
    fn values_are_checked_by_their_rule_when_set_and_when_read() {
        let mut task = Task::new("FixedInterval-v0").unwrap();
        let err = task.set("td", "0").unwrap_err().to_string();
        assert!(err.contains("td") && err.contains("1..=10000"), "{err}");
        let err = serde_json::from_str::<Task>(r#"{"task":"FixedInterval-v0","env":{"td":"6"}}"#)
            .unwrap_err()
            .to_string();
        assert!(err.contains("td"), "{err}");
        let err = serde_json::from_str::<Task>(r#"{"task":"FixedInterval-v0","env":{"tdd":6}}"#)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("tdd") && err.contains("max_timesteps"),
            "{err}"
        );
    }

    #[test]
    fn cross_field_rules_wait_for_the_whole_task() {
        // S = 20 is out of order with the default L = 12 until L is set too.
        let mut task = Task::new("Bisection-v0").unwrap();
        task.set("short", "20").unwrap();
        assert!(task.config().is_err());
        task.set("long", "40").unwrap();
        let config = task.config().unwrap();
        assert_eq!(
            config.params,
            super::super::TaskParams::Bisection {
                short: 20,
                long: 40
            }
        );
    }

    #[test]
    fn a_field_moved_by_another_is_recorded_so_the_json_rebuilds_the_task() {
        let task = Task::parse("MultiTimer-v0", &["num_timers=4", "tds=6,9"]).unwrap();
        let back: Task = serde_json::from_str(&serde_json::to_string(&task).unwrap()).unwrap();
        assert_eq!(back, task);
        assert_eq!(back.config().unwrap(), task.config().unwrap());
    }

    #[test]
    fn an_alias_is_recorded_under_its_key_and_a_later_value_replaces_the_earlier() {
        let task = Task::parse("FixedInterval-v0", &["oven_duration=6"]).unwrap();
        let task = task.with(&["td=9"]).unwrap();
        assert_eq!(task.overrides(), ["td=9"]);
        assert_eq!(task.to_string(), "FixedInterval-v0 td=9");
    }
}
