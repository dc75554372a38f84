//! The placement of one agent's signature among the timing mechanisms: its distance to
//! every mechanism's fingerprint beside that mechanism's self-distance range (the distances
//! of its own held-out seeds, leave one seed out) and identification limit (the upper 99%
//! prediction limit for a new seed), the bootstrap share of each mechanism being the
//! nearest, and the verdict: *identified* with the nearest mechanism only when its distance
//! lies within that mechanism's identification limit. The committed mechanism signatures
//! are [`reference_signatures`]. The protocol an agent plays for its signature, and the
//! fingerprint's files, are `chronocooked_present::fingerprint`.

mod place;

pub use place::{
    Fingerprint, MechanismDistance, Placement, REFERENCE_SOURCE, place, reference_signatures,
    signatures_from_csv,
};
