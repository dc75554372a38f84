//! Settings: the `--set key=value` keys of every trainable model, declared once per
//! configuration struct as a table of [`Spec`]s (key, place in the struct's serialised form,
//! accepted values, meaning). The table machinery is the env crate's
//! ([`chronocooked_env::settings`]), which the task parameters use too.
//!
//! One table serves everything that names a setting: `--set` writes the parsed value into
//! the struct's serialised form (`serde_json::Value`) and deserialises it back (the structs
//! deny unknown fields), [`check`] is the one range check of a configuration however it was
//! made, [`listing`] is what `zoo show` prints and what error messages offer, and
//! [`markdown_table`] is the guide's table (docs/). Keys are flat (`gamma`, not `ppo.gamma`): the
//! table maps each to its path.
//!
//! Tables: [`ppo::PPO_SETTINGS`] (deep-RL runs, [`crate::TrainConfig`]) and
//! [`timing::TIMING_SETTINGS`] (timing-model runs, [`crate::TimingRunConfig`]).

pub mod ppo;
pub mod timing;

use crate::error::TrainError;
use chronocooked_env::settings as table;
pub use chronocooked_env::settings::{
    COUNT, NON_NEGATIVE, POSITIVE, POSITIVE_COUNT, Rule, Setting, SettingError, Spec, UNIT,
    display, find, has, keys, listing, markdown_table, non_negative, spec,
};
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;

impl From<SettingError> for TrainError {
    fn from(e: SettingError) -> Self {
        TrainError::param(&e.key, e.value, &e.allowed)
    }
}

/// The error for a key no spec has: it lists the keys `config` has (`extra`: keys handled
/// outside the table, such as `env.<task parameter>`).
pub fn unknown<T: Serialize>(specs: &[Spec], config: &T, key: &str, extra: &str) -> TrainError {
    TrainError::UnknownKey {
        key: key.into(),
        allowed: format!("{}, {extra}", keys(specs, config)),
    }
}

/// [`chronocooked_env::settings::set_field`] with the training crate's error.
pub fn set_field<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
) -> Result<(), TrainError> {
    Ok(table::set_field(config, spec, key, value)?)
}

/// [`chronocooked_env::settings::set_value`] with the training crate's error.
pub fn set_value<T: Serialize + DeserializeOwned>(
    config: &mut T,
    spec: &Spec,
    key: &str,
    value: &str,
    parsed: Value,
) -> Result<(), TrainError> {
    Ok(table::set_value(config, spec, key, value, parsed)?)
}

/// [`chronocooked_env::settings::check`] with the training crate's error.
pub fn check<T: Serialize>(specs: &[Spec], config: &T) -> Result<(), TrainError> {
    Ok(table::check(specs, config)?)
}
