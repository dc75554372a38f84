//! FOC per TD for each timing agent trained on FI at that TD.
use chronocooked_analysis::episode_foc;
use chronocooked_env::{ChronoEnv, make_config};
use chronocooked_models::timing::zoo::{TIMING_MODELS, make_timing_agent};
use chronocooked_models::{TimingTrainConfig, evaluate_agent, train_timing_agent};

fn main() {
    let episodes: usize = std::env::var("EPISODES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6000);
    let only = std::env::var("MODEL").ok();
    for m in TIMING_MODELS {
        if only.as_deref().is_some_and(|o| o != m.name) {
            continue;
        }
        let mut line = format!("{:20}", m.name);
        for td in [4u32, 6, 9, 12, 18, 24] {
            let config = make_config("FixedInterval-v0", &[format!("td={td}")]).unwrap();
            let env = ChronoEnv::new(&config).unwrap();
            let mut agent = make_timing_agent(m.name, &env, 0).unwrap();
            let train = TimingTrainConfig {
                episodes,
                eval_every: 0,
                ..Default::default()
            };
            let curve = train_timing_agent(&mut agent, &config, &train, &[td], 0, |_| {}).unwrap();
            let mut focs = Vec::new();
            let mut succ = 0;
            for rep in 0..5u64 {
                let recs = evaluate_agent(&mut agent, &config, &[td], 100 + rep, None).unwrap();
                succ += recs.iter().filter(|r| r.success).count();
                focs.extend(recs.iter().filter_map(episode_foc));
            }
            let mean = focs.iter().map(|&f| f as f64).sum::<f64>() / focs.len().max(1) as f64;
            let sd = (focs.iter().map(|&f| (f as f64 - mean).powi(2)).sum::<f64>()
                / focs.len().max(1) as f64)
                .sqrt();
            line += &format!(
                " TD{td}: {mean:5.1}±{sd:4.1} ({:.2}|{:.2})",
                curve.last().unwrap().eval_success.unwrap(),
                succ as f64 / 60.0
            );
        }
        println!("{line}");
    }
}
