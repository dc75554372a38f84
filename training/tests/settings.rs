//! Settings: what `zoo show` lists is exactly what `--set` accepts, for every registered
//! model; errors name the key and what it accepts; the guide's tables are the tables the
//! code declares; run folders written before the typed timing settings still load.

use chronocooked_training::settings::ppo::PPO_SETTINGS;
use chronocooked_training::settings::timing::{TIMING_SETTINGS, TimerSettings};
use chronocooked_training::settings::{Rule, Spec};
use chronocooked_training::zoo::{Family, zoo};
use chronocooked_training::{TimingRunConfig, TrainConfig, TrainError, resolve};
use std::collections::BTreeSet;

const TASK: &str = "FixedInterval-v0";

fn ppo_config(model: &str) -> TrainConfig {
    resolve::<&str>(TASK, model.parse().unwrap(), "reference", 0, &[]).unwrap()
}

/// A value `rule` accepts, other than `avoid` where it can (so that setting it changes
/// something), built from the rule alone.
fn sample(rule: &Rule, avoid: &str) -> String {
    let candidates: Vec<String> = match rule {
        Rule::Int { lo, hi } => vec![lo.to_string(), (lo + 1).min(*hi).to_string()],
        Rule::Num { .. } => ["0.5", "0", "1", "2", "0.01"].map(String::from).to_vec(),
        Rule::Bool => vec!["true".into(), "false".into()],
        Rule::Choice(names) => names.iter().map(|s| s.to_string()).collect(),
        Rule::Text => vec!["some/run".into()],
        Rule::Optional(inner) => vec![sample(inner, avoid), "none".into()],
        Rule::List(inner) => vec![format!("{},{}", sample(inner, ""), sample(inner, ""))],
        Rule::Mapped { inner, synonyms } => {
            let mut v = vec![sample(inner, avoid)];
            v.extend(synonyms.iter().map(|(s, _)| s.to_string()));
            v
        }
    };
    let ok: Vec<&String> = candidates
        .iter()
        .filter(|c| rule.parse(c).is_some())
        .collect();
    ok.iter()
        .find(|c| c.as_str() != avoid)
        .or(ok.first())
        .map(|c| c.to_string())
        .unwrap_or_else(|| panic!("no sample value for {rule:?}"))
}

fn listed_keys(listing: &[chronocooked_training::settings::Setting]) -> BTreeSet<String> {
    listing.iter().map(|s| s.key.clone()).collect()
}

#[test]
fn every_setting_zoo_show_lists_is_accepted_by_set_and_changes_the_config() {
    let entries = zoo();
    assert!(entries.iter().any(|e| e.family == Family::Timing));
    for entry in &entries {
        assert!(
            entry.family == Family::Baseline || !entry.parameters.is_empty(),
            "{} lists no settings",
            entry.name
        );
        for s in &entry.parameters {
            let (specs, accept_listed, accept_other): (&[Spec], _, _) = match entry.family {
                Family::DeepRl => {
                    let base = ppo_config(&entry.name);
                    let spec = *chronocooked_training::settings::find(PPO_SETTINGS, &s.key)
                        .unwrap_or_else(|| panic!("{}: {} has no spec", entry.name, s.key));
                    let mut a = base.clone();
                    let listed = a.set(&s.key, &s.value).map(|_| a);
                    let other = sample(&spec.rule, &s.value);
                    let mut b = base.clone();
                    let changed = b.set(&s.key, &other).map(|_| b != base || other == s.value);
                    (PPO_SETTINGS, listed.map(|a| a == base), changed)
                }
                Family::Timing => {
                    let base = TimingRunConfig::new(
                        &chronocooked_env::Task::new(TASK).unwrap(),
                        &entry.name,
                        0,
                    );
                    let spec = *chronocooked_training::settings::find(TIMING_SETTINGS, &s.key)
                        .unwrap_or_else(|| panic!("{}: {} has no spec", entry.name, s.key));
                    let mut a = base.clone();
                    let listed = a.set(&format!("{}={}", s.key, s.value)).map(|_| {
                        // The listed default, set explicitly, builds the same agent.
                        serde_json::to_value(a.build_agent().unwrap()).unwrap()
                            == serde_json::to_value(base.build_agent().unwrap()).unwrap()
                    });
                    let other = sample(&spec.rule, &s.value);
                    let mut b = base.clone();
                    let changed = b.set(&format!("{}={other}", s.key)).map(|_| {
                        b.listing().iter().any(|x| {
                            x.key == s.key && spec.rule.parse(&x.value) == spec.rule.parse(&other)
                        })
                    });
                    (TIMING_SETTINGS, listed, changed)
                }
                Family::Baseline => panic!("baseline {} lists {}", entry.name, s.key),
            };
            assert!(
                specs.iter().any(|x| x.key == s.key),
                "{}: {}",
                entry.name,
                s.key
            );
            assert!(
                matches!(accept_listed, Ok(true)),
                "{}: --set {}={} (the listed value): {accept_listed:?}",
                entry.name,
                s.key,
                s.value
            );
            assert!(
                matches!(accept_other, Ok(true)),
                "{}: --set {} to another value: {accept_other:?}",
                entry.name,
                s.key
            );
        }
    }
}

