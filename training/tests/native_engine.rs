//! The native engine computes the same function and the same parameter gradients as the
//! burn modules (autodiff), for every architecture: CNN-MLP and each recurrent core, with
//! an episode start inside the sequence and a non-zero initial state.

use burn::tensor::{Tensor, TensorData};
use chronocooked_models::deep::native::{Cache, NativePolicy, SeqBatch};
use chronocooked_models::{Architecture, CoreKind, CoreState, PolicyConfig, cpu_autodiff, to_vec};
use chronocooked_training::ppo::params::{flat_grads, flat_params, write_params};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn uniform(n: usize, scale: f32, rng: &mut Xoshiro256PlusPlus) -> Vec<f32> {
    (0..n).map(|_| rng.random_range(-scale..scale)).collect()
}

fn assert_close(what: &str, got: &[f32], want: &[f32], tol: f32) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    let scale = want.iter().fold(0f32, |m, v| m.max(v.abs())).max(1e-3);
    for (i, (a, b)) in got.iter().zip(want).enumerate() {
        assert!(
            (a - b).abs() <= tol * scale,
            "{what}[{i}]: native {a} vs burn {b} (scale {scale})"
        );
    }
}

/// Native vs burn at one architecture. With `lens` (sequence lengths, longest first) the
/// rows past each sequence's end are padding: their output weights are zero, the native
/// engine skips them (`SeqBatch::active`) and outputs are compared on real rows only.
fn check(arch: Architecture, seed: u64, lens: Option<[usize; 3]>) {
    let (cells, ch, actions) = (15, 6, 6);
    let (t, b) = (6, 3);
    let real = |row: usize| lens.is_none_or(|l| row / b < l[row % b]);
    let active: Option<Vec<usize>> = lens.map(|l| {
        (0..t)
            .map(|s| l.iter().filter(|&&x| x > s).count())
            .collect()
    });
    let d = cpu_autodiff();
    let pc = PolicyConfig::new(arch, cells, ch, actions);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    // Perturbed weights (non-zero biases, GRU recurrent bias, spread of CTRNN τ).
    let model = pc.init(seed, &d);
    let mut theta = flat_params(&model);
    for v in theta.iter_mut() {
        *v += rng.random_range(-0.2..0.2);
    }
    let model = write_params(model, &theta);
    let native = NativePolicy::new(&pc);
    assert_eq!(native.num_params(), theta.len(), "{arch}: layout size");
    // Observations: integer codes 0..5 (many zeros, as in the env), one episode start
    // at step 3 for sequence 1 and at step 0 for sequence 2.
    let obs: Vec<f32> = (0..t * b * cells * ch)
        .map(|_| rng.random_range(0..6u8).saturating_sub(2) as f32)
        .collect();
    let mut keep = vec![1f32; t * b];
    keep[3 * b + 1] = 0.0;
    keep[2] = 0.0;
    let hid = arch.hidden;
    let lat = if arch.is_recurrent() { hid } else { 64 };
    let h0 = uniform(b * hid, 0.8, &mut rng);
    let c0 = uniform(b * hid, 0.8, &mut rng);
    let lstm = arch.core == Some(CoreKind::Lstm);
    // burn.
    let x = Tensor::<4>::from_data(TensorData::new(obs.clone(), [t, b, cells, ch]), &d);
    let state = arch
        .is_recurrent()
        .then(|| CoreState::from_vecs(h0.clone(), lstm.then(|| c0.clone()), b, &d));
    let keep_t: Vec<Option<Tensor<2>>> = keep
        .chunks_exact(b)
        .map(|k| {
            k.iter()
                .any(|&v| v != 1.0)
                .then(|| Tensor::<2>::from_data(TensorData::new(k.to_vec(), [b, 1]), &d))
        })
        .collect();
    let out = model.forward_seq(x, state, &keep_t);
    let mut wl = uniform(t * b * actions, 1.0, &mut rng);
    let mut wv = uniform(t * b, 1.0, &mut rng);
    for row in (0..t * b).filter(|&r| !real(r)) {
        wv[row] = 0.0;
        wl[row * actions..(row + 1) * actions].fill(0.0);
    }
    let objective = (out.logits.clone()
        * Tensor::<2>::from_data(TensorData::new(wl.clone(), [t * b, actions]), &d))
    .sum()
        + (out.values.clone()
            * Tensor::<2>::from_data(TensorData::new(wv.clone(), [t * b, 1]), &d))
        .sum();
    let g_burn = flat_grads(&model, &objective.backward());
    // native.
    let mut cache = Cache::default();
    let batch = SeqBatch {
        obs: &obs,
        steps: t,
        batch: b,
        keep: &keep,
        h0: if arch.is_recurrent() { &h0 } else { &[] },
        c0: lstm.then_some(&c0[..]),
        active: active.as_deref(),
    };
    native.forward(&theta, &batch, &mut cache);
    // Real rows only (all rows without padding), `width` values per row.
    let rows = |v: &[f32], width: usize| -> Vec<f32> {
        v.chunks_exact(width)
            .enumerate()
            .filter(|(r, _)| real(*r))
            .flat_map(|(_, x)| x.to_vec())
            .collect()
    };
    assert_close(
        &format!("{arch} logits"),
        &rows(&cache.logits, actions),
        &rows(&to_vec(&out.logits), actions),
        2e-5,
    );
    assert_close(
        &format!("{arch} values"),
        &rows(&cache.values, 1),
        &rows(&to_vec(&out.values), 1),
        2e-5,
    );
    assert_close(
        &format!("{arch} latent"),
        // With padding the native latent holds the real rows only (step after step).
        &if lens.is_some() {
            cache.latent().to_vec()
        } else {
            rows(cache.latent(), lat)
        },
        &rows(&to_vec(&out.latent), lat),
        2e-5,
    );
    if let (Some(st), None) = (&out.state, lens) {
        let (h, c) = cache.final_state();
        assert_close(&format!("{arch} final h"), h, &to_vec(&st.h), 2e-5);
        if let (Some(c), Some(want)) = (c, &st.c) {
            assert_close(&format!("{arch} final c"), c, &to_vec(want), 2e-5);
        }
    }
    let mut g = vec![f32::NAN; theta.len()];
    native.backward(&theta, &mut cache, &wl, &wv, &mut g);
    // Compare block by block so a failure names the parameter.
    let l = native.layout();
    let mut blocks = vec![
        ("conv1.w", l.conv1.0),
        ("conv1.b", l.conv1.1),
        ("conv2.w", l.conv2.0),
        ("conv2.b", l.conv2.1),
        ("dense.w", l.dense.0),
        ("dense.b", l.dense.1),
        ("hidden.w", l.hidden.0),
        ("hidden.b", l.hidden.1),
        ("pi.w", l.pi.0),
        ("pi.b", l.pi.1),
        ("vf.w", l.vf.0),
        ("vf.b", l.vf.1),
    ];
    if let Some((w, bb)) = l.core_in {
        blocks.push(("core.in.w", w));
        blocks.push(("core.in.b", bb));
    }
    if let Some((w, bb)) = l.core_rec {
        blocks.push(("core.rec.w", w));
        if let Some(bb) = bb {
            blocks.push(("core.rec.b", bb));
        }
    }
    if let Some(tau) = l.tau {
        blocks.push(("core.tau", tau));
    }
    let covered: usize = blocks.iter().map(|(_, bl)| bl.len).sum();
    assert_eq!(covered, theta.len(), "{arch}: blocks cover every parameter");
    for (name, bl) in blocks {
        assert_close(
            &format!("{arch} grad {name}"),
            bl.of(&g),
            bl.of(&g_burn),
            2e-4,
        );
    }
}

