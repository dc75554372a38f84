//! Quick probe: train each timing agent on a task and print its learning curve.
//! `cargo run --release -p chronocooked-models --example timing_probe -- FixedInterval-v0 td=12`
use chronocooked_env::{ChronoEnv, make_config};
use chronocooked_models::timing::zoo::{TIMING_MODELS, make_timing_agent};
use chronocooked_models::{TimingTrainConfig, train_timing_agent};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let task = args.first().cloned().unwrap_or("FixedInterval-v0".into());
    let overrides: Vec<String> = args
        .iter()
        .skip(1)
        .filter(|a| a.contains('='))
        .cloned()
        .collect();
    let episodes: usize = std::env::var("EPISODES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(6000);
    let only = std::env::var("MODEL").ok();
    let config = make_config(&task, &overrides).unwrap();
    let env = ChronoEnv::new(&config).unwrap();
    let tds: Vec<u32> = match &config.params {
        chronocooked_env::TaskParams::Bisection { short, long } => vec![*short, *long],
        p => vec![p.td().unwrap_or(12)],
    };
    for m in TIMING_MODELS {
        if only.as_deref().is_some_and(|o| o != m.name) {
            continue;
        }
        let t0 = std::time::Instant::now();
        let mut agent = make_timing_agent(m.name, &env, 0).unwrap();
        let train = TimingTrainConfig {
            episodes,
            eval_every: episodes / 6,
            ..Default::default()
        };
        let curve = train_timing_agent(&mut agent, &config, &train, &tds, 0, |_| {}).unwrap();
        let pts: Vec<String> = curve
            .iter()
            .map(|p| {
                format!(
                    "{}:{:.2}/{:.2}",
                    p.episode,
                    p.train_success,
                    p.eval_success.unwrap_or(-1.0)
                )
            })
            .collect();
        println!(
            "{:20} {:.1}s {}",
            m.name,
            t0.elapsed().as_secs_f64(),
            pts.join(" ")
        );
    }
}
