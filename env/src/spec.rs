//! The immutable, shared description of a task instance: validated layout, flattened
//! rules for the hot loop, and the static part of the codes observation.

use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::task::{CueMode, RewardMode, TaskConfig, TaskFamily, TaskParams};
use std::sync::Arc;

/// Number of channels of the "codes" observation (`u8`, `[R, C, 6]`, channel-last; the
/// channels are described in `obs`).
pub const CODE_CHANNELS: usize = 6;

/// Task rules, flattened to a small `Copy` value for the hot loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Rules {
    Fixed,
    Probe {
        factor: u32,
    },
    Bisection {
        short: u32,
        long: u32,
    },
    Window {
        mode: RewardMode,
        under: u32,
        over: u32,
        reduced: f32,
    },
    Dual {
        under: u32,
        over: u32,
        reduced: f32,
        sink: f32,
    },
    Uncertainty {
        p_never: f32,
        over: u32,
        overcooked: f32,
        manual: f32,
    },
}

/// Immutable, shared description of a task instance.
#[derive(Debug)]
pub(crate) struct Spec {
    pub(crate) config: TaskConfig,
    pub(crate) family: TaskFamily,
    pub(crate) layout: Layout,
    pub(crate) rules: Rules,
    pub(crate) default_td: u32,
    pub(crate) tds: Vec<u32>,
    pub(crate) cue: Option<CueMode>,
    pub(crate) oven: usize,
    /// Channel-0 codes of the empty grid (`[R, C, 6]`, other channels 0).
    pub(crate) background: Vec<u8>,
}

impl Spec {
    pub(crate) fn new(config: &TaskConfig) -> Result<Arc<Self>, EnvError> {
        let layout = config.validate()?;
        let (rules, default_td, tds, cue) = match &config.params {
            TaskParams::FixedInterval { td } => (Rules::Fixed, *td, vec![*td], None),
            TaskParams::PeakInterval { td, probe_factor } => (
                Rules::Probe {
                    factor: *probe_factor,
                },
                *td,
                vec![*td],
                None,
            ),
            TaskParams::Bisection { short, long } => (
                Rules::Bisection {
                    short: *short,
                    long: *long,
                },
                *short,
                vec![*short, *long],
                None,
            ),
            TaskParams::MultiTimer {
                tds,
                mode,
                cue,
                under_buffer,
                over_buffer,
                reduced_reward,
                ..
            } => (
                Rules::Window {
                    mode: *mode,
                    under: *under_buffer,
                    over: *over_buffer,
                    reduced: *reduced_reward,
                },
                tds[0],
                tds.clone(),
                Some(*cue),
            ),
            TaskParams::Dual {
                td,
                under_buffer,
                over_buffer,
                reduced_reward,
                sink_reward,
            } => (
                Rules::Dual {
                    under: *under_buffer,
                    over: *over_buffer,
                    reduced: *reduced_reward,
                    sink: *sink_reward,
                },
                *td,
                vec![*td],
                None,
            ),
            TaskParams::Uncertainty {
                td,
                never_ready_prob,
                over_buffer,
                overcooked_reward,
                manual_reward,
            } => (
                Rules::Uncertainty {
                    p_never: *never_ready_prob,
                    over: *over_buffer,
                    overcooked: *overcooked_reward,
                    manual: *manual_reward,
                },
                *td,
                vec![*td],
                None,
            ),
        };
        let oven = layout.cells_of(ObjectKind::Oven)[0];
        let mut background = vec![0u8; layout.n_cells() * CODE_CHANNELS];
        for cell in 0..layout.n_cells() {
            if let Some(kind) = layout.object_at(cell) {
                background[cell * CODE_CHANNELS] = kind.code();
            }
        }
        Ok(Arc::new(Spec {
            config: config.clone(),
            family: config.family(),
            layout,
            rules,
            default_td,
            tds,
            cue,
            oven,
            background,
        }))
    }

    /// Length of one codes observation (`R·C·6`).
    pub(crate) fn obs_len(&self) -> usize {
        self.background.len()
    }
}

/// Derives the seed of sub-environment `index` from a base seed (SplitMix64 finaliser),
/// so that runs with neighbouring base seeds do not share streams.
pub fn derive_seed(base: u64, index: u64) -> u64 {
    let mut z = base ^ index.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
