//! Dense kernels for the native engine: register-tiled matrix products, transposes and
//! vectorisable element-wise functions (exp, sigmoid, tanh).
//!
//! Three instruction sets, chosen once at run time ([`Isa::detect`]): AVX-512F (the
//! matrix product hand-written with intrinsics in `avx512.rs`, the element-wise kernels
//! compiled from the portable code with 512-bit vectors), AVX2+FMA, and a scalar
//! fallback. The portable kernels are written once as plain Rust (`#[inline(always)]`,
//! generic over whether fused multiply–add is available) and compiled per instruction
//! set; LLVM vectorises the inner loops. Results are deterministic on a given machine
//! (fixed summation order per instruction set).

#[cfg(target_arch = "x86_64")]
mod avx512;

/// Rows of `C` computed together by the tiled product.
const MR: usize = 4;
/// Columns of `C` computed together by the tiled product (two AVX2 registers).
const NR: usize = 16;

#[inline(always)]
fn madd<const FMA: bool>(a: f32, b: f32, c: f32) -> f32 {
    if FMA { a.mul_add(b, c) } else { a * b + c }
}

/// An instruction set the kernels are compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Isa {
    /// Portable code for the baseline target (no fused multiply–add).
    Scalar,
    /// AVX2 with FMA (x86-64).
    Avx2,
    /// AVX-512F (x86-64; implies AVX2+FMA on every CPU that has it, checked anyway).
    Avx512,
}

impl Isa {
    /// The best instruction set this CPU supports (detected once, then cached), or a
    /// lower one named by the environment variable `CHRONOCOOKED_ISA` (`scalar`, `avx2`,
    /// `avx512`; to test and measure the fallbacks on a machine that has more).
    pub fn detect() -> Isa {
        static BEST: std::sync::OnceLock<Isa> = std::sync::OnceLock::new();
        *BEST.get_or_init(|| {
            let cap = match std::env::var("CHRONOCOOKED_ISA").as_deref() {
                Ok("scalar") => Isa::Scalar,
                Ok("avx2") => Isa::Avx2,
                _ => Isa::Avx512,
            };
            Isa::all()
                .into_iter()
                .rev()
                .find(|i| *i <= cap && i.supported())
                .unwrap_or(Isa::Scalar)
        })
    }

    /// Every instruction set, baseline first.
    pub fn all() -> [Isa; 3] {
        [Isa::Scalar, Isa::Avx2, Isa::Avx512]
    }

    /// Whether this CPU can run the kernels compiled for `self`.
    pub fn supported(self) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            let avx2 =
                std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma");
            match self {
                Isa::Scalar => true,
                Isa::Avx2 => avx2,
                Isa::Avx512 => avx2 && std::is_x86_feature_detected!("avx512f"),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            self == Isa::Scalar
        }
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
    matmul_isa(Isa::detect(), a, b, c, ldc, accumulate);
}

