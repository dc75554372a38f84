//! AVX-512F kernels (x86-64), chosen at run time by the dispatch in [`super`].
//!
//! The matrix product keeps an `R × 16·V` block of `C` in `R·V` zmm registers (`R ≤ 8`
//! rows, `V ≤ 4` vectors of 16 columns, `R·V ≤ 24`: with the `B` row and the broadcast at
//! most 29 of the 32 registers), streams `B` row by row and cuts the last, partial column
//! block with lane masks (masked-off lanes are neither read nor written: no padding copy).
//! For the recurrent step `B = W_hh` is first packed into contiguous panels of 64
//! columns ([`pack`]) so that the 1–8-row product streams it sequentially (a row-major
//! `W_hh` of 1024 columns puts every row of a column block on a new 4 KiB page, which
//! the hardware prefetchers do not follow).
//!
//! Hand-written rather than the `gemm` crate: measured at the engine's shapes with
//! `models/examples/kernel_bench.rs` (`BENCHMARKS.md`, "Recurrent kernels"), this kernel is
//! 2–5× faster on the 1–8-row recurrent products that dominate the recurrent cores and on
//! par with `gemm` 0.19 (whose default features compile no AVX-512 path) on the
//! 128-row window products.

use super::Mat;
use std::arch::x86_64::*;

/// Columns per packed panel (four zmm vectors).
pub(super) const PANEL: usize = 64;

/// Lane mask of the first `n.min(16)` lanes.
#[inline(always)]
fn lane_mask(n: usize) -> __mmask16 {
    if n >= 16 {
        0xFFFF
    } else {
        ((1u32 << n) - 1) as __mmask16
    }
}

/// Packs `b [K, N]` (or, with `transpose`, the transpose of `b [N, K]`) into
/// `⌈N/64⌉` zero-padded panels `[K, 64]`, panel after panel, in `out`.
pub(super) fn pack(b: Mat<'_>, transpose: bool, out: &mut Vec<f32>) {
    let (k, n) = if transpose {
        (b.cols, b.rows)
    } else {
        (b.rows, b.cols)
    };
    out.clear();
    out.resize(n.div_ceil(PANEL) * k * PANEL, 0.0);
    for (p, panel) in out.chunks_exact_mut(k * PANEL).enumerate() {
        let j0 = p * PANEL;
        let w = PANEL.min(n - j0);
        if transpose {
            for jj in 0..w {
                let src = b.row(j0 + jj);
                for (kk, &v) in src.iter().enumerate() {
                    panel[kk * PANEL + jj] = v;
                }
            }
        } else {
            for (kk, dst) in panel.chunks_exact_mut(PANEL).enumerate() {
                dst[..w].copy_from_slice(&b.row(kk)[j0..j0 + w]);
            }
        }
    }
}

/// One `R × 16·V` block of `C (+)= A·B`: `A[r, kk]` at `ap + r·lda + kk·acs`, `B` rows at `bp`
/// (stride `ldb`), `C` rows at `cp` (stride `ldc`), `k` terms, lane masks per vector.
/// `U` interleaved sets of accumulators (`k` split by parity when `U = 2`, summed at the
/// end) keep enough independent FMA chains in flight when `R·V` is small (one or two
/// rows: the recurrent step of one or two sequences).
///
/// # Safety
/// AVX-512F is available; `R` rows of `A` with `k` elements, `k` rows of `B` and `R` rows
/// of `C` are readable (and `C` writable) in every lane the masks select.
#[inline(always)]
unsafe fn tile<const R: usize, const V: usize, const U: usize>(
    (ap, lda, acs): (*const f32, usize, usize),
    (bp, ldb): (*const f32, usize),
    (cp, ldc): (*mut f32, usize),
    k: usize,
    masks: [__mmask16; V],
    accumulate: bool,
) {
    // SAFETY: every pointer below stays inside the rows and masked lanes the caller
    // guarantees (see the function's contract); AVX-512F is available.
    unsafe {
        let mut acc = [[[_mm512_setzero_ps(); V]; R]; U];
        if accumulate {
            for (r, acc_r) in acc[0].iter_mut().enumerate() {
                for (v, x) in acc_r.iter_mut().enumerate() {
                    *x = _mm512_maskz_loadu_ps(masks[v], cp.add(r * ldc + 16 * v));
                }
            }
        }
        let k_main = k - k % U;
        let mut kk = 0;
        while kk < k_main {
            for (u, acc_u) in acc.iter_mut().enumerate() {
                step::<R, V>(acc_u, (ap, lda, acs), (bp, ldb), kk + u, masks);
            }
            kk += U;
        }
        for kk in k_main..k {
            step::<R, V>(&mut acc[0], (ap, lda, acs), (bp, ldb), kk, masks);
        }
        let (first, rest) = acc.split_at_mut(1);
        for other in rest.iter() {
            for (x_r, o_r) in first[0].iter_mut().zip(other) {
                for (x, &o) in x_r.iter_mut().zip(o_r) {
                    *x = _mm512_add_ps(*x, o);
                }
            }
        }
        for (r, acc_r) in first[0].iter().enumerate() {
            for (v, &x) in acc_r.iter().enumerate() {
                _mm512_mask_storeu_ps(cp.add(r * ldc + 16 * v), masks[v], x);
            }
        }
    }
}

