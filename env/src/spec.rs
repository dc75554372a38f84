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
    /// Multi-anchor: the first `k` of `anchors` are active (counters 1…k).
    MultiAnchor {
        anchors: [u32; 4],
        k: u8,
    },
    /// Temporal reproduction (details in [`Spec::rsg`]).
    Reproduction,
    /// Multi-oven: `n` ovens, each soup short or long.
    MultiOven {
        short: u32,
        long: u32,
        n: u8,
        asynchronous: bool,
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
    /// Cells of ovens 0, 1, 2 (multi-oven; the first is `oven`, absent ones repeat it).
    pub(crate) ovens: [usize; 3],
    /// Channel-0 codes of the empty grid (`[R, C, 6]`, other channels 0).
    pub(crate) background: Vec<u8>,
    /// Reproduction: priors, gains, window and foreperiods.
    pub(crate) rsg: Option<RsgSpec>,
}

/// The reproduction task's draws and reward window.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RsgSpec {
    /// Each prior's inclusive range of ts (steps).
    pub(crate) priors: Vec<(u32, u32)>,
    /// Gains of the production.
    pub(crate) gains: Vec<f32>,
    /// Window half-width: `tolerance · target + tolerance_steps` (the decimal values as
    /// given, to 1e-6: an `f32` 0.2 would widen the window by 3e-9 and pay an edge response).
    pub(crate) tolerance: f64,
    /// Constant part of the window (steps).
    pub(crate) tolerance_steps: f64,
    /// Foreperiod range (steps).
    pub(crate) foreperiod: (u32, u32),
    /// Whether the counter shows the prior.
    pub(crate) prior_cue: bool,
    /// Counter cell (where the context cue is shown).
    pub(crate) counter: usize,
}

impl RsgSpec {
    /// Contexts shown on the counter: `prior · gains + gain` (+1 in the observation), or
    /// none when there is nothing to cue.
    pub(crate) fn cued_contexts(&self) -> usize {
        let priors = if self.prior_cue { self.priors.len() } else { 1 };
        let n = priors * self.gains.len();
        if n > 1 { n } else { 0 }
    }

    /// The cue value of `(prior, gain)` (0: no cue).
    pub(crate) fn cue(&self, prior: u8, gain: u8) -> u8 {
        if self.cued_contexts() == 0 {
            return 0;
        }
        let p = if self.prior_cue { prior as usize } else { 0 };
        (1 + p * self.gains.len() + gain as usize) as u8
    }

    /// The target production `g · ts` and the window half-width (steps).
    pub(crate) fn target(&self, ts: u32, gain: u8) -> (f64, f64) {
        let target = decimal(f64::from(self.gains[gain as usize])) * f64::from(ts);
        (target, self.tolerance * target + self.tolerance_steps)
    }
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
            TaskParams::MultiAnchor { .. } => {
                let active = config.params.active_anchors().unwrap_or(&[]);
                let mut anchors = [0; 4];
                anchors[..active.len()].copy_from_slice(active);
                (
                    Rules::MultiAnchor {
                        anchors,
                        k: active.len() as u8,
                    },
                    active[0],
                    active.to_vec(),
                    None,
                )
            }
            TaskParams::Reproduction { priors, .. } => {
                let (lo, _) = crate::task::parse_prior(&priors[0])?;
                (Rules::Reproduction, lo, Vec::new(), None)
            }
            TaskParams::MultiOven {
                short,
                long,
                ovens,
                asynchronous,
            } => (
                Rules::MultiOven {
                    short: *short,
                    long: *long,
                    n: *ovens as u8,
                    asynchronous: *asynchronous,
                },
                *short,
                vec![*short, *long],
                None,
            ),
        };
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
                background[cell * CODE_CHANNELS] = object_code(kind, config.family());
            }
        }
        let rsg = match &config.params {
            TaskParams::Reproduction {
                priors,
                prior_cue,
                gains,
                tolerance,
                tolerance_steps,
                foreperiod_min,
                foreperiod_max,
            } => Some(RsgSpec {
                priors: priors
                    .iter()
                    .map(|p| crate::task::parse_prior(p))
                    .collect::<Result<_, _>>()?,
                gains: gains.clone(),
                tolerance: decimal(f64::from(*tolerance)),
                tolerance_steps: decimal(f64::from(*tolerance_steps)),
                foreperiod: (*foreperiod_min, *foreperiod_max),
                prior_cue: *prior_cue,
                counter: layout.cells_of(ObjectKind::DeliveryCounter)[0],
            }),
            _ => None,
        };
        Ok(Arc::new(Spec {
            config: config.clone(),
            family: config.family(),
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

/// An `f32` setting as the decimal it was written as (rounded to 1e-6).
fn decimal(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

/// The channel-0 code of `kind` in `family`: the multi-anchor reference writes the oven as 4
/// and counter i as 6 + i; the multi-oven reference writes the short and long counters as 4
/// and 5 and oven i as 3 + 3i; every other task the kind's own code.
pub(crate) fn object_code(kind: ObjectKind, family: TaskFamily) -> u8 {
    match (family, kind) {
        (TaskFamily::MultiAnchor, ObjectKind::Oven) => 4,
        (TaskFamily::MultiAnchor, ObjectKind::ShortCounter) => 7,
        (TaskFamily::MultiAnchor, ObjectKind::LongCounter) => 8,
        (TaskFamily::MultiOven, ObjectKind::LongCounter) => 5,
        (TaskFamily::MultiOven, ObjectKind::Oven) => 6,
        _ => kind.code(),
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
