//! Registry of the timing-model agents: names, descriptions, construction.

use crate::timing::agent::{TimingAgent, TimingAgentConfig};
use crate::timing::timers::Timer;
use crate::timing::{FrequencyLayout, Representation};
use chronocooked_env::ChronoEnv;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// One timing model of the zoo.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TimingModelSpec {
    /// Zoo name.
    pub name: &'static str,
    /// One-line description.
    pub description: &'static str,
}

/// Every timing model, in display order.
pub const TIMING_MODELS: [TimingModelSpec; 7] = [
    TimingModelSpec {
        name: "ddm",
        description: "drift-diffusion timer (Simen et al. 2011): z 1, m 0.15, drift learning at reinforcement; gates oven checks; SARSA(lambda) over [1, x/z, responding]",
    },
    TimingModelSpec {
        name: "sbf",
        description: "striatal beat frequency (Matell & Meck 2004): 1000 oscillators 5-15 Hz (random), 25 ms/step, memory noise 0.1; gates oven checks",
    },
    TimingModelSpec {
        name: "sbf-even",
        description: "striatal beat frequency with evenly spaced frequencies (aliases at T + k/df)",
    },
    TimingModelSpec {
        name: "timecells-csc",
        description: "complete serial compound (64-unit delay line) + SARSA(lambda) (Ludvig et al. 2008)",
    },
    TimingModelSpec {
        name: "timecells-ms",
        description: "microstimuli (d 0.985, sigma 0.08, m 10) + SARSA(lambda) (Ludvig et al. 2008)",
    },
    TimingModelSpec {
        name: "timecells-presence",
        description: "presence representation (one unit while the oven is on) + SARSA(lambda): cannot time",
    },
    TimingModelSpec {
        name: "timecells-laplace",
        description: "scale-invariant Laplace time cells (24 cells, tau* 1-64 steps, k 8) + SARSA(lambda)",
    },
];

/// Whether `name` is a timing model.
pub fn is_timing_model(name: &str) -> bool {
    TIMING_MODELS.iter().any(|m| m.name == name)
}

/// Builds an untrained timing agent `name` for `env`'s task (`seed` draws SBF frequencies).
/// Errors name the allowed values.
pub fn make_timing_agent(name: &str, env: &ChronoEnv, seed: u64) -> Result<TimingAgent, String> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let timer = match name {
        "ddm" => Timer::ddm(0.15),
        "sbf" => Timer::sbf(1000, FrequencyLayout::Random, 0.1, &mut rng),
        "sbf-even" => Timer::sbf(1000, FrequencyLayout::Even, 0.1, &mut rng),
        "timecells-csc" => Timer::time_cells(Representation::csc()),
        "timecells-ms" => Timer::time_cells(Representation::microstimulus()),
        "timecells-presence" => Timer::time_cells(Representation::Presence),
        "timecells-laplace" => Timer::time_cells(Representation::laplace()),
        other => {
            let names: Vec<&str> = TIMING_MODELS.iter().map(|m| m.name).collect();
            return Err(format!(
                "unknown timing model `{other}`; allowed: {}",
                names.join(", ")
            ));
        }
    };
    Ok(TimingAgent::new(
        name,
        timer,
        env,
        TimingAgentConfig::default(),
    ))
}
