//! The immutable, shared description of a task instance: validated layout, flattened
//! rules for the hot loop, and the static part of the codes observation.

use crate::error::EnvError;
use crate::layout::{Layout, ObjectKind};
use crate::rules::{CueMode, ReadySetGo, Rules};
use crate::task::family::RuleSet;
use crate::task::{TaskConfig, TaskFamily};
use std::sync::Arc;

/// Number of channels of the "codes" observation (`u8`, `[R, C, 6]`, channel-last; the
/// channels are described in `obs`).
pub const CODE_CHANNELS: usize = 6;

/// Immutable, shared description of a task instance.
#[derive(Debug)]
pub(crate) struct Spec {
    pub(crate) config: TaskConfig,
    pub(crate) family: TaskFamily,
    /// Whether the oven shows a "ready" state (the family's).
    pub(crate) shows_ready: bool,
    /// The options `reset` takes (the family's).
    pub(crate) reset_options: &'static [crate::task::reset_option::ResetOption],
    pub(crate) layout: Layout,
    pub(crate) rules: Rules,
    pub(crate) default_td: u32,
    pub(crate) tds: Vec<u32>,
    pub(crate) cue: Option<CueMode>,
    pub(crate) oven: usize,
    /// Cells of ovens 0, 1, 2 (multi-oven; the first is `oven`, absent ones repeat it).
    pub(crate) ovens: [usize; 3],
    /// Channel-0 codes of the empty grid (`[R, C, 6]`, other channels 0).
    pub(crate) background: Vec<u8>,
    /// Ready-Set-Go: priors, gains, window and foreperiods.
    pub(crate) rsg: Option<ReadySetGo>,
}

impl Spec {
    pub(crate) fn new(config: &TaskConfig) -> Result<Arc<Self>, EnvError> {
        let layout = config.validate()?;
        let family = crate::task::family::of_params(&config.params);
        let RuleSet {
            rules,
            default_td,
            tds,
            cue,
            rsg,
        } = family.rules(config, &layout)?;
        let oven = layout.cells_of(ObjectKind::Oven)[0];
        let mut ovens = [oven; 3];
        for (slot, kind) in [ObjectKind::Oven2, ObjectKind::Oven3]
            .into_iter()
            .enumerate()
        {
            if let Some(&cell) = layout.cells_of(kind).first() {
                ovens[slot + 1] = cell;
            }
        }
        let mut background = vec![0u8; layout.n_cells() * CODE_CHANNELS];
        for cell in 0..layout.n_cells() {
            if let Some(kind) = layout.object_at(cell) {
                background[cell * CODE_CHANNELS] = family.object_code(kind);
            }
        }
        Ok(Arc::new(Spec {
            config: config.clone(),
            family: config.family(),
            shows_ready: family.shows_ready(),
            reset_options: family.reset_options(),
            layout,
            rules,
            default_td,
            tds,
            cue,
            oven,
            ovens,
            background,
            rsg,
        }))
    }

    /// Length of one codes observation (`R·C·6`).
    pub(crate) fn obs_len(&self) -> usize {
        self.background.len()
    }
}

/// The channel-0 code of `kind` in `family` (the family's reference codes; see
/// `task::family`).
pub(crate) fn object_code(kind: ObjectKind, family: TaskFamily) -> u8 {
    crate::task::family::of(family).object_code(kind)
}

/// Derives the seed of sub-environment `index` from a base seed (SplitMix64 finaliser),
/// so that runs with neighbouring base seeds do not share streams.
pub fn derive_seed(base: u64, index: u64) -> u64 {
    let mut z = base ^ index.wrapping_add(1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
