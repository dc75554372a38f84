//! The settings of a deep-RL (PPO) run: every `--set` key of [`crate::TrainConfig`] and
//! of its [`crate::PpoConfig`] and [`crate::Curriculum`], with its accepted values.

use super::{COUNT, NON_NEGATIVE, POSITIVE, Rule, Spec, UNIT, spec};

/// Largest PPO budget (env steps): about 1,000 × the reference protocol's largest (1.76M,
/// the multi-anchor and multi-oven curricula) — days on the lab's CPUs, so a larger value is
/// a typo or a corrupted file, not a plan (a run folder's `total_steps = i64::MAX` trained on
/// without end before this bound).
pub const MAX_TOTAL_STEPS: u64 = 2_000_000_000;

/// Largest count of episodes a PPO setting averages over (the success-rate and curriculum
/// windows): 10,000 × the reference's 100-episode window.
pub const MAX_WINDOW_EPISODES: u64 = 1_000_000;

/// Largest number of checkpoints kept: a checkpoint is 0.1–10 MB, so 1,000 of the largest
/// fill 10 GB, more than the lab's disk budget for one run.
pub const MAX_KEEP_CHECKPOINTS: u64 = 1_000;

/// An interval in env steps: 0 (off) up to the largest budget.
const STEP_INTERVAL: Rule = Rule::Int {
    lo: 0,
    hi: MAX_TOTAL_STEPS,
};
/// A window of episodes.
const EPISODE_WINDOW: Rule = Rule::Int {
    lo: 1,
    hi: MAX_WINDOW_EPISODES,
};

/// `spec`, a setting only the configurations `when` names have (e.g.
/// `curriculum=tolerance`).
const fn only_with(when: &'static str, spec: Spec) -> Spec {
    Spec {
        only_with: Some(when),
        ..spec
    }
}

/// The curricula whose levels are left on a share of the last `window` episodes.
const LEVELLED: &str = "curriculum=multi_timer, multi_anchor, multi_oven or tolerance";

/// Names of the curricula (`curriculum=NAME` starts the named one with its defaults).
pub const CURRICULA: &[&str] = &[
    "none",
    "multi_timer",
    "uncertainty",
    "multi_anchor",
    "multi_oven",
    "tolerance",
];

