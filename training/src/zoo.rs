//! The model zoo: one registry of every model the lab can train, evaluate or record — the
//! deep-RL architectures (PPO), the biologically plausible timing models and the two
//! reference agents (oracle, random) — with a description, parameters and presets.

use crate::error::TrainError;
use crate::ppo::config::ObsEncoding;
use crate::ppo::obs::ObsEncoder;
use crate::ppo::presets::PRESETS;
use crate::settings::Setting;
use chronocooked_env::{Action, Autoreset, VecEnv, make_config};
use chronocooked_models::{Architecture, PolicyConfig};
use serde::{Deserialize, Serialize};

/// What kind of model an entry is (decides how it is trained).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// PPO actor–critic network (`train --steps`, presets).
    DeepRl,
    /// Timing model + TD learner (`train`, episodes via `--set episodes=N`).
    Timing,
    /// Reference agent with nothing to train (`eval --agent NAME`).
    Baseline,
}

impl Family {
    /// Display name.
    pub fn label(self) -> &'static str {
        match self {
            Family::DeepRl => "deep RL (PPO)",
            Family::Timing => "timing model",
            Family::Baseline => "baseline",
        }
    }
}

/// One fixed property of a model (set by its name or construction, not a `--set` key):
/// name, value, meaning (with units).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZooParam {
    /// Property name.
    pub name: String,
    /// Value.
    pub value: String,
    /// Meaning and units.
    pub meaning: String,
}

/// One model of the zoo.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZooEntry {
    /// Zoo name (what `train --model`, `sweep` and `zoo show` take).
    pub name: String,
    /// Family.
    pub family: Family,
    /// One-line description.
    pub description: String,
    /// Settings with their defaults (deep RL: the `reference` preset on FixedInterval-v0;
    /// timing models: the model's defaults on FixedInterval-v0): every one a `--set` key
    /// and every `--set` key of the model here ([`crate::settings`]), besides the task
    /// parameters (`env.<task parameter>`).
    pub parameters: Vec<Setting>,
    /// Fixed properties (architecture, sizes fixed by the name or drawn at construction):
    /// not settings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub structure: Vec<ZooParam>,
    /// Hyperparameter presets (deep RL only).
    pub presets: Vec<String>,
    /// How to get a trained instance.
    pub usage: String,
    /// Timing models: per task (and multi-timer reward mode), `None` when nothing in the
    /// mechanism stops it, or the mechanistic reason it cannot reach the reference success.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tasks: Vec<TaskAbility>,
}

/// What a timing model's mechanism allows on one task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskAbility {
    /// Task id, with the multi-timer reward mode when it matters.
    pub task: String,
    /// Why the model cannot do it (`None`: no mechanistic limit).
    pub limit: Option<String>,
}

/// The task list of timing model `name`: every registered task the timing models play (its
/// family declares a response kind; a family registered at run time too), the multi-timer
/// in both reward modes, the dual task with its default one-step windows.
fn timing_tasks(name: &str) -> Vec<TaskAbility> {
    use chronocooked_models::timing::zoo::task_limit;
    let mut out = Vec::new();
    for spec in chronocooked_env::registry::all_tasks() {
        let playable = chronocooked_env::Task::new(spec.id)
            .and_then(|t| t.config())
            .is_ok_and(|c| c.response_kind().is_some());
        if !playable {
            continue;
        }
        let rows: Vec<(String, bool)> = match spec.id {
            "MultiTimer-v0" => vec![
                (format!("{} mode=lower_bounded", spec.id), false),
                (format!("{} mode=exact", spec.id), true),
            ],
            "PeakInterval-v0" => vec![(format!("{} (probe trials)", spec.id), false)],
            "DualTask-v0" => vec![(spec.id.to_string(), true)],
            _ => vec![(spec.id.to_string(), false)],
        };
        out.extend(rows.into_iter().map(|(task, exact)| TaskAbility {
            limit: task_limit(name, spec.id, exact).map(str::to_string),
            task,
        }));
    }
    out
}

fn p(name: &str, value: impl ToString, meaning: &str) -> ZooParam {
    ZooParam {
        name: name.into(),
        value: value.to_string(),
        meaning: meaning.into(),
    }
}

/// The baseline agents.
pub const BASELINES: [(&str, &str); 2] = [
    (
        "oracle",
        "scripted optimal policy that reads the true oven timer (upper bound: FOC = TD, P(long) 0/1 on the anchors)",
    ),
    (
        "random",
        "uniform random actions (lower bound: fits fail, reported as such)",
    ),
];

