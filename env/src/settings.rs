//! Settings tables: the `key=value` parameters of a configuration struct, declared once as
//! a table of [`Spec`]s (key, aliases, place in the struct's serialised form, accepted
//! values, meaning).
//!
//! One table serves everything that names a setting: [`set_field`] writes a parsed value
//! into the struct's serialised form (`serde_json::Value`) and deserialises it back,
//! [`check`] is the one range check of a configuration however it was made, [`listing`] is
//! what `env list` / `zoo show` print and what error messages offer, and [`markdown_table`]
//! is the README's table. Keys are flat (`short`, not `params.short`): the table maps each
//! to its path. The task parameters ([`crate::task::params`]) and the training settings of
//! the training crate are tables of this one kind.

use crate::markdown::Table;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use thiserror::Error;

/// A value that a setting does not accept (or a setting the configuration lacks).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("invalid value for `{key}`: {value} (allowed: {allowed})")]
pub struct SettingError {
    /// The key as given.
    pub key: String,
    /// The rejected value, as text.
    pub value: String,
    /// What is accepted, in words.
    pub allowed: String,
}

impl SettingError {
    /// An error naming `key`, the rejected `value` and what is `allowed`.
    pub fn new(key: &str, value: impl ToString, allowed: impl Into<String>) -> Self {
        SettingError {
            key: key.to_string(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

/// The values one setting accepts.
#[derive(Debug, Clone, Copy)]
pub enum Rule {
    /// An integer in `lo..=hi`.
    Int {
        /// Smallest value.
        lo: u64,
        /// Largest value.
        hi: u64,
    },
    /// A finite number passing `ok`; `allowed` says which in words.
    Num {
        /// The range check.
        ok: fn(f64) -> bool,
        /// The range in words (`number in [0, 1]`).
        allowed: &'static str,
    },
    /// `true` or `false`.
    Bool,
    /// One of these names.
    Choice(&'static [&'static str]),
    /// Any text.
    Text,
    /// `none` (or empty) for "unset", else the inner rule.
    Optional(&'static Rule),
    /// Comma-separated values of the inner rule (surrounding `[` `]` are allowed).
    List(&'static Rule),
    /// The inner rule, after replacing whole-value synonyms (`never` → `0`): the names are
    /// listed with the accepted values, so nothing is accepted that the docs do not say.
    Mapped {
        /// The rule the mapped text must pass.
        inner: &'static Rule,
        /// `(synonym, value)` pairs.
        synonyms: &'static [(&'static str, &'static str)],
    },
}

impl Rule {
    /// The accepted values in words (what error messages and tables print).
    pub fn allowed(&self) -> String {
        match self {
            Rule::Int { lo, hi } if *hi == u64::MAX => format!("integer >= {lo}"),
            Rule::Int { lo, hi } => format!("integer {lo}..={hi}"),
            Rule::Num { allowed, .. } => (*allowed).to_string(),
            Rule::Bool => "true or false".into(),
            Rule::Choice(names) => names.join("|"),
            Rule::Text => "text".into(),
            Rule::Optional(inner) => format!("none, or {}", inner.allowed()),
            Rule::List(inner) => format!("comma-separated list of {}", inner.allowed()),
            Rule::Mapped { inner, synonyms } => {
                let names: Vec<String> =
                    synonyms.iter().map(|(s, v)| format!("{s} = {v}")).collect();
                format!("{} (also {})", inner.allowed(), names.join(", "))
            }
        }
    }

    /// The value type in one word (`integer`, `number`, `bool`, `choice`, `text`,
    /// `optional number`, `list of number`).
    pub fn kind(&self) -> String {
        match self {
            Rule::Int { .. } => "integer".into(),
            Rule::Num { .. } => "number".into(),
            Rule::Bool => "bool".into(),
            Rule::Choice(_) => "choice".into(),
            Rule::Text => "text".into(),
            Rule::Optional(inner) => format!("optional {}", inner.kind()),
            Rule::List(inner) => format!("list of {}", inner.kind()),
            Rule::Mapped { inner, .. } => inner.kind(),
        }
    }

    /// Parses the text of a `--set` value into its serialised form; `None` when it is not a
    /// value of this rule (type or range).
    pub fn parse(&self, text: &str) -> Option<Value> {
        let text = text.trim();
        let value = match self {
            Rule::Int { .. } => Value::from(text.parse::<u64>().ok()?),
            Rule::Num { .. } => Value::from(text.parse::<f64>().ok()?),
            Rule::Bool => Value::Bool(text.parse().ok()?),
            Rule::Choice(_) | Rule::Text => Value::String(text.into()),
            Rule::Optional(inner) => match text {
                "none" | "null" | "" => Value::Null,
                _ => inner.parse(text)?,
            },
            Rule::List(inner) => {
                let text = text.strip_prefix('[').unwrap_or(text);
                let text = text.strip_suffix(']').unwrap_or(text);
                Value::Array(
                    text.split(',')
                        .map(|x| inner.parse(x))
                        .collect::<Option<_>>()?,
                )
            }
            Rule::Mapped { inner, synonyms } => {
                let lower = text.to_ascii_lowercase();
                let mapped = synonyms
                    .iter()
                    .find(|(s, _)| *s == lower)
                    .map_or(text, |(_, v)| *v);
                inner.parse(mapped)?
            }
        };
        self.accepts(&value).then_some(value)
    }

    /// Whether a serialised value lies in this rule's range.
    pub fn accepts(&self, value: &Value) -> bool {
        match (self, value) {
            (Rule::Int { lo, hi }, v) => v.as_u64().is_some_and(|x| (*lo..=*hi).contains(&x)),
            (Rule::Num { ok, .. }, v) => v.as_f64().is_some_and(|x| x.is_finite() && ok(x)),
            (Rule::Bool, v) => v.is_boolean(),
            (Rule::Choice(names), Value::String(s)) => names.contains(&s.as_str()),
            (Rule::Text, v) => v.is_string(),
            (Rule::Optional(_), Value::Null) => true,
            (Rule::Optional(inner), v) => inner.accepts(v),
            (Rule::List(inner), Value::Array(items)) => items.iter().all(|x| inner.accepts(x)),
            (Rule::Mapped { inner, .. }, v) => inner.accepts(v),
            _ => false,
        }
    }
}

fn unit(x: f64) -> bool {
    (0.0..=1.0).contains(&x)
}
fn positive(x: f64) -> bool {
    x > 0.0
}
/// Whether `x >= 0` (the range of costs and noise levels).
pub fn non_negative(x: f64) -> bool {
    x >= 0.0
}

/// A number in `[0, 1]`.
pub const UNIT: Rule = Rule::Num {
    ok: unit,
    allowed: "number in [0, 1]",
};
/// A finite number `> 0`.
pub const POSITIVE: Rule = Rule::Num {
    ok: positive,
    allowed: "number > 0",
};
/// A finite number `>= 0`.
pub const NON_NEGATIVE: Rule = Rule::Num {
    ok: non_negative,
    allowed: "number >= 0",
};
/// Any integer `>= 0`.
pub const COUNT: Rule = Rule::Int {
    lo: 0,
    hi: u64::MAX,
};
/// Any integer `>= 1`.
pub const POSITIVE_COUNT: Rule = Rule::Int {
    lo: 1,
    hi: u64::MAX,
};

/// One setting: its `--set` key and where it lives in the configuration's serialised form.
#[derive(Debug, Clone, Copy)]
pub struct Spec {
    /// The `--set` key.
    pub key: &'static str,
    /// Other names accepted for the key (`lr` for `learning_rate`).
    pub aliases: &'static [&'static str],
    /// Path of the field in the serialised configuration (`["ppo", "gamma"]`).
    pub path: &'static [&'static str],
    /// Accepted values.
    pub rule: Rule,
    /// Meaning (with units).
    pub doc: &'static str,
    /// When the field exists only in some configurations (a curriculum's parameters, a
    /// model family's timer): the condition in words, for the error when it is absent.
    pub only_with: Option<&'static str>,
}

/// One setting as a configuration holds it (a row of `zoo show` and of the README tables).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Setting {
    /// The `--set` key.
    pub key: String,
    /// Value type (`integer`, `number`, …).
    #[serde(rename = "type")]
    pub kind: String,
    /// The current value as `--set` takes it (`none` for an unset option).
    pub value: String,
    /// Accepted values in words.
    pub allowed: String,
    /// Meaning (with units).
    pub doc: String,
}

fn get<'a>(value: &'a Value, path: &[&str]) -> Option<&'a Value> {
    path.iter().try_fold(value, |v, k| v.as_object()?.get(*k))
}