#[test]
fn every_key_set_accepts_is_listed() {
    for entry in zoo() {
        match entry.family {
            Family::DeepRl => {
                // Each curriculum lists its own parameters: try the keys on all three.
                for curriculum in chronocooked_training::settings::ppo::CURRICULA {
                    let mut cfg = ppo_config(&entry.name);
                    cfg.set("curriculum", curriculum).unwrap();
                    let listed = listed_keys(&cfg.listing());
                    for spec in PPO_SETTINGS {
                        let mut c = cfg.clone();
                        for key in std::iter::once(&spec.key).chain(spec.aliases) {
                            let accepted = c.set(key, &sample(&spec.rule, "")).is_ok();
                            assert_eq!(
                                accepted,
                                listed.contains(spec.key),
                                "{} with curriculum={curriculum}: {key}",
                                entry.name
                            );
                        }
                    }
                }
            }
            Family::Timing => {
                let cfg = TimingRunConfig::new(
                    &chronocooked_env::Task::new(TASK).unwrap(),
                    &entry.name,
                    0,
                );
                let listed = listed_keys(&cfg.listing());
                assert_eq!(listed, listed_keys(&entry.parameters), "{}", entry.name);
                for spec in TIMING_SETTINGS {
                    let mut c = cfg.clone();
                    let accepted = c
                        .set(&format!("{}={}", spec.key, sample(&spec.rule, "")))
                        .is_ok();
                    assert_eq!(
                        accepted,
                        listed.contains(spec.key),
                        "{}: {}",
                        entry.name,
                        spec.key
                    );
                }
            }
            Family::Baseline => assert!(entry.parameters.is_empty()),
        }
    }
}

/// Paths of the leaves of a serialised configuration (objects walked, anything else — an
/// empty object too, e.g. a task with no parameter set — a leaf).
fn leaves(v: &serde_json::Value, prefix: &mut Vec<String>, out: &mut BTreeSet<Vec<String>>) {
    match v {
        serde_json::Value::Object(m) if !m.is_empty() => {
            for (k, x) in m {
                prefix.push(k.clone());
                leaves(x, prefix, out);
                prefix.pop();
            }
        }
        _ => {
            out.insert(prefix.clone());
        }
    }
}

fn spec_paths(specs: &[Spec]) -> BTreeSet<Vec<String>> {
    specs
        .iter()
        .map(|s| s.path.iter().map(|p| p.to_string()).collect())
        .collect()
}