/// Number of trainable parameters of `arch` with the paper's input (code channels) on the
/// reference FI grid, counted from the parameter specification
/// ([`chronocooked_models::deep::spec::param_spec`]) without building the network (cheap
/// for any size: `zoo show lstm4096` does not allocate its 68M weights).
pub fn parameter_count(arch: Architecture) -> usize {
    let task = make_config("FixedInterval-v0", &[] as &[&str]).expect("FI is registered");
    let envs = VecEnv::new(&task, 1, Autoreset::SameStep).expect("FI builds");
    let encoder = ObsEncoder::new(ObsEncoding::Codes, &envs);
    let cfg = PolicyConfig::new(arch, encoder.cells(), encoder.channels(), Action::COUNT);
    chronocooked_models::deep::spec::param_spec(&cfg)
        .iter()
        .map(|p| p.shape.iter().product::<usize>())
        .sum()
}

/// The settings of a PPO run of `arch` with the `reference` preset on FixedInterval-v0.
fn deep_settings(arch: Architecture) -> Vec<Setting> {
    crate::ppo::presets::resolve::<&str>("FixedInterval-v0", arch, "reference", 0, &[])
        .map(|cfg| cfg.listing())
        .unwrap_or_default()
}

/// The settings of timing model `name` with its defaults on FixedInterval-v0.
fn timing_settings(name: &str) -> Vec<Setting> {
    crate::timing_run::TimingRunConfig::new(
        &chronocooked_env::Task::new("FixedInterval-v0").expect("FI is registered"),
        name,
        0,
    )
    .listing()
}

fn deep_entry(arch: Architecture) -> ZooEntry {
    let trunk = format!(
        "Conv1x1 {}->8, ReLU, Conv1x1 8->6, ReLU, flatten, Linear->64, ReLU",
        6 * arch.frames
    );
    let (description, mut structure) = match arch.core {
        None if arch.frames > 1 => (
            format!(
                "CNN trunk + heads pi=[64], vf=[64] fed the last {} observations stacked along \
                 the channel axis (SB3's VecFrameStack); no memory beyond that window",
                arch.frames
            ),
            vec![p(
                "frames",
                arch.frames,
                "observations stacked per input (steps of the window)",
            )],
        ),
        None => (
            "CNN trunk + heads pi=[64], vf=[64]; no memory".to_string(),
            vec![],
        ),
        Some(kind) => {
            let what = match kind.name() {
                "lstm" => "LSTM",
                "gru" => "GRU",
                "rnn" => "vanilla tanh RNN",
                _ => {
                    "continuous-time RNN (h <- (1-a)h + a tanh(W_in x + W_rec h + b), a = dt/softplus(tau))"
                }
            };
            let mut ps = vec![p("hidden", arch.hidden, "units of the recurrent core")];
            if kind.name() == "ctrnn" {
                ps.push(p("dt", 0.1, "CTRNN integration step (model time units)"));
                ps.push(p(
                    "tau_raw",
                    1.0,
                    if arch.reservoir {
                        "initial raw time constant per unit (fixed; tau = softplus(tau_raw))"
                    } else {
                        "initial raw time constant per unit (learnable; tau = softplus(tau_raw))"
                    },
                ));
            }
            let trained = if arch.reservoir {
                " that is never trained (a fixed random reservoir, as the paper's code leaves its CTRNN: only the trunk and heads learn)"
            } else {
                ""
            };
            (
                format!(
                    "CNN trunk + {what} core ({} units){trained} shared by actor and critic + heads pi=[64], vf=[64]",
                    arch.hidden
                ),
                ps,
            )
        }
    };
    structure.insert(
        0,
        p(
            "parameters",
            parameter_count(arch),
            "trainable weights on the reference 5x3 grid",
        ),
    );
    structure.insert(1, p("trunk", "cnn", &trunk));
    ZooEntry {
        name: arch.name(),
        family: Family::DeepRl,
        description,
        parameters: deep_settings(arch),
        structure,
        presets: PRESETS.iter().map(|s| s.to_string()).collect(),
        usage: format!(
            "chronocooked train --model {} --task ID [--preset reference|fast] [--steps N] [--set key=value]",
            arch.name()
        ),
        tasks: vec![],
    }
}