/// Every setting of a PPO run, in display order. Not settings: `task` and `model`
/// (`--task`, `--model`), `preset` (`--preset`) and the task parameters, set as
/// `env.<task parameter>=v`.
pub const PPO_SETTINGS: &[Spec] = &[
    spec(
        "seed",
        &["seed"],
        COUNT,
        "seed of everything random in the run",
    ),
    Spec {
        aliases: &["steps"],
        ..spec(
            "total_steps",
            &["total_steps"],
            Rule::Int {
                lo: 1,
                hi: MAX_TOTAL_STEPS,
            },
            "env-step budget (all envs together; at most 2e9, about 1,000 x the reference's largest budget of 1.76M)",
        )
    },
    spec(
        "obs",
        &["obs"],
        Rule::Choice(&["codes", "onehot"]),
        "observation encoding: the 6 integer code channels (the paper's input) or one-hot channels",
    ),
    spec(
        "checkpoint_every",
        &["checkpoint_every"],
        STEP_INTERVAL,
        "env steps between checkpoints, rounded up to whole updates (0 = only at the end)",
    ),
    spec(
        "keep_checkpoints",
        &["keep_checkpoints"],
        Rule::Int {
            lo: 1,
            hi: MAX_KEEP_CHECKPOINTS,
        },
        "newest checkpoints kept in checkpoints/",
    ),
    spec(
        "eval_every",
        &["eval_every"],
        STEP_INTERVAL,
        "env steps between deterministic evaluations from every start cell (0 = only at the end)",
    ),
    spec(
        "stats_window",
        &["stats_window"],
        EPISODE_WINDOW,
        "episodes in the training success-rate window",
    ),
    spec(
        "core_init",
        &["core_init"],
        Rule::Choice(&["lab", "torch"]),
        "initial weights of the recurrent core: the lab's or PyTorch's defaults (the paper's code)",
    ),
    spec(
        "init_from",
        &["init_from"],
        Rule::Optional(&Rule::Text),
        "run folder whose final policy initialises the weights (fine-tuning; same architecture)",
    ),
    spec(
        "stop_at_success",
        &["stop_at_success"],
        Rule::Optional(&UNIT),
        "stop once the deterministic evaluation reaches this success rate",
    ),
    spec(
        "n_envs",
        &["ppo", "n_envs"],
        Rule::Int { lo: 1, hi: 4096 },
        "parallel environments N",
    ),
    spec(
        "n_steps",
        &["ppo", "n_steps"],
        Rule::Int {
            lo: 1,
            hi: 1_000_000,
        },
        "steps per env per rollout T (buffer = N*T transitions, at most 2^20)",
    ),
    spec(
        "batch_size",
        &["ppo", "batch_size"],
        Rule::Int {
            lo: 1,
            hi: 10_000_000,
        },
        "transitions per minibatch (recurrent: whole chunks of bptt_len)",
    ),
    spec(
        "n_epochs",
        &["ppo", "n_epochs"],
        Rule::Int { lo: 1, hi: 1000 },
        "passes over the buffer per update",
    ),
    spec(
        "bptt_len",
        &["ppo", "bptt_len"],
        Rule::Int {
            lo: 0,
            hi: 1_000_000,
        },
        "recurrent: BPTT chunk length in steps (0 = whole rollout sequences)",
    ),
    spec(
        "engine",
        &["ppo", "engine"],
        Rule::Choice(&["native", "burn"]),
        "implementation of the network in training: hand-written fused (native) or burn autodiff",
    ),
    spec(
        "recurrent_batches",
        &["ppo", "recurrent_batches"],
        Rule::Choice(&["chunks", "sequences"]),
        "recurrent minibatches: shuffled bptt_len chunks, or sb3-contrib's sequence windows",
    ),
    spec(
        "detach_critic",
        &["ppo", "detach_critic"],
        Rule::Bool,
        "recurrent: the value loss trains only the value head (sb3-contrib shared_lstm)",
    ),
    spec(
        "reservoir_grad_in_norm",
        &["ppo", "reservoir_grad_in_norm"],
        Rule::Bool,
        "reservoir cores: their never-applied gradients enter the grad-norm clip (the paper's code)",
    ),
    spec("gamma", &["ppo", "gamma"], UNIT, "discount per step"),
    spec("gae_lambda", &["ppo", "gae_lambda"], UNIT, "GAE lambda"),
    spec(
        "clip_range",
        &["ppo", "clip_range"],
        POSITIVE,
        "policy clip range epsilon",
    ),
    spec(
        "clip_range_vf",
        &["ppo", "clip_range_vf"],
        Rule::Optional(&POSITIVE),
        "value clip range (none: unclipped value loss)",
    ),
    spec(
        "ent_coef",
        &["ppo", "ent_coef"],
        NON_NEGATIVE,
        "entropy bonus coefficient",
    ),
    spec(
        "vf_coef",
        &["ppo", "vf_coef"],
        NON_NEGATIVE,
        "value loss coefficient",
    ),
    spec(
        "max_grad_norm",
        &["ppo", "max_grad_norm"],
        POSITIVE,
        "global gradient-norm clip",
    ),
    Spec {
        aliases: &["lr"],
        ..spec(
            "learning_rate",
            &["ppo", "learning_rate"],
            POSITIVE,
            "Adam learning rate",
        )
    },
    spec(
        "lr_schedule",
        &["ppo", "lr_schedule"],
        Rule::Choice(&["constant", "linear"]),
        "learning-rate schedule (linear: to 0 at the end of the budget)",
    ),
    spec("adam_eps", &["ppo", "adam_eps"], POSITIVE, "Adam epsilon"),
    spec(
        "target_kl",
        &["ppo", "target_kl"],
        Rule::Optional(&POSITIVE),
        "stop an update's epochs once approx-KL exceeds 1.5 * target_kl",
    ),
    spec(
        "normalize_advantage",
        &["ppo", "normalize_advantage"],
        Rule::Bool,
        "normalise advantages per minibatch",
    ),
    spec(
        "curriculum",
        &["curriculum", "kind"],
        Rule::Choice(CURRICULA),
        "curriculum (setting it starts the named one with its defaults)",
    ),
    only_with(
        LEVELLED,
        spec(
            "curriculum_thresholds",
            &["curriculum", "thresholds"],
            Rule::List(&UNIT),
            "mean reward (tolerance: share of deliveries inside the window) that ends each level",
        ),
    ),
    only_with(
        LEVELLED,
        spec(
            "curriculum_window",
            &["curriculum", "window"],
            EPISODE_WINDOW,
            "episodes averaged for the thresholds (and the tolerance curriculum's fallback)",
        ),
    ),
    only_with(
        "curriculum=multi_anchor or multi_oven",
        spec(
            "curriculum_clear_adam",
            &["curriculum", "clear_adam"],
            Rule::Bool,
            "clear Adam's moments when a level adds a counter or an oven",
        ),
    ),
    only_with(
        "curriculum=multi_timer",
        spec(
            "curriculum_warmup",
            &["curriculum", "warmup"],
            Rule::Bool,
            "level 0: one lower-bounded timer with reduced reward before the first TD",
        ),
    ),
    only_with(
        "curriculum=tolerance",
        spec(
            "curriculum_tolerance_start",
            &["curriculum", "tolerance_start"],
            UNIT,
            "relative tolerance of the first level's reward window (narrows to the task's `tolerance`)",
        ),
    ),
    only_with(
        "curriculum=tolerance",
        spec(
            "curriculum_tolerance_steps_start",
            &["curriculum", "tolerance_steps_start"],
            Rule::Num {
                ok: |x| (0.0..=100.0).contains(&x),
                allowed: "number in [0, 100] (steps)",
            },
            "constant tolerance (steps) of the first level's window (narrows to the task's `tolerance_steps`)",
        ),
    ),
    only_with(
        "curriculum=tolerance",
        spec(
            "curriculum_fallback",
            &["curriculum", "fallback"],
            UNIT,
            "share of deliveries inside the window below which the level steps back to the wider window (0 = never)",
        ),
    ),
    only_with(
        "curriculum=tolerance",
        spec(
            "curriculum_levels",
            &["curriculum", "levels"],
            Rule::Int { lo: 2, hi: 100 },
            "levels from the first window to the task's own, both included",
        ),
    ),
    only_with(
        "curriculum=uncertainty",
        spec(
            "never_ready_start",
            &["curriculum", "start"],
            UNIT,
            "initial never-ready probability",
        ),
    ),
    only_with(
        "curriculum=uncertainty",
        spec(
            "never_ready_end",
            &["curriculum", "end"],
            UNIT,
            "final never-ready probability",
        ),
    ),
    only_with(
        "curriculum=uncertainty",
        spec(
            "never_ready_ramp",
            &["curriculum", "ramp_fraction"],
            UNIT,
            "fraction of the budget over which it ramps",
        ),
    ),
];
