//! Seeded parameter initialisers (independent of burn's global RNG, so that
//! `(config, seed)` fixes every initial weight even when runs share a process).

use burn::module::Param;
use burn::nn::Linear;
use burn::tensor::{Device, Tensor, TensorData};
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// RNG used for initialisation.
pub type InitRng = Xoshiro256PlusPlus;

/// One standard-normal draw (Box–Muller). Kept rather than `rand_distr`'s ziggurat: every
/// initial weight, and so every learning curve of a given seed, depends on these exact draws.
fn normal(rng: &mut InitRng) -> f64 {
    let u1: f64 = rng.random::<f64>().max(1e-300);
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// A `rows × cols` (row-major) matrix with orthonormal rows or columns (whichever
/// are fewer), scaled by `gain` — the orthogonal initialiser of Saxe et al. (2014)
/// that Stable-Baselines3 uses, computed by modified Gram–Schmidt on a Gaussian matrix.
pub fn orthogonal(rows: usize, cols: usize, gain: f64, rng: &mut InitRng) -> Vec<f32> {
    // Orthonormalise the `k` vectors of length `n` along the smaller dimension.
    let (k, n) = if rows <= cols {
        (rows, cols)
    } else {
        (cols, rows)
    };
    let mut vecs: Vec<Vec<f64>> = Vec::with_capacity(k);
    while vecs.len() < k {
        let mut v: Vec<f64> = (0..n).map(|_| normal(rng)).collect();
        for u in &vecs {
            let d: f64 = v.iter().zip(u).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(u).for_each(|(a, b)| *a -= d * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-8 {
            v.iter_mut().for_each(|a| *a /= norm);
            vecs.push(v);
        }
    }
    let mut out = vec![0f32; rows * cols];
    for r in 0..rows {
        for c in 0..cols {
            let x = if rows <= cols { vecs[r][c] } else { vecs[c][r] };
            out[r * cols + c] = (x * gain) as f32;
        }
    }
    out
}

/// `len` draws from U(−bound, bound).
pub fn uniform(len: usize, bound: f64, rng: &mut InitRng) -> Vec<f32> {
    (0..len)
        .map(|_| ((rng.random::<f64>() * 2.0 - 1.0) * bound) as f32)
        .collect()
}

/// A float parameter of shape `shape` holding `values` (row-major).
pub fn param<const D: usize>(
    values: Vec<f32>,
    shape: [usize; D],
    device: &Device,
) -> Param<Tensor<D>> {
    Param::from_tensor(Tensor::from_data(TensorData::new(values, shape), device))
}

/// A dense layer `y = x W + b` with `W: [d_in, d_out]` orthogonal (gain `gain`) and `b = 0`.
pub fn linear_orthogonal(
    d_in: usize,
    d_out: usize,
    gain: f64,
    rng: &mut InitRng,
    device: &Device,
) -> Linear {
    Linear {
        weight: param(orthogonal(d_in, d_out, gain, rng), [d_in, d_out], device),
        bias: Some(param(vec![0.0; d_out], [d_out], device)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn orthogonal_columns_are_orthonormal() {
        let mut rng = InitRng::seed_from_u64(3);
        for (r, c) in [(6, 4), (4, 6), (5, 5)] {
            let m = orthogonal(r, c, 2.0, &mut rng);
            let k = r.min(c);
            for a in 0..k {
                for b in 0..k {
                    let dot: f32 = if r >= c {
                        (0..r).map(|i| m[i * c + a] * m[i * c + b]).sum()
                    } else {
                        (0..c).map(|j| m[a * c + j] * m[b * c + j]).sum()
                    };
                    let want = if a == b { 4.0 } else { 0.0 };
                    assert!((dot - want).abs() < 1e-4, "{r}x{c} ({a},{b}) {dot}");
                }
            }
        }
    }
}