/// Term `kk` of a tile: `acc[r] += A[r, kk] · B[kk, ..]`.
///
/// # Safety
/// As [`tile`], for term `kk < k`.
#[inline(always)]
unsafe fn step<const R: usize, const V: usize>(
    acc: &mut [[__m512; V]; R],
    (ap, lda, acs): (*const f32, usize, usize),
    (bp, ldb): (*const f32, usize),
    kk: usize,
    masks: [__mmask16; V],
) {
    // SAFETY: row kk of B and column kk of the R rows of A exist (the caller's contract);
    // AVX-512F is available.
    unsafe {
        let brow = bp.add(kk * ldb);
        let bv: [__m512; V] =
            std::array::from_fn(|v| _mm512_maskz_loadu_ps(masks[v], brow.add(16 * v)));
        for (r, acc_r) in acc.iter_mut().enumerate() {
            let av = _mm512_set1_ps(*ap.add(r * lda + kk * acs));
            for (x, &bvv) in acc_r.iter_mut().zip(&bv) {
                *x = _mm512_fmadd_ps(av, bvv, *x);
            }
        }
    }
}

/// Rows `i0..i0 + r` (`r ≤ 8`) of `C` at columns `j0..j0 + w` from the `B` column block
/// at `bp` (row stride `ldb`), with `V` vectors per row (`16·V ≥ w`).
///
/// # Safety
/// As [`tile`], for the rows and columns named.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn block<const V: usize>(
    a: ATerm<'_>,
    (i0, r): (usize, usize),
    (bp, ldb): (*const f32, usize),
    (c, ldc): (*mut f32, usize),
    (j0, w): (usize, usize),
    accumulate: bool,
) {
    let masks: [__mmask16; V] = std::array::from_fn(|v| lane_mask(w.saturating_sub(16 * v)));
    let ap = a.rows_from(i0);
    let cp = (c.wrapping_add(i0 * ldc + j0), ldc);
    let (k, b) = (a.k(), (bp, ldb));
    // SAFETY: forwarded contract; r rows from i0 exist in A and C.
    unsafe {
        match r {
            8 if V <= 3 => tile::<8, V, 1>(ap, b, cp, k, masks, accumulate),
            7 if V <= 3 => tile::<7, V, 1>(ap, b, cp, k, masks, accumulate),
            6 => tile::<6, V, 1>(ap, b, cp, k, masks, accumulate),
            5 => tile::<5, V, 1>(ap, b, cp, k, masks, accumulate),
            4 => tile::<4, V, 1>(ap, b, cp, k, masks, accumulate),
            3 => tile::<3, V, 1>(ap, b, cp, k, masks, accumulate),
            2 => tile::<2, V, 2>(ap, b, cp, k, masks, accumulate),
            1 => tile::<1, V, 2>(ap, b, cp, k, masks, accumulate),
            _ => unreachable!("row block of {r} rows with {V} vectors"),
        }
    }
}

