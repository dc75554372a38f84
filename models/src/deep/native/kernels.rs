//! Dense kernels for the native engine: one register-tiled matrix product, transposes and
//! vectorisable element-wise functions (exp, sigmoid, tanh).
//!
//! Every kernel is written once as plain Rust (`#[inline(always)]`, generic over whether
//! fused multiply–add is available) and compiled twice: for the baseline target and, on
//! x86-64, with AVX2+FMA enabled, chosen at run time. LLVM vectorises the inner loops.
//! Results are deterministic on a given machine (fixed summation order).

/// Rows of `C` computed together by the tiled product.
const MR: usize = 4;
/// Columns of `C` computed together by the tiled product (two AVX2 registers).
const NR: usize = 16;

#[inline(always)]
fn madd<const FMA: bool>(a: f32, b: f32, c: f32) -> f32 {
    if FMA { a.mul_add(b, c) } else { a * b + c }
}

/// Whether the AVX2+FMA versions can run here (cached by the std macro).
#[inline]
fn use_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// A row-major matrix view: `rows × cols` with row stride `ld` (elements).
#[derive(Debug, Clone, Copy)]
pub struct Mat<'a> {
    /// Backing data.
    pub data: &'a [f32],
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Row stride (≥ `cols`).
    pub ld: usize,
}

impl<'a> Mat<'a> {
    /// A dense `rows × cols` matrix.
    pub fn new(data: &'a [f32], rows: usize, cols: usize) -> Self {
        Mat::strided(data, rows, cols, cols)
    }

    /// A `rows × cols` view with row stride `ld`.
    pub fn strided(data: &'a [f32], rows: usize, cols: usize, ld: usize) -> Self {
        assert!(ld >= cols, "row stride below the column count");
        assert!(
            rows == 0 || data.len() >= (rows - 1) * ld + cols,
            "matrix view longer than its data"
        );
        Mat {
            data,
            rows,
            cols,
            ld,
        }
    }

    #[inline(always)]
    fn row(&self, i: usize) -> &'a [f32] {
        &self.data[i * self.ld..i * self.ld + self.cols]
    }
}

/// `C = A·B` (or `C += A·B` when `accumulate`), `A [M, K]`, `B [K, N]`, `C [M, N]` with
/// row stride `ldc`.
pub fn matmul(a: Mat<'_>, b: Mat<'_>, c: &mut [f32], ldc: usize, accumulate: bool) {
    assert_eq!(a.cols, b.rows, "inner dimensions differ");
    assert!(ldc >= b.cols, "output row stride below the column count");
    if a.rows == 0 || b.cols == 0 {
        return;
    }
    assert!(
        c.len() >= (a.rows - 1) * ldc + b.cols,
        "output shorter than the product"
    );
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: the CPU supports AVX2 and FMA (checked just above).
        unsafe { matmul_avx2(a, b, c, ldc, accumulate) };
        return;
    }
    matmul_impl::<false>(a, b, c, ldc, accumulate);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn matmul_avx2(a: Mat<'_>, b: Mat<'_>, c: &mut [f32], ldc: usize, accumulate: bool) {
    matmul_impl::<true>(a, b, c, ldc, accumulate);
}

