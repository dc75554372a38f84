//! Settings: the `--set key=value` keys of every trainable model, declared once per
//! configuration struct as a table of [`Spec`]s (key, place in the struct's serialised form,
//! accepted values, meaning).
//!
//! One table serves everything that names a setting: `--set` writes the parsed value into
//! the struct's serialised form (`serde_json::Value`) and deserialises it back (the structs
//! deny unknown fields), [`check`] is the one range check of a configuration however it was
//! made, [`listing`] is what `zoo show` prints and what error messages offer, and
//! [`markdown_table`] is the README's table. Keys are flat (`gamma`, not `ppo.gamma`): the
//! table maps each to its path.
//!
//! Tables: [`ppo::PPO_SETTINGS`] (deep-RL runs, [`crate::TrainConfig`]) and
//! [`timing::TIMING_SETTINGS`] (timing-model runs, [`crate::TimingRunConfig`]).

pub mod ppo;
pub mod timing;

use crate::error::TrainError;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

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
    /// Comma-separated values of the inner rule.
    List(&'static Rule),
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
            Rule::List(inner) => Value::Array(
                text.split(',')
                    .map(|x| inner.parse(x))
                    .collect::<Option<_>>()?,
            ),
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

/// The spec of `key` (or of one of its aliases).
pub fn find<'a>(specs: &'a [Spec], key: &str) -> Option<&'a Spec> {
    specs
        .iter()
        .find(|s| s.key == key || s.aliases.contains(&key))
}

/// Whether `config` has the setting `key` (an alias counts).
pub fn has<T: Serialize>(specs: &[Spec], config: &T, key: &str) -> bool {
    find(specs, key).is_some_and(|s| get(&to_value(config), s.path).is_some())
}

/// The keys `config` has, comma-separated (what an unknown-key error offers).
pub fn keys<T: Serialize>(specs: &[Spec], config: &T) -> String {
    let v = to_value(config);
    specs
        .iter()
        .filter(|s| get(&v, s.path).is_some())
        .map(|s| s.key)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The error for a key no spec has: it lists the keys `config` has (`extra`: keys handled
/// outside the table, such as `env.<task parameter>`).
pub fn unknown<T: Serialize>(specs: &[Spec], config: &T, key: &str, extra: &str) -> TrainError {
    TrainError::UnknownKey {
        key: key.into(),
        allowed: format!("{}, {extra}", keys(specs, config)),
    }
}

/// Writes `value` into `config`'s field `spec.path` (after [`Rule::parse`]) through the
/// serialised form; errors name the key and what it accepts.
pub fn set_field<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
) -> Result<(), TrainError> {
    let bad = || TrainError::param(key, value, &spec.rule.allowed());
    let parsed = spec.rule.parse(value).ok_or_else(bad)?;
    set_value(config, spec, key, value, parsed)
}

/// Writes an already serialised value into `config`'s field `spec.path`.
pub fn set_value<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
    parsed: Value,
) -> Result<(), TrainError> {
    let mut v = to_value(config);
    let Some(slot) = get_mut(&mut v, spec.path) else {
        return Err(TrainError::param(
            key,
            value,
            &format!(
                "only with {}",
                spec.only_with.unwrap_or("another configuration")
            ),
        ));
    };
    *slot = parsed;
    *config = serde_json::from_value(v)
        .map_err(|e| TrainError::param(key, value, &format!("{} ({e})", spec.rule.allowed())))?;
    Ok(())
}

/// The one range check: every field of `config` that has a spec holds a value its rule
/// accepts (an unset option always does). The error names the key.
pub fn check<T: Serialize>(specs: &[Spec], config: &T) -> Result<(), TrainError> {
    let v = to_value(config);
    for s in specs {
        if let Some(x) = get(&v, s.path)
            && !x.is_null()
            && !s.rule.accepts(x)
        {
            return Err(TrainError::param(s.key, display(x), &s.rule.allowed()));
        }
    }
    Ok(())
}

/// Every setting `config` has, in table order, with its current value.
pub fn listing<T: Serialize>(specs: &[Spec], config: &T) -> Vec<Setting> {
    let v = to_value(config);
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
    let mut out = String::from(
        "| key | type | default | allowed | meaning |\n|-----|------|---------|---------|---------|\n",
    );
    for s in settings {
        out += &format!(
            "| `{}` | {} | `{}` | {} | {} |\n",
            s.key,
            s.kind,
            s.value,
            s.allowed.replace('|', "\\|"),
            s.doc.replace('|', "\\|")
        );
    }
    out
}

/// A setting of `key` at `path` in the serialised configuration, accepted by `rule`, with
/// no aliases and no restriction to other settings' values.
pub(crate) const fn spec(
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