/// [`matmul`] with the kernels of instruction set `isa` (for tests and benchmarks).
///
/// # Panics
/// If this CPU does not support `isa`, or the shapes do not match.
pub fn matmul_isa(isa: Isa, a: Mat<'_>, b: Mat<'_>, c: &mut [f32], ldc: usize, accumulate: bool) {
    assert!(isa.supported(), "{isa:?} is not supported by this CPU");
    assert_eq!(a.cols, b.rows, "inner dimensions differ");
    assert!(ldc >= b.cols, "output row stride below the column count");
    if a.rows == 0 || b.cols == 0 {
        return;
    }
    assert!(
        c.len() >= (a.rows - 1) * ldc + b.cols,
        "output shorter than the product"
    );
    match isa {
        #[cfg(target_arch = "x86_64")]
        Isa::Avx512 if a.rows == 1 => {
            // One row (acting): the zero-skipping row path (observation codes and ReLU
            // outputs are mostly zero). SAFETY: the CPU supports AVX-512F (asserted above).
            unsafe { axpy_row_avx512(a, b, c, accumulate) }
        }
        #[cfg(target_arch = "x86_64")]
        Isa::Avx512 => {
            // SAFETY: the CPU supports AVX-512F (asserted above) and the shapes were
            // checked just above.
            unsafe { avx512::matmul(avx512::ATerm::Plain(a), b, c, ldc, accumulate) }
        }
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2 => {
            // SAFETY: the CPU supports AVX2 and FMA (asserted above).
            unsafe { matmul_avx2(a, b, c, ldc, accumulate) }
        }
        _ => matmul_impl::<false>(a, b, c, ldc, accumulate),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
fn axpy_row_avx512(a: Mat<'_>, b: Mat<'_>, c: &mut [f32], accumulate: bool) {
    axpy_row::<true>(a, b, c, accumulate);
}

/// A right-hand matrix `B [K, N]` prepared once for many products `A·B` with few rows
/// (the recurrent step's `W_hh`, reused for every step of a window): packed into
/// contiguous 64-column panels for AVX-512, a plain row-major copy otherwise.
#[derive(Debug, Default, Clone)]
pub struct Packed {
    isa: Option<Isa>,
    k: usize,
    n: usize,
    data: Vec<f32>,
}

impl Packed {
    /// Prepares `b [K, N]`, or with `transpose` the transpose of `b [N, K]`, for
    /// [`matmul_packed`] (reusing this buffer).
    pub fn pack(&mut self, b: Mat<'_>, transpose: bool) {
        let isa = Isa::detect();
        (self.k, self.n) = if transpose {
            (b.cols, b.rows)
        } else {
            (b.rows, b.cols)
        };
        self.isa = Some(isa);
        #[cfg(target_arch = "x86_64")]
        if isa == Isa::Avx512 {
            avx512::pack(b, transpose, &mut self.data);
            return;
        }
        if transpose {
            transpose_into(b, &mut self.data);
        } else {
            self.data.clear();
            for i in 0..b.rows {
                self.data.extend_from_slice(b.row(i));
            }
        }
    }
}

/// `C = A·B` (or `C += A·B`) with `B [K, N]` prepared by [`Packed::pack`]; `A [M, K]`,
/// `C [M, N]` with row stride `ldc`.
pub fn matmul_packed(a: Mat<'_>, b: &Packed, c: &mut [f32], ldc: usize, accumulate: bool) {
    let isa = b.isa.expect("matrix packed before use");
    assert_eq!(a.cols, b.k, "inner dimensions differ");
    assert!(ldc >= b.n, "output row stride below the column count");
    if a.rows == 0 || b.n == 0 {
        return;
    }
    assert!(
        c.len() >= (a.rows - 1) * ldc + b.n,
        "output shorter than the product"
    );
    #[cfg(target_arch = "x86_64")]
    if isa == Isa::Avx512 {
        // SAFETY: `pack` chose AVX-512 because the CPU supports it; the shapes were
        // checked above and `pack` wrote ⌈N/64⌉·K·64 values.
        unsafe { avx512::matmul_packed(a, &b.data, b.n, c, ldc, accumulate) };
        return;
    }
    matmul_isa(isa, a, Mat::new(&b.data, b.k, b.n), c, ldc, accumulate);
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
    #[cfg(target_arch = "x86_64")]
    if Isa::detect() == Isa::Avx512 && a.cols > 1 {
        // AVX-512 reads Aᵀ in place (no transposed copy).
        assert!(
            c.len() >= a.cols * b.cols,
            "output shorter than the product"
        );
        if a.rows == 0 {
            if !accumulate {
                c[..a.cols * b.cols].fill(0.0);
            }
            return;
        }
        // SAFETY: the CPU supports AVX-512F (detected); Aᵀ is [a.cols, a.rows] with
        // a.rows == b.rows, and C holds a.cols rows of b.cols (checked above).
        unsafe { avx512::matmul(avx512::ATerm::Transposed(a), b, c, b.cols, accumulate) };
        return;
    }
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
    ($(#[$doc:meta])* $name:ident, $avx:ident, $avx512:ident, $f:ident) => {
        $(#[$doc])*
        pub fn $name(x: &mut [f32]) {
            match Isa::detect() {
                #[cfg(target_arch = "x86_64")]
                // SAFETY: the CPU supports AVX-512F, AVX2 and FMA (detected).
                Isa::Avx512 => unsafe { $avx512(x) },
                #[cfg(target_arch = "x86_64")]
                // SAFETY: the CPU supports AVX2 and FMA (detected).
                Isa::Avx2 => unsafe { $avx(x) },
                _ => x.iter_mut().for_each(|v| *v = $f(*v)),
            }
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,fma")]
        fn $avx(x: &mut [f32]) {
            x.iter_mut().for_each(|v| *v = $f(*v));
        }

        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx512f,avx2,fma")]
        fn $avx512(x: &mut [f32]) {
            x.iter_mut().for_each(|v| *v = $f(*v));
        }
    };
}

elementwise!(
    /// In-place logistic sigmoid of every element.
    sigmoid_inplace,
    sigmoid_avx2,
    sigmoid_avx512,
    sigmoid_f32
);
elementwise!(
    /// In-place `tanh` of every element.
    tanh_inplace,
    tanh_avx2,
    tanh_avx512,
    tanh_f32
);

/// The LSTM cell of one sequence, every gate in one pass: `pre [4H]` holds the gate
/// pre-activations `(i, f, g, o)` and is overwritten with the activated gates
/// `(σ(i), σ(f), tanh(g), σ(o))`; writes `c = σ(f)·c_prev + σ(i)·tanh(g)`, `tc = tanh(c)`
/// and `h = σ(o)·tc` (each `[H]`).
pub fn lstm_cell(pre: &mut [f32], c_prev: &[f32], c: &mut [f32], tc: &mut [f32], h: &mut [f32]) {
    let n = c.len();
    assert!(pre.len() == 4 * n && c_prev.len() == n && tc.len() == n && h.len() == n);
    match Isa::detect() {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: the CPU supports AVX-512F, AVX2 and FMA (detected).
        Isa::Avx512 => unsafe { lstm_cell_avx512(pre, c_prev, c, tc, h) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: the CPU supports AVX2 and FMA (detected).
        Isa::Avx2 => unsafe { lstm_cell_avx2(pre, c_prev, c, tc, h) },
        _ => lstm_cell_impl(pre, c_prev, c, tc, h),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx2,fma")]
fn lstm_cell_avx512(pre: &mut [f32], cp: &[f32], c: &mut [f32], tc: &mut [f32], h: &mut [f32]) {
    lstm_cell_impl(pre, cp, c, tc, h);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn lstm_cell_avx2(pre: &mut [f32], cp: &[f32], c: &mut [f32], tc: &mut [f32], h: &mut [f32]) {
    lstm_cell_impl(pre, cp, c, tc, h);
}

#[inline(always)]
fn lstm_cell_impl(pre: &mut [f32], c_prev: &[f32], c: &mut [f32], tc: &mut [f32], h: &mut [f32]) {
    let n = c.len();
    let (i, rest) = pre.split_at_mut(n);
    let (f, rest) = rest.split_at_mut(n);
    let (g, o) = rest.split_at_mut(n);
    let it = i
        .iter_mut()
        .zip(f.iter_mut())
        .zip(g.iter_mut())
        .zip(o.iter_mut());
    let out = c
        .iter_mut()
        .zip(tc.iter_mut())
        .zip(h.iter_mut())
        .zip(c_prev);
    for ((((iv, fv), gv), ov), (((cv, tv), hv), &cpv)) in it.zip(out) {
        let (si, sf, tg, so) = (
            sigmoid_f32(*iv),
            sigmoid_f32(*fv),
            tanh_f32(*gv),
            sigmoid_f32(*ov),
        );
        (*iv, *fv, *gv, *ov) = (si, sf, tg, so);
        *cv = sf * cpv + si * tg;
        *tv = tanh_f32(*cv);
        *hv = so * *tv;
    }
}

/// In-place ReLU.
pub fn relu_inplace(x: &mut [f32]) {
    x.iter_mut().for_each(|v| *v = v.max(0.0));
}

#[cfg(test)]
mod tests;