/// Removes the fields below each of `names` (each must have some).
fn remove_fields(fields: &mut BTreeSet<Vec<String>>, names: &[&str]) {
    for name in names {
        let before = fields.len();
        fields.retain(|f| f[0] != *name);
        assert!(fields.len() < before, "no field {name}");
    }
}

#[test]
fn every_field_of_the_configurations_is_a_setting_or_a_named_exception() {
    // PPO: every field of every curriculum; not settings: the task, model and preset
    // (`--task`, `--model`, `--preset`) and the task parameters (`env.<param>`).
    let mut fields = BTreeSet::new();
    for curriculum in chronocooked_training::settings::ppo::CURRICULA {
        let mut cfg = ppo_config("lstm125");
        cfg.set("curriculum", curriculum).unwrap();
        leaves(
            &serde_json::to_value(&cfg).unwrap(),
            &mut vec![],
            &mut fields,
        );
    }
    remove_fields(&mut fields, &["task", "model", "preset", "env"]);
    assert_eq!(fields, spec_paths(PPO_SETTINGS));
    // Timing: every field of every family; not settings: kind, task, model, seed, env and
    // the timer's family tag.
    let mut fields = BTreeSet::new();
    for model in ["ddm", "sbf", "timecells-ms"] {
        let cfg = TimingRunConfig::new(&chronocooked_env::Task::new(TASK).unwrap(), model, 0);
        leaves(
            &serde_json::to_value(&cfg).unwrap(),
            &mut vec![],
            &mut fields,
        );
    }
    remove_fields(&mut fields, &["kind", "task", "model", "seed", "env"]);
    assert!(fields.remove(["agent", "timer", "family"].map(String::from).as_slice()));
    assert_eq!(fields, spec_paths(TIMING_SETTINGS));
}

#[test]
fn an_unknown_key_or_a_bad_value_names_the_key_and_what_it_accepts() {
    let mut cfg = ppo_config("cnn-mlp");
    let err = cfg.set("gama", "0.9").unwrap_err();
    assert!(matches!(err, TrainError::UnknownKey { .. }), "{err:?}");
    let msg = err.to_string();
    assert!(
        msg.contains("`gama`") && msg.contains("gamma") && msg.contains("n_envs"),
        "{msg}"
    );
    for (key, value, allowed) in [
        ("gamma", "1.5", "number in [0, 1]"),
        ("gamma", "high", "number in [0, 1]"),
        ("obs", "rgb", "codes|onehot"),
        ("n_envs", "0", "integer 1..=4096"),
        ("target_kl", "-1", "none, or number > 0"),
        ("normalize_advantage", "yes", "true or false"),
        ("curriculum", "easy", "none|multi_timer|uncertainty"),
        ("curriculum_window", "5", "only with curriculum=multi_timer"),
    ] {
        let msg = cfg.set(key, value).unwrap_err().to_string();
        assert!(
            msg.contains(&format!("`{key}`"))
                && msg.contains(&format!("`{value}`"))
                && msg.contains(allowed),
            "{key}={value}: {msg}"
        );
    }
    // A config.json edited by hand gets the same rule, naming the same key.
    let mut edited = ppo_config("cnn-mlp");
    edited.ppo.gae_lambda = 2.0;
    let msg = edited.validate().unwrap_err().to_string();
    assert!(
        msg.contains("`gae_lambda`") && msg.contains("[0, 1]"),
        "{msg}"
    );

    let mut sbf = TimingRunConfig::new(&chronocooked_env::Task::new(TASK).unwrap(), "sbf", 0);
    let err = sbf.set("noise=0.1").unwrap_err().to_string();
    assert!(
        err.contains("`noise`") && err.contains("only with ddm"),
        "{err}"
    );
    let err = sbf.set("threshold=0.5").unwrap_err().to_string();
    assert!(
        err.contains("`threshold`") && err.contains("clock_noise") && err.contains("episodes"),
        "{err}"
    );
    let err = sbf.set("decision_rule=median").unwrap_err().to_string();
    assert!(
        err.contains("`decision_rule`") && err.contains("ratio|difference"),
        "{err}"
    );
    let err = sbf.set("probe=1").unwrap_err().to_string();
    assert!(err.contains("`probe`") && err.contains("[0, 1)"), "{err}");
}

