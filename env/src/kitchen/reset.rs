//! The start of an episode: the reset options checked against what the task declares, and
//! the draws of a new episode (start cell, TD, never-ready; every oven of a multi-oven
//! episode; a Ready-Set-Go episode's context) in the reference's order.

use super::{Kitchen, ResetOptions, Rules};
use crate::error::EnvError;
use crate::info::{Carry, Events, Info};
use crate::task::CueMode;
use crate::task::reset_option::ResetOption;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

impl Kitchen {
    /// Refuses an option the task's family does not declare, naming the task's own options
    /// and the tasks that take it.
    fn check_declared_options(&self, options: &ResetOptions) -> Result<(), EnvError> {
        let declared = self.spec.reset_options;
        for option in ResetOption::ALL {
            if options.sets(option) && !declared.contains(&option) {
                let own: Vec<&str> = declared.iter().map(|o| o.key()).collect();
                let takers = crate::task::family::tasks_with_reset_option(option);
                return Err(EnvError::reset_option(
                    option.key(),
                    "given",
                    format!(
                        "an option of {} (its options: {}); `{}` is an option of {}",
                        self.spec.config.id,
                        own.join(", "),
                        option.key(),
                        if takers.is_empty() {
                            "no registered task".to_string()
                        } else {
                            takers.join(", ")
                        }
                    ),
                ));
            }
        }
        Ok(())
    }

    pub(super) fn check_td_option(&self, td: u32) -> Result<(), EnvError> {
        // Reference-compatible multi-anchor / multi-oven episodes may replay the reference's
        // TD 0, which never becomes ready (the timer is already 1 after the put).
        let zero_ok = self.spec.config.reference_compat
            && matches!(
                self.spec.rules,
                Rules::Categories { .. } | Rules::MultiOven { .. }
            );
        if (td == 0 && !zero_ok) || td > 10_000 {
            let allowed = if zero_ok {
                "integer 0..=10000"
            } else {
                "integer 1..=10000 (0 only in reference-compatible multi-anchor/multi-oven replays)"
            };
            return Err(EnvError::reset_option("td", td, allowed));
        }
        match self.spec.cue {
            Some(CueMode::Value) if td > 255 => Err(EnvError::reset_option(
                "td",
                td,
                "integer 1..=255 (the value cue is a u8)",
            )),
            Some(CueMode::Categorical) if !self.spec.tds.contains(&td) => {
                Err(EnvError::reset_option(
                    "td",
                    td,
                    format!(
                        "one of the trained TDs {:?} (categorical cues have no code for other TDs)",
                        self.spec.tds
                    ),
                ))
            }
            _ => Ok(()),
        }
    }

    /// Starts a new episode, reseeding the RNG when `seed` is given, and writes the
    /// reset observation into `obs` (`[R, C, 6]`, length `R·C·6`).
    ///
    /// Draw order (only for what `options` leaves open): start cell, TD, never-ready.
    pub fn reset(
        &mut self,
        seed: Option<u64>,
        options: &ResetOptions,
        obs: &mut [u8],
    ) -> Result<Info, EnvError> {
        self.check_declared_options(options)?;
        let layout = &self.spec.layout;
        let start = match options.start {
            Some((r, c)) => {
                if !layout.is_free(r, c) {
                    let free: Vec<String> = layout
                        .free_cells()
                        .iter()
                        .map(|&f| {
                            let (fr, fc) = layout.coords(f as usize);
                            format!("{fr},{fc}")
                        })
                        .collect();
                    return Err(EnvError::reset_option(
                        "start",
                        format!("{r},{c}"),
                        format!("a free cell: {}", free.join(" ")),
                    ));
                }
                Some(layout.index(r, c))
            }
            None => None,
        };
        if let Some(td) = options.td {
            self.check_td_option(td)?;
        }
        self.check_oven_options(options)?;
        self.check_rsg_options(options)?;
        if let Some(seed) = seed {
            self.rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        }
        self.reset_state(start, options.td, options.never_ready);
        if self.is_multi_oven() {
            self.reset_ovens(options.td, options.oven_tds, options.on_times);
        }
        if self.spec.rsg.is_some() {
            self.reset_rsg(options.td, options.prior, options.gain);
        }
        self.write_full_obs(obs);
        Ok(self.info(Events::default(), -1, false))
    }

    /// Fast reset with everything drawn from the RNG (used by autoreset).
    #[inline]
    pub(crate) fn reset_random(&mut self, obs: &mut [u8]) -> Info {
        self.reset_state(None, None, None);
        if self.is_multi_oven() {
            self.reset_ovens(None, None, None);
        }
        if self.spec.rsg.is_some() {
            self.reset_rsg(None, None, None);
        }
        self.write_full_obs(obs);
        self.info(Events::default(), -1, false)
    }

    fn reset_state(&mut self, start: Option<usize>, td: Option<u32>, never: Option<bool>) {
        let free = self.spec.layout.free_cells();
        self.agent = match start {
            Some(cell) => cell,
            None => free[self.rng.random_range(0..free.len())] as usize,
        };
        self.td = match td.or(self.spec.config.fixed_td) {
            Some(td) => td,
            None => match self.spec.rules {
                Rules::Bisection { short, long } => {
                    if self.rng.random_bool(0.5) {
                        long
                    } else {
                        short
                    }
                }
                Rules::Window { .. } => self.spec.tds[self.rng.random_range(0..self.num_timers)],
                Rules::Categories { k, .. } => self.spec.tds[self.rng.random_range(0..k as usize)],
                _ => self.spec.default_td,
            },
        };
        self.never_ready = match (never, self.spec.rules) {
            (Some(n), _) => n,
            (None, Rules::Uncertainty { p_never, .. }) => {
                p_never > 0.0 && self.rng.random_bool(p_never as f64)
            }
            _ => false,
        };
        self.carry = Carry::Nothing;
        self.timer = -1;
        self.ready = false;
        self.manual = false;
        self.timestep = 0;
        self.oven_off_time = -1;
        self.manual_stop_time = -1;
        self.sink_count = 0;
        self.last_sink_timer = -1;
        self.counter = None;
        self.done = false;
    }
}
