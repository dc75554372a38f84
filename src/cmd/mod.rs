//! One module per subcommand, named after it: each parses its arguments (clap) and calls
//! the libraries (ripgrep's thin CLI over libraries).
//!
//! * [`env`] — `env list | replay | render | play | demo` (the task tour);
//! * [`demo`] — `demo`: the built-in demo study (`sweeps/demo.toml`);
//! * [`train`] — `train`: PPO agents and timing models;
//! * [`eval`] — `eval`: the reference evaluation protocol;
//! * [`adapt`] — `adapt`: uncertainty adaptation;
//! * [`record`] — `record`: neural activity datasets;
//! * [`export`] — `export`: NPZ / CSV export;
//! * [`report`] — `report`: the leaderboard;
//! * [`sweep`] — `sweep` and the hidden `sweep-job`;
//! * [`paper`] — `paper collect | analyse`: the paper's study;
//! * [`mechanisms`] — `mechanisms`: fingerprints and each agent's nearest timing mechanism;
//! * [`fingerprint`] — `fingerprint`: one agent's runs through the mechanisms protocol,
//!   placed among the committed mechanisms;
//! * [`cli_reference`] — `cli-reference`: the command line's Markdown reference (`docs/cli.md`);
//! * [`verify`] — `verify`: a folder's claims re-derived, every difference named;
//! * [`zoo`] — `zoo list | show | add`; [`zoo_agents`] — the trained agents of the zoo
//!   (`--run zoo:<model>/<task>`);
//! * [`bench`] — `bench env | train | timing`.

pub mod adapt;
pub mod bench;
pub mod cli_reference;
pub mod demo;
pub mod env;
pub mod eval;
pub mod export;
pub mod fingerprint;
pub mod mechanisms;
pub mod paper;
pub mod record;
pub mod report;
pub mod sweep;
pub mod train;
pub mod verify;
pub mod zoo;
pub mod zoo_agents;
