//! Chronocooked Lab analysis crate (grows with its issue).