#[inline(always)]
fn matmul_impl<const FMA: bool>(
    a: Mat<'_>,
    b: Mat<'_>,
    c: &mut [f32],
    ldc: usize,
    accumulate: bool,
) {
    let (m, k, n) = (a.rows, a.cols, b.cols);
    if m == 1 {
        // A single row (acting in a rollout): scaled rows of B, skipping zero inputs
        // (observation codes and ReLU outputs are mostly zero).
        axpy_row::<FMA>(a, b, c, accumulate);
        return;
    }
    let n_tiled = n - n % NR;
    let m_tiled = m - m % MR;
    // The last, partial column block is packed into a zero-padded [K, NR] panel so that
    // it runs through the same fixed-width kernel.
    let mut panel = Vec::new();
    if n_tiled < n {
        panel.resize(k * NR, 0.0);
        for kk in 0..k {
            panel[kk * NR..kk * NR + n - n_tiled]
                .copy_from_slice(&b.data[kk * b.ld + n_tiled..kk * b.ld + n]);
        }
    }
    for j0 in (0..n_tiled).step_by(NR) {
        for i0 in (0..m_tiled).step_by(MR) {
            let arows: [&[f32]; MR] = std::array::from_fn(|r| a.row(i0 + r));
            tile::<FMA, MR>(arows, (b.data, b.ld, j0), c, ldc, (i0, j0), accumulate);
        }
        for i in m_tiled..m {
            tile::<FMA, 1>([a.row(i)], (b.data, b.ld, j0), c, ldc, (i, j0), accumulate);
        }
    }
    if n_tiled < n {
        // The partial block goes through a dense [M, NR] panel of C as well.
        let w = n - n_tiled;
        let mut cp = vec![0f32; m * NR];
        if accumulate {
            for i in 0..m {
                cp[i * NR..i * NR + w].copy_from_slice(&c[i * ldc + n_tiled..i * ldc + n]);
            }
        }
        for i0 in (0..m_tiled).step_by(MR) {
            let arows: [&[f32]; MR] = std::array::from_fn(|r| a.row(i0 + r));
            tile::<FMA, MR>(arows, (&panel, NR, 0), &mut cp, NR, (i0, 0), accumulate);
        }
        for i in m_tiled..m {
            tile::<FMA, 1>([a.row(i)], (&panel, NR, 0), &mut cp, NR, (i, 0), accumulate);
        }
        for i in 0..m {
            c[i * ldc + n_tiled..i * ldc + n].copy_from_slice(&cp[i * NR..i * NR + w]);
        }
    }
}

/// `R × NR` block of `C` at `(i0, j0)`: `(+)= Σ_k A[i0 + r, k]·B[k, bj..bj + NR]`, with `B`
/// given as `(data, row stride, first column)`.
#[inline(always)]
fn tile<const FMA: bool, const R: usize>(
    arows: [&[f32]; R],
    (bdata, ldb, bj): (&[f32], usize, usize),
    c: &mut [f32],
    ldc: usize,
    (i0, j0): (usize, usize),
    accumulate: bool,
) {
    let k = arows[0].len();
    let mut acc = [[0f32; NR]; R];
    if accumulate {
        for (r, acc_r) in acc.iter_mut().enumerate() {
            let o = (i0 + r) * ldc + j0;
            acc_r.copy_from_slice(&c[o..o + NR]);
        }
    }
    for kk in 0..k {
        let bt: &[f32; NR] = bdata[kk * ldb + bj..kk * ldb + bj + NR]
            .try_into()
            .expect("tile width");
        for r in 0..R {
            let av = arows[r][kk];
            for j in 0..NR {
                acc[r][j] = madd::<FMA>(av, bt[j], acc[r][j]);
            }
        }
    }
    for (r, acc_r) in acc.iter().enumerate() {
        let o = (i0 + r) * ldc + j0;
        c[o..o + NR].copy_from_slice(acc_r);
    }
}

/// Row 0 of `C` as a sum of scaled rows of `B` (zeros in `A` skipped).
#[inline(always)]
fn axpy_row<const FMA: bool>(a: Mat<'_>, b: Mat<'_>, c: &mut [f32], accumulate: bool) {
    let n = b.cols;
    let crow = &mut c[..n];
    if !accumulate {
        crow.fill(0.0);
    }
    for (kk, &av) in a.row(0).iter().enumerate() {
        if av == 0.0 {
            continue;
        }
        let brow = &b.data[kk * b.ld..kk * b.ld + n];
        for (cv, &bv) in crow.iter_mut().zip(brow) {
            *cv = madd::<FMA>(av, bv, *cv);
        }
    }
}

/// `out [cols, rows]` = transpose of `a`.
pub fn transpose_into(a: Mat<'_>, out: &mut Vec<f32>) {
    out.clear();
    out.resize(a.rows * a.cols, 0.0);
    for i in 0..a.rows {
        for (j, &v) in a.row(i).iter().enumerate() {
            out[j * a.rows + i] = v;
        }
    }
}

