//! Kernel tests: every instruction set this CPU supports and the packed product against
//! a naive reference, on fixed and random shapes (odd sizes, tails of every width).

use super::*;
use proptest::prelude::*;

fn naive(a: &[f32], b: &[f32], m: usize, k: usize, n: usize) -> Vec<f32> {
    let mut c = vec![0f32; m * n];
    for i in 0..m {
        for j in 0..n {
            c[i * n + j] = (0..k).map(|t| a[i * k + t] * b[t * n + j]).sum();
        }
    }
    c
}

fn data(len: usize, seed: u32) -> Vec<f32> {
    (0..len)
        .map(|i| (((i as u32).wrapping_mul(2_654_435_761) ^ seed) % 1000) as f32 / 500.0 - 1.0)
        .collect()
}

#[test]
fn matmul_matches_naive_on_tile_edges() {
    for &(m, k, n) in &[
        (1, 3, 5),
        (4, 7, 16),
        (9, 13, 37),
        (8, 125, 500),
        (5, 1, 17),
    ] {
        let (a, b) = (data(m * k, 1), data(k * n, 2));
        let want = naive(&a, &b, m, k, n);
        let mut c = vec![0.5f32; m * n];
        matmul(Mat::new(&a, m, k), Mat::new(&b, k, n), &mut c, n, false);
        for (x, y) in c.iter().zip(&want) {
            assert!((x - y).abs() < 1e-4, "{m}x{k}x{n}: {x} vs {y}");
        }
        // Accumulating adds to what is there.
        matmul(Mat::new(&a, m, k), Mat::new(&b, k, n), &mut c, n, true);
        for (x, y) in c.iter().zip(&want) {
            assert!((x - 2.0 * y).abs() < 2e-4);
        }
    }
}

#[test]
fn transposed_products_match_naive() {
    let (m, k, n) = (11, 6, 19);
    let a = data(m * k, 3);
    let b = data(m * n, 4);
    let mut at = Vec::new();
    transpose_into(Mat::new(&a, m, k), &mut at);
    let want = naive(&at, &b, k, m, n);
    let mut c = vec![0f32; k * n];
    let mut s = Vec::new();
    matmul_tn(
        Mat::new(&a, m, k),
        Mat::new(&b, m, n),
        &mut c,
        false,
        &mut s,
    );
    assert!(c.iter().zip(&want).all(|(x, y)| (x - y).abs() < 1e-4));
    // A·Bᵀ with B [N, K].
    let bt = data(n * k, 5);
    let mut btt = Vec::new();
    transpose_into(Mat::new(&bt, n, k), &mut btt);
    let want = naive(&a, &btt, m, k, n);
    let mut c = vec![0f32; m * n];
    matmul_nt(
        Mat::new(&a, m, k),
        Mat::new(&bt, n, k),
        &mut c,
        n,
        false,
        &mut s,
    );
    assert!(c.iter().zip(&want).all(|(x, y)| (x - y).abs() < 1e-4));
}

#[test]
fn strided_views_read_column_blocks() {
    // The right half of a [3, 4] matrix times a [2, 2] identity is that half.
    let a = [
        1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0,
    ];
    let id = [1.0, 0.0, 0.0, 1.0];
    let mut c = vec![0f32; 6];
    matmul(
        Mat::strided(&a[2..], 3, 2, 4),
        Mat::new(&id, 2, 2),
        &mut c,
        2,
        false,
    );
    assert_eq!(c, vec![3.0, 4.0, 7.0, 8.0, 11.0, 12.0]);
}

#[test]
fn fast_exp_sigmoid_tanh_are_accurate() {
    let mut x = -20.0f32;
    while x < 20.0 {
        let e = exp_f32(x) as f64;
        let want = (x as f64).exp();
        assert!(((e - want) / want).abs() < 3e-7, "exp({x})");
        assert!((sigmoid_f32(x) as f64 - 1.0 / (1.0 + (-x as f64).exp())).abs() < 2e-7);
        assert!(
            (tanh_f32(x) as f64 - (x as f64).tanh()).abs() < 3e-7,
            "tanh({x})"
        );
        x += 0.0137;
    }
    assert_eq!(exp_f32(-1000.0), exp_f32(-87.0));
    assert!(exp_f32(1000.0).is_finite());
    assert_eq!(sigmoid_f32(-200.0), sigmoid_f32(-88.0));
    assert!(sigmoid_f32(-200.0) > 0.0 && sigmoid_f32(200.0) == 1.0);
    let mut v = vec![0.3f32, -2.0, 5.0];
    tanh_inplace(&mut v);
    assert!((v[1] - (-2.0f32).tanh()).abs() < 3e-7);
}