/// Tolerances: outputs within 2e-5 and every gradient block within 2e-4 of the block's
/// largest burn value (f32 sums in a different order: tiled, packed and fused kernels).
#[test]
fn native_forward_and_gradients_equal_burn_autodiff() {
    check(Architecture::CNN_MLP, 1, None);
    // The paper's sizes: 8, 125 (odd: tails of every kernel) and 256 (packed panels of
    // W_hh wider than one cache page), every core kind.
    for (i, kind) in CoreKind::ALL.into_iter().enumerate() {
        for (j, size) in [8, 125, 256].into_iter().enumerate() {
            check(
                Architecture::recurrent(kind, size),
                10 + 3 * i as u64 + j as u64,
                None,
            );
        }
    }
}

#[test]
fn native_skips_padding_after_each_sequence_and_keeps_the_gradients() {
    // Sequences of 6, 4 and 1 steps (longest first) in a batch of 6 steps.
    for (i, kind) in CoreKind::ALL.into_iter().enumerate() {
        for size in [8, 125] {
            check(
                Architecture::recurrent(kind, size),
                40 + i as u64,
                Some([6, 4, 1]),
            );
        }
    }
}

#[test]
fn native_outputs_do_not_depend_on_state_before_an_episode_start() {
    // Two different initial states, episode start at step 0 for every sequence: identical.
    let pc = PolicyConfig::new(Architecture::recurrent(CoreKind::Lstm, 9), 15, 6, 6);
    let d = chronocooked_models::cpu();
    let theta = flat_params(&pc.init(3, &d));
    let native = NativePolicy::new(&pc);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let (t, b) = (4, 2);
    let obs = uniform(t * b * 15 * 6, 2.0, &mut rng);
    let mut keep = vec![1f32; t * b];
    keep[..b].fill(0.0);
    let run = |h0: &[f32], c0: &[f32]| {
        let mut cache = Cache::default();
        let batch = SeqBatch {
            obs: &obs,
            steps: t,
            batch: b,
            keep: &keep,
            h0,
            c0: Some(c0),
            active: None,
        };
        native.forward(&theta, &batch, &mut cache);
        cache.logits.clone()
    };
    let a = run(
        &uniform(b * 9, 1.0, &mut rng),
        &uniform(b * 9, 1.0, &mut rng),
    );
    let z = run(&[0.0; 18], &[0.0; 18]);
    assert_eq!(a, z);
}