#[test]
fn timing_settings_are_typed_per_family_and_old_run_folders_still_load() {
    let mut ddm = TimingRunConfig::new(&chronocooked_env::Task::new(TASK).unwrap(), "ddm", 3);
    ddm.set("noise=0.06").unwrap();
    ddm.set("decision_rule=difference").unwrap();
    ddm.set("q_init=0.5").unwrap();
    assert!(matches!(
        ddm.agent.timer,
        TimerSettings::Ddm {
            noise: Some(n),
            memory_noise: None,
            reproduction_rate: None,
        } if n == 0.06
    ));
    let agent = ddm.build_agent().unwrap();
    assert_eq!(agent.learner.q_init, 0.5);
    // New config.json: the typed settings round-trip.
    let text = serde_json::to_string(&ddm).unwrap();
    let back: TimingRunConfig = serde_json::from_str(&text).unwrap();
    assert_eq!(back, ddm);
    // A config.json written before the typed settings (a list of `key=value` overrides).
    let mut old: serde_json::Value = serde_json::from_str(&text).unwrap();
    old["agent"] = serde_json::json!(["noise=0.06", "decision_rule=difference", "q_init=0.5"]);
    let loaded: TimingRunConfig = serde_json::from_value(old.clone()).unwrap();
    assert_eq!(loaded, ddm);
    old["agent"] = serde_json::json!(["clock_noise=0"]);
    assert!(
        serde_json::from_value::<TimingRunConfig>(old).is_err(),
        "ddm has no clock noise"
    );
}

/// The table between `<!-- settings:NAME -->` and `<!-- /settings:NAME -->` in a guide page.
fn readme_table(readme: &str, name: &str) -> String {
    let open = format!("<!-- settings:{name} -->\n");
    let start = readme
        .find(&open)
        .unwrap_or_else(|| panic!("the guide page lacks {open}"))
        + open.len();
    let end = readme[start..]
        .find(&format!("<!-- /settings:{name} -->"))
        .unwrap()
        + start;
    readme[start..end].to_string()
}

#[test]
fn the_guide_settings_tables_are_generated_from_the_settings() {
    let page = |name: &str| {
        std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../docs/{name}")),
        )
        .unwrap()
    };
    let ppo = chronocooked_training::TrainConfig::settings_markdown();
    let timing = chronocooked_training::TimingRunConfig::settings_markdown();
    for key in ["gamma", "curriculum_window", "never_ready_ramp", "engine"] {
        assert!(ppo.contains(&format!("| `{key}` |")), "{key}");
    }
    for key in [
        "episodes",
        "alpha",
        "noise",
        "memory_noise",
        "clock_noise",
        "q_init",
    ] {
        assert!(timing.contains(&format!("| `{key}` |")), "{key}");
    }
    for (name, file, table) in [
        ("ppo", "training.md", ppo),
        ("timing", "timing-models.md", timing),
    ] {
        assert_eq!(
            readme_table(&page(file), name),
            table,
            "docs/{file}'s {name} settings table differs from the code's; the table the code declares:\n{table}"
        );
    }
}

