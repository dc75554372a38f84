//! First oven check (FOC), the paper's fixed-interval timing measure.
//!
//! FOC = the oven timer at the first action of the unbroken run of interacts next to the
//! running oven (oven checks) that ends in the pickup. A run is broken by any action that is
//! not such a check (a move, a wait, an interact elsewhere). Episodes without a pickup have
//! no FOC.

use chronocooked_env::{Events, Info};
use chronocooked_models::EpisodeRecord;

/// FOC of one episode from its actions (codes) and per-step `info`; `None` without pickup.
pub fn first_oven_check(actions: &[u8], infos: &[Info]) -> Option<i32> {
    let pickup = infos.iter().position(|i| i.events.has(Events::PICKUP))?;
    let mut first = pickup;
    while first > 0 {
        let j = first - 1;
        let is_check = actions[j] == 5 && infos[j].events.has(Events::OVEN_CHECK);
        if !is_check {
            break;
        }
        first = j;
    }
    Some(infos[first].timer_at_action)
}

/// FOC of a recorded episode.
pub fn episode_foc(record: &EpisodeRecord) -> Option<i32> {
    first_oven_check(&record.actions, &record.infos)
}