#[test]
fn native_and_burn_engines_train_alike() {
    // Two PPO updates (2 envs) from the same seed on each engine: the same rollouts (actions sampled
    // from logits that agree to ~1e-6 with the same RNG) and the same losses and parameters
    // up to float rounding (Adam normalises steps, so rounding noise in near-zero gradients
    // can move a parameter by up to ~lr per step: the bound below is a few such steps).
    use chronocooked_training::{Check, Trainer, resolve};
    // The reference preset (sequence minibatches, detached critic, reservoir gradients in
    // the clip) and the lab's chunked, trained-through variant.
    let lab = [
        "recurrent_batches=chunks",
        "bptt_len=16",
        "detach_critic=false",
    ];
    for (model, extra) in [
        ("cnn-mlp", &[][..]),
        ("lstm8", &[][..]),
        ("ctrnn8", &[][..]),
        ("gru8", &[][..]),
        ("ctrnn-reservoir8", &[][..]),
        ("lstm8", &lab[..]),
    ] {
        let cfg = |engine: &str| {
            let mut sets = vec![
                "n_envs=2".to_string(),
                "n_steps=150".into(),
                "n_epochs=2".into(),
                "env.td=4".into(),
                format!("engine={engine}"),
            ];
            sets.extend(extra.iter().map(|s| s.to_string()));
            resolve(
                "FixedInterval-v0",
                model.parse().unwrap(),
                "reference",
                3,
                &sets,
            )
            .unwrap()
        };
        let mut native = Trainer::new(cfg("native").check().unwrap()).unwrap();
        let mut burn = Trainer::new(cfg("burn").check().unwrap()).unwrap();
        for update in 0..2 {
            let a = native.update().unwrap();
            let b = burn.update().unwrap();
            assert_eq!(
                a.episodes, b.episodes,
                "{model} update {update}: rollouts differ"
            );
            for (what, x, y) in [
                ("policy loss", a.policy_loss, b.policy_loss),
                ("value loss", a.value_loss, b.value_loss),
                ("entropy", a.entropy, b.entropy),
                (
                    "explained variance",
                    a.explained_variance,
                    b.explained_variance,
                ),
            ] {
                assert!(
                    (x - y).abs() <= 1e-3 * (1.0 + y.abs()),
                    "{model} update {update} {what}: native {x} vs burn {y}"
                );
            }
        }
        let (ta, tb) = (&native.state().theta, &burn.state().theta);
        let max_diff = ta
            .iter()
            .zip(tb)
            .map(|(a, b)| (a - b).abs())
            .fold(0f32, f32::max);
        assert!(max_diff < 2e-3, "{model}: parameters differ by {max_diff}");
        // The burn module the trainer exposes carries the native engine's parameters.
        assert_eq!(&flat_params(&native.policy()), ta);
    }
}