/// The left factor `A [M, K]` of a product: a row-major view, or the transpose of one
/// (`A = Xᵀ` for `X [K, M]`, read in place: the weight gradients `xᵀ·dy`).
#[derive(Clone, Copy)]
pub(super) enum ATerm<'a> {
    /// `A` itself.
    Plain(Mat<'a>),
    /// `A = Xᵀ`.
    Transposed(Mat<'a>),
}

impl ATerm<'_> {
    fn m(&self) -> usize {
        match self {
            ATerm::Plain(x) => x.rows,
            ATerm::Transposed(x) => x.cols,
        }
    }

    fn k(&self) -> usize {
        match self {
            ATerm::Plain(x) => x.cols,
            ATerm::Transposed(x) => x.rows,
        }
    }

    /// `(pointer to A[i0, 0], row stride, column stride)`.
    fn rows_from(&self, i0: usize) -> (*const f32, usize, usize) {
        match self {
            ATerm::Plain(x) => (x.data.as_ptr().wrapping_add(i0 * x.ld), x.ld, 1),
            ATerm::Transposed(x) => (x.data.as_ptr().wrapping_add(i0), 1, x.ld),
        }
    }
}

/// Rows per block for `V` vectors (`R·V ≤ 24` accumulators).
const fn rows_for(v: usize) -> usize {
    if v >= 4 { 6 } else { 8 }
}

/// `C (+)= A·B` for `A [M, K]` (row-major or the transpose of a row-major view), `B [K, N]`,
/// `C [M, N]` (row stride `ldc`), `B` row-major.
///
/// # Safety
/// The CPU supports AVX-512F; the caller has checked the shapes (`A`'s `K == b.rows`,
/// `ldc ≥ N`, `c.len() ≥ (M−1)·ldc + N`).
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn matmul(a: ATerm<'_>, b: Mat<'_>, c: &mut [f32], ldc: usize, accumulate: bool) {
    let (m, n) = (a.m(), b.cols);
    // Narrow products use fewer, fully used vectors per row; wide ones 3 (8 rows).
    let v = n.div_ceil(16).clamp(1, 4);
    let v = if v == 4 && n > 64 { 3 } else { v };
    let cp = c.as_mut_ptr();
    let width = 16 * v;
    let rows = if v == 4 { rows_for(4) } else { rows_for(3) };
    let mut j0 = 0;
    while j0 < n {
        let w = width.min(n - j0);
        let bp = (b.data.as_ptr().wrapping_add(j0), b.ld);
        let mut i0 = 0;
        while i0 < m {
            let r = rows.min(m - i0);
            // SAFETY: rows i0..i0 + r < M; columns j0..j0 + w ≤ N (masks), shapes checked
            // by the caller; AVX-512F available.
            unsafe {
                match v {
                    1 => block::<1>(a, (i0, r), bp, (cp, ldc), (j0, w), accumulate),
                    2 => block::<2>(a, (i0, r), bp, (cp, ldc), (j0, w), accumulate),
                    3 => block::<3>(a, (i0, r), bp, (cp, ldc), (j0, w), accumulate),
                    _ => block::<4>(a, (i0, r), bp, (cp, ldc), (j0, w), accumulate),
                }
            }
            i0 += r;
        }
        j0 += width;
    }
}

/// `C (+)= A·B` with `B [K, N]` packed by [`pack`] (`packed.len() = ⌈N/64⌉·K·64`).
///
/// # Safety
/// The CPU supports AVX-512F; `a.cols == K`, `ldc ≥ N`, `c.len() ≥ (M−1)·ldc + N` and
/// `packed` holds `B` packed for this `K` and `N` (checked by the caller).
#[target_feature(enable = "avx512f")]
pub(super) unsafe fn matmul_packed(
    a: Mat<'_>,
    packed: &[f32],
    n: usize,
    c: &mut [f32],
    ldc: usize,
    accumulate: bool,
) {
    let (m, k) = (a.rows, a.cols);
    let cp = c.as_mut_ptr();
    for (p, panel) in packed.chunks_exact(k * PANEL).enumerate() {
        let j0 = p * PANEL;
        let w = PANEL.min(n - j0);
        let mut i0 = 0;
        while i0 < m {
            let r = rows_for(4).min(m - i0);
            // SAFETY: the panel holds k rows of 64 columns; rows i0..i0 + r < M;
            // columns j0..j0 + w ≤ N (masks); AVX-512F available.
            unsafe {
                block::<4>(
                    ATerm::Plain(a),
                    (i0, r),
                    (panel.as_ptr(), PANEL),
                    (cp, ldc),
                    (j0, w),
                    accumulate,
                )
            };
            i0 += r;
        }
    }
}
