//! The paper's training conventions (`docs/paper-protocol.md` §1.0): the critic
//! reads a detached copy of the recurrent output, reservoir cores never change, and
//! recurrent minibatches are sb3-contrib's rotated windows cut into sequences.

use chronocooked_models::deep::native::{Cache, NativePolicy, SeqBatch};
use chronocooked_models::{Architecture, CoreKind, PolicyConfig};
use chronocooked_training::ppo::params::flat_params;
use chronocooked_training::ppo::rollout::{Chunk, sequence_batches};
use chronocooked_training::{Check, Trainer, resolve};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

fn uniform(n: usize, rng: &mut Xoshiro256PlusPlus) -> Vec<f32> {
    (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
}

/// Gradient of `Σ wl·logits + Σ wv·values` for one random batch.
fn gradient(
    native: &NativePolicy,
    theta: &[f32],
    batch: &SeqBatch<'_>,
    wl: &[f32],
    wv: &[f32],
) -> Vec<f32> {
    let mut cache = Cache::default();
    native.forward(theta, batch, &mut cache);
    let mut g = vec![f32::NAN; theta.len()];
    native.backward(theta, &mut cache, wl, wv, &mut g);
    g
}

#[test]
fn detached_critic_keeps_the_value_loss_out_of_core_and_trunk() {
    for arch in [
        Architecture::recurrent(CoreKind::Lstm, 9),
        Architecture::recurrent(CoreKind::Ctrnn, 9),
        Architecture::recurrent(CoreKind::Gru, 9),
    ] {
        let (cells, ch, actions, t, b) = (15, 6, 6, 5, 3);
        let pc = PolicyConfig::new(arch, cells, ch, actions);
        let theta = flat_params(&pc.init(4, &chronocooked_models::cpu()));
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
        let obs: Vec<f32> = (0..t * b * cells * ch)
            .map(|_| rng.random_range(0..4u8) as f32)
            .collect();
        let mut keep = vec![1f32; t * b];
        keep[2 * b + 1] = 0.0;
        let h0 = uniform(b * arch.hidden, &mut rng);
        let c0 = uniform(b * arch.hidden, &mut rng);
        let batch = SeqBatch {
            obs: &obs,
            steps: t,
            batch: b,
            keep: &keep,
            h0: &h0,
            c0: (arch.core == Some(CoreKind::Lstm)).then_some(&c0[..]),
            active: None,
        };
        let wl = uniform(t * b * actions, &mut rng);
        let wv = uniform(t * b, &mut rng);
        let zl = vec![0f32; wl.len()];
        let zv = vec![0f32; wv.len()];
        let full = NativePolicy::new(&pc);
        let det = NativePolicy::new(&pc).with_detached_critic(true);
        let l = full.layout();
        let heads = l.hidden.0.offset..l.total;
        // Value loss alone: exactly zero gradient below the heads.
        let g = gradient(&det, &theta, &batch, &zl, &wv);
        assert!(
            g[..heads.start].iter().all(|&x| x == 0.0),
            "{arch}: value gradient reached the core or trunk"
        );
        assert!(g[heads.clone()].iter().any(|&x| x != 0.0));
        // Both losses: below the heads, the policy loss's gradient; in the heads, the full one.
        let g_det = gradient(&det, &theta, &batch, &wl, &wv);
        let g_pi = gradient(&full, &theta, &batch, &wl, &zv);
        let g_all = gradient(&full, &theta, &batch, &wl, &wv);
        for i in 0..heads.start {
            assert!(
                (g_det[i] - g_pi[i]).abs() <= 1e-6 * (1.0 + g_pi[i].abs()),
                "{arch}[{i}]: {} vs {}",
                g_det[i],
                g_pi[i]
            );
        }
        for i in heads.clone() {
            assert!(
                (g_det[i] - g_all[i]).abs() <= 1e-6 * (1.0 + g_all[i].abs()),
                "{arch} head[{i}]"
            );
        }
        // The untouched engine: the value loss does train the core.
        let g = gradient(&full, &theta, &batch, &zl, &wv);
        assert!(g[..heads.start].iter().any(|&x| x != 0.0));
    }
}

#[test]
fn sequence_minibatches_equal_a_by_hand_reference() {
    // 2 envs × 5 steps, episode starts at (env 0, t 1) and (env 1, t 3) besides t 0.
    // keep is time-major [T, N].
    let (n, t) = (2, 5);
    let mut keep = vec![1f32; n * t];
    keep[0] = 0.0;
    keep[1] = 0.0;
    keep[n] = 0.0; // t 1, env 0
    keep[3 * n + 1] = 0.0; // t 3, env 1
    // Env-major flat order rotated by 3: (0,3) (0,4) (1,0) (1,1) | (1,2) (1,3) (1,4) (0,0) |
    // (0,1) (0,2); windows of 4.
    let got = sequence_batches(&keep, n, t, 4, 3);
    let c = |env, start, len| Chunk {
        env,
        index: start,
        start,
        len,
    };
    let want = vec![
        vec![c(0, 3, 2), c(1, 0, 2)],
        vec![c(1, 2, 1), c(1, 3, 2), c(0, 0, 1)],
        vec![c(0, 1, 2)],
    ];
    assert_eq!(got, want);
    // Every transition is used exactly once, whatever the split.
    for split in 0..n * t {
        let mut seen = vec![0; n * t];
        for mb in sequence_batches(&keep, n, t, 3, split) {
            assert!(mb.iter().map(|c| c.len).sum::<usize>() <= 3);
            for s in mb {
                for k in s.start..s.start + s.len {
                    seen[k * n + s.env] += 1;
                    // An episode start can only open a sequence.
                    if k > s.start {
                        assert_eq!(keep[k * n + s.env], 1.0);
                    }
                }
            }
        }
        assert!(seen.iter().all(|&v| v == 1), "split {split}: {seen:?}");
    }
}

fn small(model: &str, extra: &[&str]) -> Trainer {
    let mut sets: Vec<String> = ["n_steps=200", "n_epochs=2", "env.td=4"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    sets.extend(extra.iter().map(|s| s.to_string()));
    let cfg = resolve(
        "FixedInterval-v0",
        model.parse().unwrap(),
        "reference",
        11,
        &sets,
    )
    .unwrap();
    Trainer::new(cfg.check().unwrap()).unwrap()
}

#[test]
fn reservoir_core_weights_never_change() {
    for extra in [&[][..], &["reservoir_grad_in_norm=false"][..]] {
        let mut tr = small("ctrnn-reservoir8", extra);
        let before = tr.state().theta.clone();
        let pc = *tr.policy_config();
        let core = NativePolicy::new(&pc).layout().core_range().unwrap();
        for _ in 0..3 {
            tr.update().unwrap();
        }
        let after = &tr.state().theta;
        assert_eq!(before[core.clone()], after[core.clone()], "{extra:?}");
        assert!(
            before[core.end..]
                .iter()
                .zip(&after[core.end..])
                .any(|(a, b)| a != b),
            "heads did not train"
        );
        assert!(
            before[..core.start]
                .iter()
                .zip(&after[..core.start])
                .any(|(a, b)| a != b),
            "trunk did not train"
        );
        // The paper's clip carries the accumulated, never-applied core gradient.
        let acc = &tr.state().reservoir_grad;
        if extra.is_empty() {
            assert_eq!(acc.len(), core.len());
            let norm = acc.iter().map(|x| (*x as f64).powi(2)).sum::<f64>().sqrt();
            assert!(norm > 0.0 && norm <= 0.5 + 1e-4, "accumulated norm {norm}");
        } else {
            assert!(acc.is_empty());
        }
    }
    // The trained CTRNN's core does change.
    let mut tr = small("ctrnn8", &[]);
    let before = tr.state().theta.clone();
    let core = NativePolicy::new(tr.policy_config())
        .layout()
        .core_range()
        .unwrap();
    tr.update().unwrap();
    assert_ne!(before[core.clone()], tr.state().theta[core]);
}

#[test]
fn reservoir_names_parse_and_print() {
    let a: Architecture = "ctrnn-reservoir125".parse().unwrap();
    assert_eq!(a, Architecture::reservoir(CoreKind::Ctrnn, 125));
    assert_eq!(a.name(), "ctrnn-reservoir125");
    assert_eq!(
        "ctrnn125".parse::<Architecture>().unwrap().name(),
        "ctrnn125"
    );
    assert!(Architecture::all().contains(&a));
    // Old run configs (no `reservoir` field) still load as trained cores.
    let old: Architecture = serde_json::from_str(r#"{"core":"ctrnn","hidden":8}"#).unwrap();
    assert!(!old.reservoir);
}

#[test]
fn torch_core_init_draws_pytorch_default_ranges() {
    use chronocooked_models::CoreInit;
    for (arch, h) in [
        (Architecture::reservoir(CoreKind::Ctrnn, 125), 125usize),
        (Architecture::recurrent(CoreKind::Lstm, 125), 125),
    ] {
        let mut pc = PolicyConfig::new(arch, 15, 6, 6);
        pc.core_init = CoreInit::Torch;
        let theta = flat_params(&pc.init(3, &chronocooked_models::cpu()));
        let l = NativePolicy::new(&pc).layout().clone();
        let (w_in, b_in) = l.core_in.unwrap();
        let (w_rec, _) = l.core_rec.unwrap();
        let max = |b: chronocooked_models::deep::native::Block| {
            b.of(&theta).iter().fold(0f32, |m, v| m.max(v.abs())) as f64
        };
        let mean_abs = |b: chronocooked_models::deep::native::Block| {
            b.of(&theta).iter().map(|v| v.abs() as f64).sum::<f64>() / b.len as f64
        };
        let kh = 1.0 / (h as f64).sqrt();
        if arch.core == Some(CoreKind::Ctrnn) {
            // nn.Linear(64, H) and nn.Linear(H, H, bias=False): U(±1/8) and U(±1/√H).
            let ki = 1.0 / 8.0;
            assert!(max(w_in) <= ki && max(w_in) > 0.95 * ki);
            assert!(max(b_in) <= ki && max(b_in) > 0.9 * ki);
            assert!(max(w_rec) <= kh && max(w_rec) > 0.95 * kh);
            // Uniform: mean |w| = bound / 2.
            assert!((mean_abs(w_rec) / kh - 0.5).abs() < 0.02);
            let tau = l.tau.unwrap();
            assert!(tau.of(&theta).iter().all(|&t| t == 1.0));
        } else {
            // nn.LSTM: every weight U(±1/√H); the single bias is b_ih + b_hh.
            assert!(max(w_in) <= kh && max(w_rec) <= kh);
            assert!(max(b_in) <= 2.0 * kh && max(b_in) > kh);
            assert!((mean_abs(w_rec) / kh - 0.5).abs() < 0.02);
        }
        // The lab's scheme: orthogonal recurrent blocks (row norms 1 for a square block).
        pc.core_init = CoreInit::Lab;
        let lab = flat_params(&pc.init(3, &chronocooked_models::cpu()));
        assert_ne!(w_rec.of(&lab), w_rec.of(&theta));
    }
}