#[test]
fn native_ctrnn_with_zero_weights_follows_exact_euler_decay() {
    // Zero weights and biases: the target tanh(0) = 0, so h_n = (1 − α)^n h_0 with
    // α = dt / softplus(τ_raw) = 0.1 / ln(1 + e) for the reference τ_raw = 1.
    let pc = PolicyConfig::new(Architecture::recurrent(CoreKind::Ctrnn, 5), 15, 6, 6);
    let native = NativePolicy::new(&pc);
    let mut theta = vec![0f32; native.num_params()];
    let tau = native.layout().tau.unwrap();
    theta[tau.offset..tau.offset + tau.len].fill(1.0);
    let (t, b) = (30, 2);
    let obs = vec![1f32; t * b * 15 * 6];
    let keep = vec![1f32; t * b];
    let h0: Vec<f32> = (0..b * 5).map(|i| i as f32 * 0.2 - 0.9).collect();
    let mut cache = Cache::default();
    let batch = SeqBatch {
        obs: &obs,
        steps: t,
        batch: b,
        keep: &keep,
        h0: &h0,
        c0: None,
        active: None,
    };
    native.forward(&theta, &batch, &mut cache);
    let alpha = 0.1 / (1.0 + 1f64.exp()).ln();
    for step in 0..t {
        for (i, &h) in h0.iter().enumerate() {
            let want = (1.0 - alpha).powi(step as i32 + 1) * h as f64;
            let got = cache.latent()[step * b * 5 + i] as f64;
            assert!(
                (got - want).abs() < 1e-6,
                "step {step} unit {i}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn native_empty_batch_gives_empty_outputs_and_zero_gradient() {
    let pc = PolicyConfig::new(Architecture::recurrent(CoreKind::Gru, 7), 15, 6, 6);
    let native = NativePolicy::new(&pc);
    let theta = flat_params(&pc.init(1, &chronocooked_models::cpu()));
    let mut cache = Cache::default();
    let batch = SeqBatch {
        obs: &[],
        steps: 0,
        batch: 3,
        keep: &[],
        h0: &[0.0; 21],
        c0: None,
        active: None,
    };
    native.forward(&theta, &batch, &mut cache);
    assert!(cache.logits.is_empty() && cache.values.is_empty());
    let mut g = vec![1f32; theta.len()];
    native.backward(&theta, &mut cache, &[], &[], &mut g);
    assert!(g.iter().all(|&v| v == 0.0));
}

#[test]
fn burn_ctrnn_leak_equals_the_one_scalar_definition() {
    use chronocooked_models::deep::cores::{CoreConfig, ctrnn_alpha};
    // burn's tensor form of α = min(dt/softplus(τ_raw), 1) against `ctrnn_alpha`, which the
    // native engine and the stand-alone CTRNN use: below and on the clamp, and past the
    // softplus linear branch (τ_raw > 20).
    for (tau, dt) in [
        (-3.0f32, 0.1f32),
        (-3.0, 2.0),
        (0.0, 0.1),
        (1.0, 0.1),
        (5.0, 0.5),
        (25.0, 0.1),
    ] {
        let mut cfg = CoreConfig::new(CoreKind::Ctrnn, 3, 4);
        cfg.tau_init = tau;
        cfg.dt = dt;
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
        let core = cfg.init(&mut rng, &chronocooked_models::cpu());
        let burn_alpha = to_vec(&core.alpha().unwrap());
        let (want, _) = ctrnn_alpha(f64::from(tau), f64::from(dt));
        for a in burn_alpha {
            assert!(
                (f64::from(a) - want).abs() <= 1e-6 * want.max(1e-3),
                "tau_raw {tau}, dt {dt}: burn {a} vs {want}"
            );
        }
    }
    // The derivative matches a central difference.
    for tau in [-2.0, 0.5, 3.0] {
        let h = 1e-6;
        let num = (ctrnn_alpha(tau + h, 0.1).0 - ctrnn_alpha(tau - h, 0.1).0) / (2.0 * h);
        assert!((ctrnn_alpha(tau, 0.1).1 - num).abs() < 1e-6, "tau {tau}");
    }
}

#[test]
fn every_architecture_matches_the_one_parameter_spec_shape_by_shape() {
    use chronocooked_models::deep::native::ParamLayout;
    use chronocooked_models::deep::spec::{check_shapes, param_spec};
    use chronocooked_training::ppo::params::param_shapes;
    for arch in Architecture::all() {
        let pc = PolicyConfig::new(arch, 15, 6, 6);
        let spec = param_spec(&pc);
        let module = pc.init(0, &chronocooked_models::cpu());
        check_shapes(&spec, &param_shapes(&module)).unwrap_or_else(|e| panic!("{arch:?}: {e}"));
        let total: usize = spec.iter().map(|p| p.len()).sum();
        assert_eq!(ParamLayout::new(&pc).total, total);
        assert_eq!(flat_params(&module).len(), total);
    }
    // A mismatch is named, not counted.
    let pc = PolicyConfig::new(Architecture::recurrent(CoreKind::Lstm, 8), 15, 6, 6);
    let other = PolicyConfig::new(Architecture::recurrent(CoreKind::Gru, 8), 15, 6, 6);
    let err = check_shapes(
        &param_spec(&pc),
        &param_shapes(&other.init(0, &chronocooked_models::cpu())),
    )
    .unwrap_err();
    assert!(err.contains("core.input.weight"), "{err}");
}