fn get_mut<'a>(value: &'a mut Value, path: &[&str]) -> Option<&'a mut Value> {
    path.iter()
        .try_fold(value, |v, k| v.as_object_mut()?.get_mut(*k))
}

/// A serialised value as `--set` writes it (`none`, `0.95,0.9`, `lab`, `0.0003`).
pub fn display(value: &Value) -> String {
    match value {
        Value::Null => "none".into(),
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(display).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

/// The serialised form of a configuration, read back from its JSON text (as `config.json`
/// holds it: an `f32` field reads `0.99`, not its `f64` widening).
fn to_value<T: Serialize>(config: &T) -> Value {
    let text = serde_json::to_string(config).expect("configurations serialise to JSON");
    serde_json::from_str(&text).expect("JSON text parses")
}

/// The serialised form with every optional setting that it omits written as `null`.
fn value_of<T: Serialize>(specs: &[Spec], config: &T) -> Value {
    let mut v = to_value(config);
    for s in specs {
        if matches!(s.rule, Rule::Optional(_)) {
            insert_missing_null(&mut v, s.path);
        }
    }
    v
}

/// The spec of `key` (or of one of its aliases).
pub fn find<'a>(specs: &'a [Spec], key: &str) -> Option<&'a Spec> {
    specs
        .iter()
        .find(|s| s.key == key || s.aliases.contains(&key))
}

