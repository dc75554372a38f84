//! Synthetic populations shared by the unit-category tests.

use chronocooked_analysis::neural::Cube;
use rand::Rng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// A standard normal draw (Irwin–Hall sum of 12 uniforms, less 6).
pub fn gauss(rng: &mut Xoshiro256PlusPlus) -> f64 {
    (0..12).map(|_| rng.random::<f64>()).sum::<f64>() - 6.0
}

/// `[trials, time, units]` from `f(trial, t, unit)`, generated unit by unit (each unit's
/// trials an independent series).
pub fn cube(
    trials: usize,
    time: usize,
    units: usize,
    mut f: impl FnMut(usize, usize, usize) -> f64,
) -> Cube {
    let mut data = vec![0.0; trials * time * units];
    for i in 0..units {
        for k in 0..trials {
            for t in 0..time {
                data[(k * time + t) * units + i] = f(k, t, i);
            }
        }
    }
    Cube::new(trials, time, units, data).expect("trials × time × units values")
}
