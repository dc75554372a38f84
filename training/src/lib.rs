//! Chronocooked Lab training crate (grows with its issue).
