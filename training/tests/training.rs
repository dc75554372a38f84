//! Training-crate oracles: GAE, PPO loss and its gradients, recurrent masking, CTRNN decay,
//! the split-graph BPTT gradients, save/load, determinism, resume, and short real runs.

use burn::module::Module;
use burn::tensor::{Int, Tensor, TensorData};
use chronocooked_models::{
    Architecture, CoreConfig, CoreKind, PolicyConfig, cpu, cpu_autodiff, to_vec,
};
use chronocooked_training::ppo::gae::compute_gae;
use chronocooked_training::ppo::loss::{
    LossBatch, LossCoefs, OutputBatch, ppo_loss, ppo_output_grads,
};
use chronocooked_training::ppo::params::{flat_grads, param_offset};
use chronocooked_training::{Check, Silent, Trainer, load_policy, resolve, run_training};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

#[test]
fn gae_matches_hand_computation_with_boundary_and_truncation() {
    // One env, 4 steps, γ = 0.5, λ = 0.5. The episode ends at t = 1 (terminated) and the
    // next one is truncated at t = 3 with bootstrap value 2 already added: r3 = 1 + 0.5·2.
    let rewards = [1.0, 2.0, 0.0, 2.0];
    let values = [0.5, 1.0, 0.25, 0.5];
    let dones = [false, true, false, true];
    let (adv, ret) = compute_gae(&rewards, &values, &dones, &[10.0], 0.5, 0.5);
    // t=3: δ = 2 − 0.5 = 1.5 (done: no bootstrap from last_values), A = 1.5
    // t=2: δ = 0 + 0.5·0.5 − 0.25 = 0, A = 0 + 0.25·1.5 = 0.375
    // t=1: δ = 2 − 1 = 1 (done), A = 1
    // t=0: δ = 1 + 0.5·1 − 0.5 = 1, A = 1 + 0.25·1 = 1.25
    let want = [1.25, 1.0, 0.375, 1.5];
    for i in 0..4 {
        assert!(
            close(adv[i] as f64, want[i], 1e-6),
            "adv[{i}] {} vs {}",
            adv[i],
            want[i]
        );
        assert!(close(ret[i] as f64, want[i] + values[i] as f64, 1e-6));
    }
    // Not done at the end: bootstraps from last_values.
    let (adv2, _) = compute_gae(&[0.0], &[1.0], &[false], &[3.0], 0.9, 0.95);
    assert!(close(adv2[0] as f64, 0.9 * 3.0 - 1.0, 1e-6));
}

