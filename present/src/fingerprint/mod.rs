//! The fingerprint of one agent: which timing mechanism does it resemble?
//!
//! The agent plays the mechanisms study's protocol ([`PROTOCOL`]): fixed interval at TD 6
//! and TD 12 and bisection 4–12, each evaluated with the reference protocol (every free
//! start cell, [`chronocooked_models::timing::NOISE_DRAWS`] times for a noisy agent) and
//! the fixed-interval conditions also recorded on peak-interval probe trials with the
//! neural summary. Its [`Signature`](chronocooked_analysis::mechanisms::Signature) (the features of [`chronocooked_analysis::mechanisms`]) is placed
//! among the committed mechanism signatures ([`reference_signatures`]): its distance to
//! every mechanism's fingerprint beside that mechanism's self-distance range (the
//! distances of its own held-out seeds, leave one seed out) and identification limit (the
//! upper 99% prediction limit for a new seed), the bootstrap share of each mechanism being
//! the nearest, and the verdict: *identified* with the nearest mechanism only when its
//! distance lies within that mechanism's identification limit.
//!
//! The folder of one fingerprint:
//!
//! * `<condition>/eval/` — the condition's evaluation folder (as `chronocooked eval`);
//! * `<condition>/activity.json`, `<condition>/activity.summary.json` — the probe recording
//!   and its neural summary (fixed interval, agents with activity);
//! * `fingerprint.json`, `fingerprint.md`, `fingerprint.html`, `fingerprint.png` — the
//!   signature, the placement and the card ([`write_fingerprint`]).

mod card;
mod play;

pub use card::{agreement, read_signature, verdict, write_fingerprint};
pub use chronocooked_analysis::fingerprint::{
    Fingerprint, MechanismDistance, Placement, REFERENCE_SOURCE, place, reference_signatures,
    signatures_from_csv,
};
pub use play::{
    ConditionPlay, PROTOCOL, ProtocolCondition, agent_signature, play_condition, write_condition,
};
/// Writes the played conditions into `out` (holding its lock; folders of conditions not
/// played now are removed, `fingerprint.json` first removed so that it is written last)
/// and places the agent `model`: its signature (`units_correspond` as in
/// [`agent_signature`]), the placement in both views among [`reference_signatures`]
/// (`resamples` bootstrap resamples, `seed`) and the fingerprint's files. Returns the
/// placements and the files.
pub fn write_and_place(
    out: &std::path::Path,
    plays: &[ConditionPlay],
    model: &str,
    units_correspond: bool,
    seed: u64,
    resamples: usize,
) -> Result<(Fingerprint, Vec<std::path::PathBuf>), chronocooked_analysis::mechanisms::MechanismError>
{
    use chronocooked_analysis::mechanisms::MechanismError;
    let _lock =
        chronocooked_env::fs::FolderLock::acquire(out).map_err(|e| MechanismError::at(out, e))?;
    let _ = std::fs::remove_file(out.join("fingerprint.json"));
    for c in &PROTOCOL {
        if !plays.iter().any(|p| p.condition.name == c.name) {
            let _ = std::fs::remove_dir_all(out.join(c.name));
        }
    }
    for play in plays {
        write_condition(out, play, model, seed)?;
    }
    let signature = agent_signature(out, model, units_correspond, seed)?;
    let fingerprint = Fingerprint::place(&signature, &reference_signatures(), resamples, seed);
    let files = write_fingerprint(out, &fingerprint)?;
    Ok((fingerprint, files))
}