/// `C = Aᵀ·B` (or `+=`): `A [M, K]`, `B [M, N]` → `C [K, N]` (dense); `scratch` holds `Aᵀ`.
pub fn matmul_tn(a: Mat<'_>, b: Mat<'_>, c: &mut [f32], accumulate: bool, scratch: &mut Vec<f32>) {
    assert_eq!(a.rows, b.rows, "row counts differ");
    transpose_into(a, scratch);
    matmul(Mat::new(scratch, a.cols, a.rows), b, c, b.cols, accumulate);
}

/// `C = A·Bᵀ` (or `+=`): `A [M, K]`, `B [N, K]` → `C [M, N]` with row stride `ldc`;
/// `scratch` holds `Bᵀ`.
pub fn matmul_nt(
    a: Mat<'_>,
    b: Mat<'_>,
    c: &mut [f32],
    ldc: usize,
    accumulate: bool,
    scratch: &mut Vec<f32>,
) {
    assert_eq!(a.cols, b.cols, "inner dimensions differ");
    transpose_into(b, scratch);
    matmul(a, Mat::new(scratch, b.cols, b.rows), c, ldc, accumulate);
}

/// Adds the column sums of `a` to `out [cols]`.
pub fn add_col_sums(a: Mat<'_>, out: &mut [f32]) {
    assert_eq!(out.len(), a.cols, "bias gradient length");
    for i in 0..a.rows {
        for (o, &v) in out.iter_mut().zip(a.row(i)) {
            *o += v;
        }
    }
}

/// Adds `bias [cols]` to every row of the dense `[rows, cols]` matrix `x`.
pub fn add_bias(x: &mut [f32], bias: &[f32]) {
    for row in x.chunks_exact_mut(bias.len()) {
        for (v, &b) in row.iter_mut().zip(bias) {
            *v += b;
        }
    }
}

/// `exp(x)` in f32 without a libm call (relative error < 2e-7 on [−87, 88]): `x = n·ln 2 + r`,
/// `|r| ≤ ln2/2`, `eʳ` by its Taylor series to degree 7 (truncation < 6e-9), then `2ⁿ` by
/// exponent bits. Branch-free so that loops over it vectorise.
#[inline(always)]
pub fn exp_f32(x: f32) -> f32 {
    const LOG2E: f32 = std::f32::consts::LOG2_E;
    // ln 2 split in a part exact in f32 and the remainder (Cody–Waite reduction).
    const LN2_HI: f32 = 0.693_145_75;
    const LN2_LO: f32 = 1.428_606_8e-6;
    // 1.5·2²³: adding and subtracting it rounds to the nearest integer.
    const ROUND: f32 = 12_582_912.0;
    let x = x.clamp(-87.0, 88.0);
    let n = (x * LOG2E + ROUND) - ROUND;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let mut p = 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    let scale = f32::from_bits(((n as i32 + 127) as u32) << 23);
    p * scale
}

/// Logistic sigmoid `1/(1 + e^{−x})`.
#[inline(always)]
pub fn sigmoid_f32(x: f32) -> f32 {
    1.0 / (1.0 + exp_f32(-x))
}

/// `tanh(x)` as `1 − 2/(e^{2x} + 1)` (absolute error ~1e-7).
#[inline(always)]
pub fn tanh_f32(x: f32) -> f32 {
    1.0 - 2.0 / (exp_f32(2.0 * x) + 1.0)
}

macro_rules! elementwise {
    ($(#[$doc:meta])* $name:ident, $avx:ident, $f:ident) => {
        $(#[$doc])*
        pub fn $name(x: &mut [f32]) {
            #[cfg(target_arch = "x86_64")]
            if use_avx2() {
                // SAFETY: the CPU supports AVX2 and FMA (checked just above).
                unsafe { $avx(x) };
                return;
            }
            x.iter_mut().for_each(|v| *v = $f(*v));
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,fma")]
        fn $avx(x: &mut [f32]) {
            x.iter_mut().for_each(|v| *v = $f(*v));
        }
    };
}

elementwise!(
    /// In-place logistic sigmoid of every element.
    sigmoid_inplace,
    sigmoid_avx2,
    sigmoid_f32
);
elementwise!(
    /// In-place `tanh` of every element.
    tanh_inplace,
    tanh_avx2,
    tanh_f32
);

/// In-place ReLU.
pub fn relu_inplace(x: &mut [f32]) {
    x.iter_mut().for_each(|v| *v = v.max(0.0));
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