#[test]
fn ppo_loss_terms_match_hand_computation() {
    // Two samples, two actions. Sample 0: ratio inside the clip range; sample 1: ratio 2 with
    // positive advantage → clipped at 1.2.
    let logits = [0.0f32, 0.0, (2f32).ln(), 0.0];
    let lp0 = (0.5f64).ln(); // uniform
    let p1 = 2.0 / 3.0; // action 0 of sample 1
    let old = [lp0 as f32, (p1 / 2.0f64).ln() as f32];
    let c = LossCoefs {
        clip_range: 0.2,
        clip_range_vf: None,
        ent_coef: 0.1,
        vf_coef: 0.5,
    };
    let (s, dl, dv) = ppo_output_grads(
        OutputBatch {
            logits: &logits,
            values: &[1.0, 0.0],
            actions: &[1, 0],
            old_log_prob: &old,
            advantages: &[-1.0, 2.0],
            returns: &[2.0, 1.0],
            old_values: &[0.0, 0.0],
            mask: &[1.0, 1.0],
        },
        c,
    );
    // policy: −mean(min(−1·1, −1·1), min(2·2, 2·1.2)) = −(−1 + 2.4)/2 = −0.7
    assert!(close(s.policy_loss, -0.7, 1e-6), "{}", s.policy_loss);
    // value: mean((2−1)², (1−0)²) = 1
    assert!(close(s.value_loss, 1.0, 1e-6));
    let h0 = 2f64.ln();
    let h1 = -(p1 * p1.ln() + (1.0 - p1) * (1.0 - p1).ln());
    assert!(close(s.entropy_loss, -(h0 + h1) / 2.0, 1e-6));
    // approx_kl = mean((r−1) − ln r) with r = 1, 2
    assert!(close(s.approx_kl, (1.0 - 2f64.ln()) / 2.0, 1e-6));
    assert!(close(s.clip_fraction, 0.5, 1e-9));
    assert!(close(s.loss, -0.7 - 0.1 * (h0 + h1) / 2.0 + 0.5, 1e-6));
    // value gradient: −2·0.5·(R − v)/n
    assert!(close(dv[0] as f64, -0.5, 1e-6) && close(dv[1] as f64, -0.5, 1e-6));
    // clipped sample: only the entropy term reaches its logits.
    let ent_grad = |p: f64, h: f64| 0.1 * p * (p.ln() + h) / 2.0;
    assert!(close(dl[2] as f64, ent_grad(p1, h1), 1e-5), "{}", dl[2]);

    // The tensor implementation gives the same loss and, through autodiff, the same ∂L/∂logits.
    let d = cpu_autodiff();
    let lt = Tensor::<2>::from_data(TensorData::new(logits.to_vec(), [2, 2]), &d).require_grad();
    let vt = Tensor::<2>::from_data(TensorData::new(vec![1.0f32, 0.0], [2, 1]), &d).require_grad();
    let f = |v: Vec<f32>| Tensor::<1>::from_data(TensorData::new(v, [2]), &d);
    let out = ppo_loss(
        LossBatch {
            logits: lt.clone(),
            values: vt.clone(),
            actions: Tensor::<2, Int>::from_data(TensorData::new(vec![1i64, 0], [2, 1]), &d),
            old_log_prob: f(old.to_vec()),
            advantages: f(vec![-1.0, 2.0]),
            returns: f(vec![2.0, 1.0]),
            old_values: f(vec![0.0, 0.0]),
            mask: f(vec![1.0, 1.0]),
            n_valid: 2.0,
        },
        c,
    );
    assert!(close(out.policy_loss as f64, s.policy_loss, 1e-5));
    let grads = out.loss.backward();
    let g = to_vec(&lt.grad(&grads).unwrap());
    for (a, b) in g.iter().zip(&dl) {
        assert!(
            close(*a as f64, *b as f64, 1e-4),
            "autodiff {a} vs analytic {b}"
        );
    }
    let gv = to_vec(&vt.grad(&grads).unwrap());
    assert!(close(gv[0] as f64, dv[0] as f64, 1e-5));
}

#[test]
fn ctrnn_with_zero_weights_follows_exact_euler_decay() {
    let d = cpu();
    let mut core = CoreConfig::new(CoreKind::Ctrnn, 3, 4).init(&mut rand_seed(1), &d);
    core = core.map(&mut Zeroer);
    // Zeroer zeroes every parameter, including τ_raw → softplus(0) = ln 2.
    let alpha = 0.1f64 / 2f64.ln();
    let h0 = vec![1.0f32, -0.5, 0.25, 2.0];
    let mut st = chronocooked_models::CoreState::from_vecs(h0.clone(), None, 1, &d);
    for n in 1..=30 {
        let x = Tensor::<2>::zeros([1, 3], &d);
        let (_, s) = core.step(x, st, None);
        st = s;
        let h = to_vec(&st.h);
        for (k, &v) in h.iter().enumerate() {
            let want = (1.0 - alpha).powi(n) * h0[k] as f64;
            assert!(
                (v as f64 - want).abs() < 1e-5,
                "step {n} unit {k}: {v} vs {want}"
            );
        }
    }
}

struct Zeroer;
impl burn::module::ModuleMapper for Zeroer {
    fn map_float<const D: usize>(
        &mut self,
        p: burn::module::Param<Tensor<D>>,
    ) -> burn::module::Param<Tensor<D>> {
        p.map(|t| t.zeros_like())
    }
}

fn rand_seed(s: u64) -> chronocooked_models::deep::init::InitRng {
    use rand::SeedableRng;
    chronocooked_models::deep::init::InitRng::seed_from_u64(s)
}

fn seq_inputs(t: usize, b: usize, cells: usize, seed: u64) -> Vec<f32> {
    let mut x = seed.wrapping_mul(2654435761) | 1;
    (0..t * b * cells * 6)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % 7) as f32
        })
        .collect()
}