/// Whether `config` has the setting `key` (an alias counts).
pub fn has<T: Serialize>(specs: &[Spec], config: &T, key: &str) -> bool {
    find(specs, key).is_some_and(|s| get(&value_of(specs, config), s.path).is_some())
}

/// The keys `config` has, comma-separated (what an unknown-key error offers).
pub fn keys<T: Serialize>(specs: &[Spec], config: &T) -> String {
    let v = value_of(specs, config);
    specs
        .iter()
        .filter(|s| get(&v, s.path).is_some())
        .map(|s| s.key)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Writes `value` into `config`'s field `spec.path` (after [`Rule::parse`]) through the
/// serialised form; errors name the key and what it accepts.
pub fn set_field<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
) -> Result<(), SettingError> {
    let parsed = spec
        .rule
        .parse(value)
        .ok_or_else(|| SettingError::new(key, value, spec.rule.allowed()))?;
    set_value(config, spec, key, value, parsed)
}

/// Writes an already serialised value into `config`'s field `spec.path`. An optional field
/// that the serialised form omits (`skip_serializing_if = "Option::is_none"`) counts as
/// present.
pub fn set_value<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
    parsed: Value,
) -> Result<(), SettingError> {
    let mut v = to_value(config);
    if matches!(spec.rule, Rule::Optional(_)) {
        insert_missing_null(&mut v, spec.path);
    }
    let Some(slot) = get_mut(&mut v, spec.path) else {
        return Err(SettingError::new(
            key,
            value,
            format!(
                "only with {}",
                spec.only_with.unwrap_or("another configuration")
            ),
        ));
    };
    *slot = parsed;
    *config = serde_json::from_value(v)
        .map_err(|e| SettingError::new(key, value, format!("{} ({e})", spec.rule.allowed())))?;
    Ok(())
}

fn insert_missing_null(value: &mut Value, path: &[&str]) {
    let Some((last, parent)) = path.split_last() else {
        return;
    };
    if let Some(obj) = get_mut(value, parent).and_then(Value::as_object_mut) {
        obj.entry(*last).or_insert(Value::Null);
    }
}

/// The one range check: every field of `config` that has a spec holds a value its rule
/// accepts (an unset option always does). The error names the key.
pub fn check<T: Serialize>(specs: &[Spec], config: &T) -> Result<(), SettingError> {
    let v = to_value(config);
    for s in specs {
        if let Some(x) = get(&v, s.path)
            && !x.is_null()
            && !s.rule.accepts(x)
        {
            return Err(SettingError::new(s.key, display(x), s.rule.allowed()));
        }
    }
    Ok(())
}

/// The serialised value of every spec's field in `config`, in table order (`None` where
/// the configuration lacks the field; an unset option is `Some(Null)`).
pub fn values<T: Serialize>(specs: &[Spec], config: &T) -> Vec<Option<Value>> {
    let v = value_of(specs, config);
    specs.iter().map(|s| get(&v, s.path).cloned()).collect()
}

/// Every setting `config` has, in table order, with its current value.
pub fn listing<T: Serialize>(specs: &[Spec], config: &T) -> Vec<Setting> {
    let v = value_of(specs, config);
    specs
        .iter()
        .filter_map(|s| {
            get(&v, s.path).map(|x| Setting {
                key: s.key.into(),
                kind: s.rule.kind(),
                value: display(x),
                allowed: s.rule.allowed(),
                doc: s.doc.into(),
            })
        })
        .collect()
}

/// A Markdown table of settings (key, type, default, accepted values, meaning).
pub fn markdown_table(settings: &[Setting]) -> String {
    let mut table = Table::new(["key", "type", "default", "allowed", "meaning"]);
    for s in settings {
        table.row([
            format!("`{}`", s.key),
            s.kind.clone(),
            format!("`{}`", s.value),
            s.allowed.clone(),
            s.doc.clone(),
        ]);
    }
    table.render()
}

/// A setting of `key` at `path` in the serialised configuration, accepted by `rule`, with
/// no aliases and no restriction to other settings' values.
pub const fn spec(
    key: &'static str,
    path: &'static [&'static str],
    rule: Rule,
    doc: &'static str,
) -> Spec {
    Spec {
        key,
        aliases: &[],
        path,
        rule,
        doc,
        only_with: None,
    }
}
