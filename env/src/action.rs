//! The six discrete actions of the reference environment.

use crate::error::EnvError;
use serde::{Deserialize, Serialize};
use strum::IntoStaticStr;

/// One agent action; the discriminant is the reference action code (`Discrete(6)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, IntoStaticStr)]
#[strum(serialize_all = "lowercase")]
#[repr(u8)]
pub enum Action {
    /// 0: do nothing.
    Wait = 0,
    /// 1: row + 1.
    Down = 1,
    /// 2: row − 1.
    Up = 2,
    /// 3: col + 1.
    Right = 3,
    /// 4: col − 1.
    Left = 4,
    /// 5: interact with the single object next to the agent.
    Interact = 5,
}

impl Action {
    /// Number of actions (size of the `Discrete` action space).
    pub const COUNT: usize = 6;

    /// Every action in code order.
    pub const ALL: [Action; 6] = [
        Action::Wait,
        Action::Down,
        Action::Up,
        Action::Right,
        Action::Left,
        Action::Interact,
    ];

    /// Converts a reference action code, rejecting anything outside `0..=5`.
    pub fn from_code(code: i64) -> Result<Self, EnvError> {
        if (0..6).contains(&code) {
            Ok(Self::ALL[code as usize])
        } else {
            Err(EnvError::InvalidAction { action: code })
        }
    }

    /// The reference action code.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// Row/column displacement of a move action (`(0, 0)` for wait and interact).
    pub fn delta(self) -> (i32, i32) {
        match self {
            Action::Down => (1, 0),
            Action::Up => (-1, 0),
            Action::Right => (0, 1),
            Action::Left => (0, -1),
            Action::Wait | Action::Interact => (0, 0),
        }
    }

    /// Short lowercase name (`wait`, `down`, …).
    pub fn name(self) -> &'static str {
        self.into()
    }
}

/// Parses a comma-separated list of action codes such as `"3,5,1,0"`.
pub fn parse_action_list(text: &str) -> Result<Vec<Action>, EnvError> {
    // One trailing comma is allowed (`3,5,`); an empty item elsewhere (`3,,5`) is a lost
    // action, which would shift every later step, so it is refused.
    let body = text.trim();
    let body = body.strip_suffix(',').unwrap_or(body);
    if body.trim().is_empty() {
        return Ok(Vec::new());
    }
    body.split(',')
        .map(str::trim)
        .enumerate()
        .map(|(i, s)| {
            if s.is_empty() {
                return Err(EnvError::BadOverride {
                    text: text.to_string(),
                    reason: format!(
                        "action {} is empty (allowed: integers 0..=5 separated by single commas)",
                        i + 1
                    ),
                });
            }
            let code: i64 = s.parse().map_err(|_| EnvError::BadOverride {
                text: s.to_string(),
                reason: "actions must be integers 0..=5 separated by commas".into(),
            })?;
            Action::from_code(code)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn action_lists_refuse_empty_items_but_take_a_trailing_comma() {
        assert_eq!(parse_action_list("3,5,").unwrap().len(), 2);
        assert_eq!(parse_action_list(" 3 , 5 ").unwrap().len(), 2);
        assert!(parse_action_list("").unwrap().is_empty());
        let e = parse_action_list("0,0,,0").unwrap_err().to_string();
        assert!(e.contains("action 3 is empty"), "{e}");
        assert!(parse_action_list(",0").is_err());
    }

    #[test]
    fn codes_round_trip_and_out_of_range_is_typed() {
        for a in Action::ALL {
            assert_eq!(Action::from_code(a.code() as i64).unwrap(), a);
        }
        assert_eq!(
            Action::from_code(6),
            Err(EnvError::InvalidAction { action: 6 })
        );
        assert!(Action::from_code(-1).is_err());
        assert_eq!(
            parse_action_list("3, 5,0").unwrap(),
            vec![Action::Right, Action::Interact, Action::Wait]
        );
        assert!(parse_action_list("3,x").is_err());
        assert!(parse_action_list("7").is_err());
    }
}