#[test]
fn recurrent_state_does_not_leak_across_an_episode_start() {
    for kind in CoreKind::ALL {
        let d = cpu_autodiff();
        let pc = PolicyConfig::new(Architecture::recurrent(kind, 16), 15, 6, 6);
        let model = pc.init(3, &d);
        let (t, b) = (6, 2);
        let obs = seq_inputs(t, b, 15, 5);
        let obs_t =
            Tensor::<4>::from_data(TensorData::new(obs.clone(), [t, b, 15, 6]), &d).require_grad();
        // Episode start at t = 3 for both sequences.
        let keep: Vec<Option<Tensor<2>>> = (0..t)
            .map(|i| (i == 3).then(|| Tensor::<2>::zeros([b, 1], &d)))
            .collect();
        let st = model.zero_state(b, &d).map(|s| {
            let h = Tensor::<2>::ones([b, 16], &d);
            chronocooked_models::CoreState {
                c: s.c.map(|c| c.ones_like()),
                h,
            }
        });
        let out = model.forward_seq(obs_t.clone(), st, &keep);
        // Outputs from t = 3 equal a fresh zero-state run on the second half.
        let tail = Tensor::<4>::from_data(
            TensorData::new(obs[3 * b * 90..].to_vec(), [3, b, 15, 6]),
            &d,
        );
        let fresh = model.forward_seq(tail, None, &[None, None, None]);
        let all = to_vec(&out.logits);
        let late = &all[3 * b * 6..];
        for (x, y) in late.iter().zip(to_vec(&fresh.logits)) {
            assert!((x - y).abs() < 1e-5, "{kind}: state leaked ({x} vs {y})");
        }
        // Gradients of the late outputs w.r.t. the early observations are exactly zero.
        let late_sum =
            out.logits.narrow(0, 3 * b, 3 * b).sum() + out.values.narrow(0, 3 * b, 3 * b).sum();
        let grads = late_sum.backward();
        let g = to_vec(&obs_t.grad(&grads).unwrap());
        let (early, later) = g.split_at(3 * b * 90);
        assert!(
            early.iter().all(|&v| v == 0.0),
            "{kind}: gradient crossed the episode start"
        );
        assert!(
            later.iter().any(|&v| v != 0.0),
            "{kind}: no gradient at all"
        );
    }
}

#[test]
fn split_graph_bptt_gradients_equal_plain_autodiff() {
    for kind in CoreKind::ALL {
        let d = cpu_autodiff();
        let pc = PolicyConfig::new(Architecture::recurrent(kind, 12), 15, 6, 6);
        let model = pc.init(11, &d);
        let (t, b) = (5, 3);
        let obs = seq_inputs(t, b, 15, 9);
        let keep: Vec<Option<Tensor<2>>> = (0..t)
            .map(|i| {
                (i == 2).then(|| {
                    Tensor::<2>::from_data(TensorData::new(vec![1.0f32, 0.0, 1.0], [b, 1]), &d)
                })
            })
            .collect();
        let w: Vec<f32> = (0..t * b * 6)
            .map(|i| ((i * 37 % 11) as f32 - 5.0) / 7.0)
            .collect();
        let wv: Vec<f32> = (0..t * b)
            .map(|i| ((i * 13 % 5) as f32 - 2.0) / 3.0)
            .collect();
        let objective = |out: &chronocooked_models::PolicyOutput| {
            (out.logits.clone()
                * Tensor::<2>::from_data(TensorData::new(w.clone(), [t * b, 6]), &d))
            .sum()
                + (out.values.clone()
                    * Tensor::<2>::from_data(TensorData::new(wv.clone(), [t * b, 1]), &d))
                .sum()
        };
        let x = || Tensor::<4>::from_data(TensorData::new(obs.clone(), [t, b, 15, 6]), &d);
        let plain = model.forward_seq(x(), None, &keep);
        let g_plain = flat_grads(&model, &objective(&plain).backward());
        let split = model.forward_seq_train(x(), None, &keep, false);
        let l1 = to_vec(&split.logits);
        assert_eq!(l1, to_vec(&plain.logits), "{kind}: forward differs");
        let grads = objective(&split).backward();
        let mut g = flat_grads(&model, &grads);
        let aux = split.aux.unwrap();
        let id = aux.weight_id;
        let (dw, sur) = aux.finish(&grads);
        let dw = to_vec(&dw.unwrap());
        let off = param_offset(&model, id).unwrap();
        g[off..off + dw.len()]
            .iter_mut()
            .zip(&dw)
            .for_each(|(a, b)| *a += b);
        let g2 = flat_grads(&model, &sur.unwrap().backward());
        g.iter_mut().zip(&g2).for_each(|(a, b)| *a += b);
        for (i, (a, b)) in g.iter().zip(&g_plain).enumerate() {
            assert!(
                (a - b).abs() <= 1e-4 * (1.0 + b.abs()),
                "{kind} param {i}: {a} vs {b}"
            );
        }
    }
}