/// Fixed properties of timing model `name` (set at its construction, not settings), read
/// from a freshly built agent (so they always match the code).
fn timing_structure(name: &str) -> Vec<ZooParam> {
    use chronocooked_models::timing::Representation;
    use chronocooked_models::timing::timers::Timer;
    let task = make_config("FixedInterval-v0", &[] as &[&str]).expect("FI is registered");
    let env = chronocooked_env::ChronoEnv::new(&task).expect("FI builds");
    let Ok(agent) = chronocooked_models::timing::zoo::make_timing_agent(name, &env, 0) else {
        return vec![];
    };
    match &agent.timer {
        Timer::Ddm(d) => vec![
            p("threshold", d.acc.threshold, "accumulator threshold z"),
            p(
                "initial_interval",
                d.initial_interval,
                "interval the drift starts at (steps)",
            ),
            p(
                "rate",
                d.rate,
                "drift learning rate after a reinforced interval",
            ),
            p("start", d.start, "response threshold as a fraction of z"),
        ],
        Timer::Sbf(s) => {
            let (lo, hi) = s
                .model
                .freqs
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(a, b), &f| (a.min(f), b.max(f)));
            vec![
                p("oscillators", s.model.freqs.len(), "cortical oscillators"),
                p(
                    "frequencies",
                    format!("{lo:.2}-{hi:.2}"),
                    "oscillator band drawn (Hz)",
                ),
                p(
                    "seconds_per_step",
                    s.seconds_per_step,
                    "model seconds per env step",
                ),
                p(
                    "learning_rate",
                    s.model.learning_rate,
                    "striatal weight learning rate",
                ),
                p(
                    "threshold",
                    s.threshold,
                    "response threshold of the striatal detector readout",
                ),
            ]
        }
        Timer::TimeCells(tc) => match &tc.cells.repr {
            Representation::Presence => vec![p("units", 1, "one unit while the oven is on")],
            Representation::Csc { units } => {
                vec![p(
                    "units",
                    units,
                    "delay-line units, one per step since onset",
                )]
            }
            Representation::Microstimulus {
                decay,
                sigma,
                count,
            } => vec![
                p("units", count, "microstimuli m"),
                p("decay", decay, "memory-trace decay d per step"),
                p("sigma", sigma, "width of each microstimulus"),
            ],
            Representation::Laplace {
                cells,
                tau_min,
                tau_max,
                order,
            } => vec![
                p("units", cells, "time cells with log-spaced peak times"),
                p(
                    "tau_star",
                    format!("{tau_min}-{tau_max}"),
                    "peak times (steps)",
                ),
                p("k", order, "order of the inverse-Laplace approximation"),
            ],
        },
    }
}

/// Every model of the zoo, in display order: deep RL, timing models, baselines.
pub fn zoo() -> Vec<ZooEntry> {
    let mut v: Vec<ZooEntry> = Architecture::all().into_iter().map(deep_entry).collect();
    v.extend(
        chronocooked_models::timing::zoo::TIMING_MODELS
            .iter()
            .map(|m| ZooEntry {
                name: m.name.into(),
                family: Family::Timing,
                description: m.description.into(),
                parameters: timing_settings(m.name),
                structure: timing_structure(m.name),
                presets: vec![],
                usage: format!(
                    "chronocooked train --model {} --task ID [--set episodes=N] [--set alpha=0.05]",
                    m.name
                ),
                tasks: timing_tasks(m.name),
            }),
    );
    v.extend(BASELINES.iter().map(|(name, what)| ZooEntry {
        name: (*name).into(),
        family: Family::Baseline,
        description: (*what).into(),
        parameters: vec![],
        structure: vec![],
        presets: vec![],
        usage: format!("chronocooked eval --agent {name} --task ID --out DIR"),
        tasks: vec![],
    }));
    v
}

/// The family of a model name (accepts any hidden size for deep models, e.g. `lstm64`).
pub fn family_of(name: &str) -> Result<Family, TrainError> {
    if BASELINES.iter().any(|b| b.0 == name) {
        return Ok(Family::Baseline);
    }
    if chronocooked_models::timing::zoo::is_timing_model(name) {
        return Ok(Family::Timing);
    }
    name.parse::<Architecture>()
        .map(|_| Family::DeepRl)
        .map_err(|e| TrainError::InvalidParam {
            field: "model".into(),
            value: name.into(),
            allowed: format!(
                "{e}; timing models: {}; baselines: oracle, random",
                chronocooked_models::timing::zoo::TIMING_MODELS
                    .iter()
                    .map(|m| m.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        })
}

/// The zoo entry of `name` (deep models of any hidden size are described on the fly).
pub fn zoo_entry(name: &str) -> Result<ZooEntry, TrainError> {
    match family_of(name)? {
        Family::DeepRl => Ok(deep_entry(name.parse().expect("checked"))),
        _ => Ok(zoo()
            .into_iter()
            .find(|e| e.name == name)
            .expect("registered")),
    }
}
