//! Matrix-product kernels at the native engine's shapes: the AVX2 and AVX-512 kernels of
//! `kernels::matmul_isa`, the product with `B` packed once (`kernels::matmul_packed`,
//! as the recurrent step uses it) and the `gemm` crate (one thread), GFLOP/s, median of 7 runs.
//!
//!     cargo run --release -p chronocooked-models --example kernel_bench
//!
//! Shapes `M × K × N` (`C [M, N] = A [M, K] · B [K, N]`): the recurrent step of 1–8
//! sequences (`h W_hh`, `K = H`, `N = G·H`, and its backward `dg W_hhᵀ`), the window's
//! input projection, weight gradient and head products (128 rows). Rates are per second of
//! this thread's CPU time (other processes on the core do not count against them).

use chronocooked_models::deep::native::kernels::{Isa, Mat, Packed, matmul_isa, matmul_packed};
use std::time::Instant;

fn data(len: usize, seed: u32) -> Vec<f32> {
    (0..len)
        .map(|i| (((i as u32).wrapping_mul(2_654_435_761) ^ seed) % 1000) as f32 / 500.0 - 1.0)
        .collect()
}

/// This thread's time on a CPU (seconds; Linux `/proc/thread-self/schedstat`), so that
/// the rates do not count time the scheduler gave to other processes; wall time elsewhere.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(s.split_whitespace().next()?.parse::<f64>().ok()? * 1e-9)
}

fn time(flop: f64, mut f: impl FnMut()) -> f64 {
    // Repeat so that one run lasts ≥ 20 ms, then take the median rate of 7 runs.
    let t = Instant::now();
    f();
    let once = t.elapsed().as_secs_f64().max(1e-7);
    let reps = ((0.02 / once) as usize).max(1);
    let mut rates: Vec<f64> = (0..7)
        .map(|_| {
            let (t, c) = (Instant::now(), cpu_seconds());
            for _ in 0..reps {
                f();
            }
            let secs = match (c, cpu_seconds()) {
                (Some(a), Some(b)) if b > a => b - a,
                _ => t.elapsed().as_secs_f64(),
            };
            flop * reps as f64 / secs / 1e9
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    rates[3]
}

fn main() {
    let shapes: &[(usize, usize, usize, &str)] = &[
        (1, 256, 1024, "LSTM256 step, 1 seq"),
        (2, 256, 1024, "LSTM256 step, 2 seq"),
        (8, 256, 1024, "LSTM256 step, 8 seq"),
        (1, 1024, 256, "LSTM256 step bwd, 1 seq"),
        (2, 1024, 256, "LSTM256 step bwd, 2 seq"),
        (1, 125, 500, "LSTM125 step, 1 seq"),
        (8, 125, 500, "LSTM125 step, 8 seq"),
        (1, 500, 125, "LSTM125 step bwd, 1 seq"),
        (1, 256, 256, "CTRNN256 step, 1 seq"),
        (128, 64, 1024, "LSTM256 input projection"),
        (128, 1024, 64, "LSTM256 input-projection bwd"),
        (256, 128, 1024, "LSTM256 W_hh gradient"),
        (125, 128, 500, "LSTM125 W_hh gradient"),
        (128, 256, 128, "head hidden"),
        (1920, 6, 8, "conv1 (1x1, 15 cells)"),
    ];
    println!(
        "{:<32} {:>9} {:>9} {:>9} {:>9}",
        "shape (GFLOP/s)", "avx2", "avx512", "packed", "gemm"
    );
    for &(m, k, n, what) in shapes {
        let (a, b) = (data(m * k, 1), data(k * n, 2));
        let mut c = vec![0f32; m * n];
        let flop = 2.0 * (m * k * n) as f64;
        let mut row = format!("{what:<24} {m}x{k}x{n}");
        row = format!("{row:<32}");
        for isa in [Isa::Avx2, Isa::Avx512] {
            if isa.supported() {
                let r = time(flop, || {
                    matmul_isa(
                        isa,
                        Mat::new(&a, m, k),
                        Mat::new(&b, k, n),
                        &mut c,
                        n,
                        false,
                    )
                });
                row += &format!(" {r:>9.1}");
            } else {
                row += &format!(" {:>9}", "-");
            }
        }
        let mut packed = Packed::default();
        packed.pack(Mat::new(&b, k, n), false);
        let r = time(flop, || {
            matmul_packed(Mat::new(&a, m, k), &packed, &mut c, n, false)
        });
        row += &format!(" {r:>9.1}");
        let r = time(flop, || {
            // SAFETY: row-major A [m, k], B [k, n], C [m, n], all of those lengths.
            unsafe {
                gemm::gemm(
                    m,
                    n,
                    k,
                    c.as_mut_ptr(),
                    1,
                    n as isize,
                    false,
                    a.as_ptr(),
                    1,
                    k as isize,
                    b.as_ptr(),
                    1,
                    n as isize,
                    0.0,
                    1.0,
                    false,
                    false,
                    false,
                    gemm::Parallelism::None,
                )
            }
        });
        row += &format!(" {r:>9.1}");
        println!("{row}");
    }
}
