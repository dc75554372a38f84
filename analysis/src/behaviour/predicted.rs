//! Where a timing model's own rule puts its category boundaries: its timer alone — the
//! learned anchor memories, its noise and its decision rule, without the task or the TD
//! learner — judges many probe intervals at every whole step between two neighbouring
//! anchors, and the logistic fit of [`super::psychometric`] over those probes (the fit the
//! lab applies to a run's choices, [`super::categorization`]) gives the boundary the run's
//! fitted boundary is compared with. For drift-diffusion the same number follows from its
//! closed form (`chronocooked_models::timing::judgment::ddm_judgment_p_long`; tested equal).

use super::psychometric::{FitError, ProbeCounts, fit_logistic};
use chronocooked_models::timing::timers::Timer;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;

/// The predicted boundary (steps) between every pair of neighbouring `anchors` (steps,
/// ascending), from `trials` judgments of `timer` per whole-step probe between the pair
/// (both anchors included); `seed` seeds the timer's noise. A judgment of another category
/// than the pair's two is not a choice between them (left out, as the metric leaves out
/// deliveries to other counters).
pub fn predicted_boundaries(
    timer: &mut Timer,
    anchors: &[u32],
    trials: u32,
    seed: u64,
) -> Result<Vec<f64>, FitError> {
    let k = anchors.len();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut out = Vec::new();
    for (i, pair) in anchors.windows(2).enumerate() {
        let mut probes = Vec::new();
        for t in pair[0]..=pair[1] {
            let (mut valid, mut upper) = (0, 0);
            for _ in 0..trials {
                timer.clear();
                timer.onset(1, k, &mut rng);
                for step in 1..=t {
                    timer.tick(step, &mut rng);
                }
                match timer.judge(k).map(usize::from) {
                    Some(c) if c == i => valid += 1,
                    Some(c) if c == i + 1 => {
                        valid += 1;
                        upper += 1;
                    }
                    _ => {}
                }
            }
            probes.push(ProbeCounts {
                t: f64::from(t),
                valid,
                long: upper,
                failed: 0,
            });
        }
        out.push(fit_logistic(&probes)?.bp);
    }
    Ok(out)
}