fn tiny_cfg(model: &str, steps: u64, seed: u64) -> chronocooked_training::TrainConfig {
    resolve(
        "FixedInterval-v0",
        model.parse().unwrap(),
        "reference",
        seed,
        &[
            format!("total_steps={steps}"),
            "n_steps=200".into(),
            "n_epochs=3".into(),
            "env.td=4".into(),
            "checkpoint_every=400".into(),
        ],
    )
    .unwrap()
}

#[test]
fn same_seed_gives_identical_learning_curves_and_resume_is_exact() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-train-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for model in ["lstm8", "cnn-mlp", "cnn-mlp-stack4"] {
        let strip = |t: &Trainer| -> Vec<String> {
            t.state()
                .curve
                .iter()
                .map(|r| {
                    format!(
                        "{} {} {} {} {} {}",
                        r.env_steps,
                        r.ep_return_mean,
                        r.policy_loss,
                        r.value_loss,
                        r.approx_kl,
                        r.entropy
                    )
                })
                .collect()
        };
        let mut a = Trainer::new(tiny_cfg(model, 1000, 4).check().unwrap()).unwrap();
        let mut b = Trainer::new(tiny_cfg(model, 1000, 4).check().unwrap()).unwrap();
        while !a.finished() {
            a.update().unwrap();
            b.update().unwrap();
        }
        assert_eq!(strip(&a), strip(&b), "{model}: reruns differ");
        assert_eq!(a.state().theta, b.state().theta);
        // Uninterrupted run folder vs a run stopped after its 400-step checkpoint and resumed.
        let full = dir.join(format!("{model}-full"));
        run_training(
            Some(tiny_cfg(model, 1000, 4).check().unwrap()),
            &full,
            "test",
            &mut Silent,
        )
        .unwrap();
        let cut = dir.join(format!("{model}-cut"));
        run_training(
            Some(tiny_cfg(model, 400, 4).check().unwrap()),
            &cut,
            "test",
            &mut Silent,
        )
        .unwrap();
        // Extend the budget as a user would after an interruption (`train --resume --steps`).
        let open = chronocooked_training::RunDir::open(&cut).unwrap();
        assert!(open.extend_budget(300).is_err(), "a budget cannot shrink");
        assert_eq!(open.extend_budget(1000).unwrap().total_steps, 1000);
        std::fs::remove_file(cut.join("model.bpk")).unwrap();
        run_training(None, &cut, "test --resume", &mut Silent).unwrap();
        let last = |d: &std::path::Path| {
            let run = chronocooked_training::RunDir::open(d).unwrap();
            run.latest_state().unwrap().unwrap()
        };
        let (sf, sc) = (last(&full), last(&cut));
        assert_eq!(sf.steps, 1000);
        assert_eq!(sf.theta, sc.theta, "{model}: resumed run ended elsewhere");
        assert_eq!(sf.adam.m, sc.adam.m);
        let csv = |d: &std::path::Path| -> Vec<String> {
            std::fs::read_to_string(d.join("curves.csv"))
                .unwrap()
                .lines()
                .map(|l| {
                    l.split(',')
                        .enumerate()
                        .filter(|(i, _)| !(2..=5).contains(i))
                        .map(|(_, v)| v)
                        .collect::<Vec<_>>()
                        .join(",")
                })
                .collect()
        };
        assert_eq!(
            csv(&full),
            csv(&cut),
            "{model}: learning curves differ after resume"
        );
        // save → load → identical greedy actions on the evaluation protocol.
        let (p1, _, c1) = load_policy(&full).unwrap();
        let task = c1.task.config().unwrap();
        let e1 = chronocooked_training::evaluate_policy(&p1, &task, c1.obs, &[4]).unwrap();
        let mut t2 = Trainer::new(tiny_cfg(model, 1000, 4).check().unwrap()).unwrap();
        while !t2.finished() {
            t2.update().unwrap();
        }
        let e2 = chronocooked_training::evaluate_policy(&t2.policy(), &task, c1.obs, &[4]).unwrap();
        assert_eq!(e1, e2, "{model}: loaded policy acts differently");
        let _ = p1.valid();
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A short real training run (reference preset, FI TD = 4): the deterministic evaluation from
/// every start cell must reach ≥ 90% successful deliveries. Seed 0 solves at 25k (CNN-MLP)
/// and 50k (LSTM125) env steps on the development machine; the budgets leave room.
#[test]
fn cnn_mlp_and_lstm_learn_fixed_interval_td4() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-learn-{}", std::process::id()));
    for (model, steps, every) in [
        ("cnn-mlp", 60_000u64, 5_000u64),
        ("lstm125", 150_000, 10_000),
    ] {
        let cfg = resolve(
            "FixedInterval-v0",
            model.parse().unwrap(),
            "reference",
            0,
            &[
                format!("total_steps={steps}"),
                format!("eval_every={every}"),
                "stop_at_success=0.9".into(),
                "env.td=4".into(),
            ],
        )
        .unwrap();
        let s = run_training(
            Some(cfg.check().unwrap()),
            &dir.join(model),
            "test",
            &mut Silent,
        )
        .unwrap();
        assert!(
            s.eval_success >= 0.9,
            "{model}: deterministic success {:.2} after {} steps",
            s.eval_success,
            s.env_steps
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A multi-timer curriculum run with thresholds every run passes: levels change after
/// `window` episodes, so a 12-update run crosses several.
fn curriculum_cfg(steps: u64) -> chronocooked_training::TrainConfig {
    resolve(
        "MultiTimer-v0",
        "lstm8".parse().unwrap(),
        "reference",
        3,
        &[
            format!("total_steps={steps}"),
            "n_steps=250".into(),
            "n_epochs=2".into(),
            "env.tds=2,4,6".into(),
            "env.mode=exact".into(),
            "env.reduced_reward=0".into(),
            "env.num_timers=3".into(),
            "curriculum_thresholds=0,0,0".into(),
            "curriculum_window=10".into(),
        ],
    )
    .unwrap()
}

#[test]
fn a_curriculum_level_keeps_the_policy_whose_rollout_passed_it() {
    let mut t = Trainer::new(curriculum_cfg(10000).check().unwrap()).unwrap();
    let mut left = Vec::new();
    while !t.finished() {
        let before = t.state().theta.clone();
        let level = t.state().curriculum_level;
        t.update().unwrap();
        if let Some((l, policy)) = t.take_left_level() {
            assert_eq!(l, level, "the level left is the one the update started in");
            assert_eq!(t.state().curriculum_level, level + 1);
            // The paper's callback saves at the rollout's end, before the optimisation:
            // the policy that collected the passing episodes, not the updated one.
            let kept = chronocooked_training::ppo::params::flat_params(&policy);
            assert_eq!(
                kept, before,
                "level {l}: not the policy that collected the rollout"
            );
            assert_ne!(
                kept,
                t.state().theta,
                "level {l}: the update changed nothing"
            );
            assert!(t.take_left_level().is_none(), "taken twice");
            left.push(l);
        } else {
            assert_eq!(t.state().curriculum_level, level);
        }
    }
    assert_eq!(
        left,
        [0, 1, 2],
        "warm-up, one timer and two timers are left in order"
    );
}

#[test]
fn a_curriculum_run_folder_keeps_every_level_and_the_last_is_the_final_policy() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cc-levels-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    run_training(
        Some(curriculum_cfg(10000).check().unwrap()),
        &dir,
        "test",
        &mut Silent,
    )
    .unwrap();
    let run = chronocooked_training::RunDir::open(&dir).unwrap();
    assert_eq!(run.saved_levels(), [0, 1, 2, 3]);
    let (final_policy, _, _) = load_policy(&dir).unwrap();
    let (last, _, _) = chronocooked_training::run_dir::load_level_policy(&dir, 3).unwrap();
    let flat = chronocooked_training::ppo::params::flat_params;
    assert_eq!(flat(&last), flat(&final_policy));
    let (first, _, _) = chronocooked_training::run_dir::load_level_policy(&dir, 0).unwrap();
    assert_ne!(flat(&first), flat(&final_policy));
    let missing = chronocooked_training::run_dir::load_level_policy(&dir, 4)
        .err()
        .unwrap()
        .to_string();
    assert!(missing.contains("level 4"), "{missing}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A multi-anchor (or multi-oven) curriculum run whose thresholds every run passes.
fn growth_cfg(task: &str, sets: &[&str], steps: u64) -> chronocooked_training::TrainConfig {
    let mut all: Vec<String> = vec![
        format!("total_steps={steps}"),
        "n_steps=250".into(),
        "n_epochs=2".into(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    if sets.iter().any(|s| s.starts_with("curriculum_thresholds")) {
        all.push("curriculum_window=10".into());
    }
    resolve(task, "lstm8".parse().unwrap(), "reference", 5, &all).unwrap()
}

#[test]
fn growth_curricula_add_counters_and_ovens_and_resume_at_their_level() {
    for (task, sets, levels, clears) in [
        (
            "MultiAnchor-v0",
            &[
                "curriculum=multi_anchor",
                "env.anchors=2,4,7,11",
                "curriculum_thresholds=0,0",
            ][..],
            2usize,
            true,
        ),
        (
            "MultiOven-v0",
            &[
                "curriculum=multi_oven",
                "env.ovens=3",
                "env.short=2",
                "env.long=5",
                "curriculum_thresholds=0,0",
            ][..],
            2,
            false,
        ),
    ] {
        let cfg = growth_cfg(task, sets, 6000);
        let mut t = Trainer::new(cfg.clone().check().unwrap()).unwrap();
        assert_eq!(
            t.state().curriculum_level,
            0,
            "{task}: starts at the fewest"
        );
        let mut seen = vec![0usize];
        let mut adam_t_at_switch = Vec::new();
        let mut per_update = None;
        while !t.finished() {
            let level = t.state().curriculum_level;
            t.update().unwrap();
            per_update.get_or_insert(t.state().adam.t);
            if t.state().curriculum_level != level {
                seen.push(t.state().curriculum_level);
                adam_t_at_switch.push(t.state().adam.t);
                // The level's policy is kept, as the multi-timer's.
                assert!(t.take_left_level().is_some());
            }
        }
        assert_eq!(
            seen,
            (0..=levels).collect::<Vec<_>>(),
            "{task}: levels in order"
        );
        // Cleared at the rollout's end (as the reference's callback), Adam has then taken
        // only that update's steps; kept, it goes on counting.
        let one = per_update.unwrap();
        for &steps in &adam_t_at_switch {
            assert_eq!(
                steps == one,
                clears,
                "{task}: Adam t {steps} after a change"
            );
        }
        // Resume from a mid-run state equals the uninterrupted run.
        let mut a = Trainer::new(cfg.clone().check().unwrap()).unwrap();
        for _ in 0..10 {
            a.update().unwrap();
        }
        let saved = a.state().clone();
        assert!(
            saved.curriculum_level >= 1,
            "{task}: mid-run after a change"
        );
        let mut b = Trainer::restore(cfg.clone().check().unwrap(), saved).unwrap();
        while !a.finished() {
            a.update().unwrap();
            b.update().unwrap();
        }
        assert_eq!(a.state().theta, b.state().theta, "{task}: resume is exact");
        // A state at a level this curriculum does not have is refused, naming the field.
        let mut bad = a.state().clone();
        bad.curriculum_level = 9;
        let err = Trainer::restore(cfg.check().unwrap(), bad)
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains("curriculum_level"), "{err}");
    }
}

#[test]
fn a_growth_curriculum_on_another_task_is_refused() {
    let cfg = growth_cfg("Bisection-v0", &["curriculum=multi_oven"], 1000);
    let err = cfg
        .check()
        .and_then(Trainer::new)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("curriculum") && err.contains("ovens"), "{err}");
}