/// Every count, size and duration setting has a documented bound sized from what the lab
/// can do, never the integer type's maximum (a typo or a corrupted file must be refused at
/// validation, not start a run that cannot end or fill the disk). Seeds are the exception:
/// every `u64` is a seed.
#[test]
fn every_count_setting_is_bounded_below_the_types_maximum() {
    for s in PPO_SETTINGS.iter().chain(TIMING_SETTINGS) {
        let mut rule = s.rule;
        while let Rule::Optional(inner) = rule {
            rule = *inner;
        }
        if let Rule::Int { hi, .. } = rule {
            if s.key == "seed" {
                continue;
            }
            assert!(hi < u64::MAX / 2, "{}: no upper bound", s.key);
            assert!(
                s.rule.allowed().contains(&hi.to_string()),
                "{}: the bound {hi} is not in its documented range {}",
                s.key,
                s.rule.allowed()
            );
        }
    }
    let mut cfg = ppo_config("cnn-mlp");
    let err = cfg
        .set("stats_window", "18446744073709551615")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("stats_window") && err.contains("1000000"),
        "{err}"
    );
}

/// The reproduction task's training defaults: every timing model anneals its step size to
/// 0.005 over 60,000 episodes; the visit-count step floor (ω 0.85) is on for the models whose
/// responses are learned (the time cells) and off for the gated clocks (drift-diffusion,
/// SBF) and on every other task.
#[test]
fn the_visit_count_floor_is_a_reproduction_default_of_the_time_cells_only() {
    use chronocooked_env::Task;
    let reproduction = Task::new("Reproduction-v0").unwrap();
    for (model, floor) in [
        ("ddm", 0.0),
        ("sbf", 0.0),
        ("timecells-csc", 0.85),
        ("timecells-ms", 0.85),
        ("timecells-laplace", 0.85),
    ] {
        let cfg = TimingRunConfig::new(&reproduction, model, 1);
        assert_eq!(cfg.train.visit_power, floor, "{model}");
        assert_eq!(cfg.train.alpha_end, Some(0.005), "{model}");
        assert_eq!(cfg.train.episodes, 60_000, "{model}");
        let fixed = TimingRunConfig::new(&Task::new(TASK).unwrap(), model, 1);
        assert_eq!(fixed.train.visit_power, 0.0, "{model} on {TASK}");
    }
    // An override still wins.
    let mut cfg = TimingRunConfig::new(&reproduction, "ddm", 1);
    cfg.set("visit_power=0.7").unwrap();
    assert_eq!(cfg.train.visit_power, 0.7);
}

/// Defect (issue #68): `train --model ddm --task Bisection-v0 --set env.short=20 --set
/// env.long=40` failed on the first key, because the timing path checked the anchors across
/// keys after each one (20 > the default long 12); the PPO path accepted it. Both paths now
/// apply every key, then check the whole, in either order, and still refuse a bad whole.
#[test]
fn overrides_valid_together_are_accepted_whatever_their_order_on_both_paths() {
    use chronocooked_env::Task;
    let bisection = || Task::new("Bisection-v0").unwrap();
    for order in [
        ["env.short=20", "env.long=40"],
        ["env.long=40", "env.short=20"],
    ] {
        for model in ["ddm", "sbf", "timecells-csc"] {
            let mut cfg = TimingRunConfig::new(&bisection(), model, 0);
            for kv in order {
                cfg.set(kv).unwrap_or_else(|e| panic!("{model} {kv}: {e}"));
            }
            cfg.validate()
                .unwrap_or_else(|e| panic!("{model} {order:?}: {e}"));
            let text = serde_json::to_string(&cfg.task.config().unwrap()).unwrap();
            assert!(
                text.contains("\"short\":20") && text.contains("\"long\":40"),
                "{text}"
            );
        }
        let mut ppo = TrainConfig::base(bisection(), "cnn-mlp".parse().unwrap());
        for kv in order {
            let (k, v) = kv.split_once('=').unwrap();
            ppo.set(k, v).unwrap();
        }
        ppo.validate().unwrap();
    }
    let mut bad = TimingRunConfig::new(&bisection(), "ddm", 0);
    bad.set("env.short=20").unwrap();
    let msg = bad.validate().unwrap_err().to_string();
    assert!(msg.contains("short") && msg.contains("long"), "{msg}");
}
