//! Chronocooked Lab models crate (grows with its issue).
