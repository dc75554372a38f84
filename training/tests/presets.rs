//! The training presets: the files compiled in from `training/presets/`, and every preset
//! resolving, validating and replaying exactly.

use chronocooked_models::Architecture;
use chronocooked_training::resolve;

/// The preset files are listed from `training/presets/` by the build script: every built-in
/// task has its file (and resolves its presets for every model), and every file but `common`
/// is named by a registered task (a misspelt file would otherwise be compiled in unused).
#[test]
fn every_task_has_its_preset_file_and_every_preset_file_names_a_task() {
    use chronocooked_training::ppo::presets::PRESET_FILES;
    let names: Vec<&str> = PRESET_FILES.iter().map(|(n, _)| *n).collect();
    assert!(names.contains(&"common"), "{names:?}");
    for task in chronocooked_env::registry::all_tasks() {
        if task.family == chronocooked_env::TaskFamily::External {
            continue;
        }
        assert!(
            names.contains(&task.id),
            "no presets/{}.toml in {names:?}",
            task.id
        );
        for arch in Architecture::all() {
            resolve(task.id, arch, "fast", 1, &[] as &[&str])
                .unwrap_or_else(|e| panic!("{} {arch:?}: {e}", task.id));
        }
    }
    for name in names.iter().filter(|n| **n != "common") {
        assert!(
            chronocooked_env::registry::find_task(name).is_ok(),
            "presets/{name}.toml names no registered task"
        );
    }
}

#[test]
fn every_preset_survives_its_own_validation_and_settings_replay_exactly() {
    // `validate` replays every setting through `set`; a resolved preset must pass and the
    // replay must reproduce it exactly (floats print and parse back to the same value).
    for task in [
        "FixedInterval-v0",
        "Bisection-v0",
        "MultiTimer-v0",
        "Uncertainty-v0",
    ] {
        for arch in Architecture::all() {
            for preset in ["reference", "fast"] {
                let cfg = resolve(task, arch, preset, 3, &[] as &[&str]).unwrap();
                cfg.validate()
                    .unwrap_or_else(|e| panic!("{task} {arch:?} {preset}: {e}"));
                let mut replay = chronocooked_training::TrainConfig::base(cfg.task.clone(), arch);
                replay.preset = cfg.preset.clone();
                for (k, v) in cfg.settings() {
                    replay.set(k, &v).unwrap();
                }
                assert_eq!(replay, cfg, "{task} {arch:?} {preset}");
            }
        }
    }
    let mut bad = resolve(
        "FixedInterval-v0",
        Architecture::all()[0],
        "fast",
        0,
        &[] as &[&str],
    )
    .unwrap();
    bad.ppo.gamma = 1.5;
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("gamma") && err.contains("[0, 1]"), "{err}");
}
