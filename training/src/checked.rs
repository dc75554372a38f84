//! Checked configurations (linfa's `ParamGuard` pattern): a configuration is checked once,
//! by [`Check::check`], into a [`Checked`] value, and what runs a configuration (the PPO
//! trainer, `run_training`) takes only a [`Checked`] one, so an unchecked configuration —
//! one built in code, edited by hand or read from an older run folder — cannot start a run.

use serde::Serialize;
use std::ops::Deref;

/// A configuration that passed its [`Check::validate`]. Read it through `Deref`; take it
/// apart with [`Checked::into_inner`] (changing it means checking it again).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(transparent)]
pub struct Checked<T>(T);

impl<T> Checked<T> {
    /// The checked configuration, no longer marked as checked.
    pub fn into_inner(self) -> T {
        self.0
    }
}

impl<T> Deref for Checked<T> {
    type Target = T;

    fn deref(&self) -> &T {
        &self.0
    }
}

/// A configuration with one check of every value and every cross-field rule.
pub trait Check: Sized {
    /// The check's error (naming the field and the allowed values).
    type Error;

    /// Checks every setting against its rule and the cross-field constraints.
    fn validate(&self) -> Result<(), Self::Error>;

    /// The configuration, checked.
    fn check(self) -> Result<Checked<Self>, Self::Error> {
        self.validate()?;
        Ok(Checked(self))
    }
}