/// `C (+)= A·B` with every supported instruction set, and with `B` packed (plain and from
/// a transposed source), equals the naive product.
fn check_all_kernels(m: usize, k: usize, n: usize, accumulate: bool, seed: u32) {
    let (a, b) = (data(m * k, seed), data(k * n, seed ^ 7));
    let c0 = data(m * n, seed ^ 11);
    let mut want = naive(&a, &b, m, k, n);
    if accumulate {
        want.iter_mut().zip(&c0).for_each(|(w, c)| *w += c);
    }
    let tol = 1e-4 * (k as f32).sqrt().max(1.0);
    let check = |what: &str, c: &[f32]| {
        for (i, (x, y)) in c.iter().zip(&want).enumerate() {
            assert!((x - y).abs() <= tol, "{what} {m}x{k}x{n} [{i}]: {x} vs {y}");
        }
    };
    for isa in Isa::all().into_iter().filter(|i| i.supported()) {
        let mut c = c0.clone();
        matmul_isa(
            isa,
            Mat::new(&a, m, k),
            Mat::new(&b, k, n),
            &mut c,
            n,
            accumulate,
        );
        check(&format!("{isa:?}"), &c);
    }
    // Aᵀ·B with A given transposed (read in place under AVX-512).
    let mut at = Vec::new();
    transpose_into(Mat::new(&a, m, k), &mut at);
    let mut c = c0.clone();
    let mut s = Vec::new();
    matmul_tn(
        Mat::new(&at, k, m),
        Mat::new(&b, k, n),
        &mut c,
        accumulate,
        &mut s,
    );
    check("tn", &c);
    let mut p = Packed::default();
    p.pack(Mat::new(&b, k, n), false);
    let mut c = c0.clone();
    matmul_packed(Mat::new(&a, m, k), &p, &mut c, n, accumulate);
    check("packed", &c);
    let mut bt = Vec::new();
    transpose_into(Mat::new(&b, k, n), &mut bt);
    p.pack(Mat::new(&bt, n, k), true);
    let mut c = c0.clone();
    matmul_packed(Mat::new(&a, m, k), &p, &mut c, n, accumulate);
    check("packed from transpose", &c);
}

#[test]
fn kernels_match_naive_at_the_engine_shapes() {
    for &(m, k, n) in &[
        (1, 256, 1024),
        (2, 256, 1024),
        (8, 1024, 256),
        (3, 125, 500),
        (7, 500, 125),
        (128, 64, 1024),
        (125, 128, 500),
        (1920, 6, 8),
    ] {
        check_all_kernels(m, k, n, true, 3);
    }
}

#[test]
fn lstm_cell_matches_its_formula() {
    let h = 37;
    let pre0 = data(4 * h, 9);
    let cp = data(h, 10);
    let (mut pre, mut c, mut tc, mut hv) = (pre0.clone(), vec![0.0; h], vec![0.0; h], vec![0.0; h]);
    lstm_cell(&mut pre, &cp, &mut c, &mut tc, &mut hv);
    for j in 0..h {
        let s = |x: f32| 1.0 / (1.0 + (-x as f64).exp());
        let (i, f, g, o) = (
            s(pre0[j]),
            s(pre0[h + j]),
            (pre0[2 * h + j] as f64).tanh(),
            s(pre0[3 * h + j]),
        );
        let cw = f * cp[j] as f64 + i * g;
        assert!((c[j] as f64 - cw).abs() < 1e-6 && (tc[j] as f64 - cw.tanh()).abs() < 1e-6);
        assert!((hv[j] as f64 - o * cw.tanh()).abs() < 1e-6);
        assert!((pre[h + j] as f64 - f).abs() < 1e-6 && (pre[2 * h + j] as f64 - g).abs() < 1e-6);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn kernels_match_naive_on_random_shapes(
        m in 1usize..20,
        k in 1usize..70,
        n in 1usize..150,
        accumulate in any::<bool>(),
        seed in any::<u32>(),
    ) {
        check_all_kernels(m, k, n, accumulate, seed);
    }
}
