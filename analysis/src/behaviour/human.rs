//! Recorded human play (`env play` JSON lines, the replay trace shape) as evaluation
//! records, so people and agents go through the same metrics.

use crate::records::EvalRecord;
use chronocooked_env::trace::TraceLine;
use chronocooked_models::EpisodeRecord;
use chronocooked_models::agent::is_success;

/// Parses a trace file (one or more episodes, each starting with its reset line) into
/// records. A recording whose reset lines carry their seed and options (`env play`) is
/// first replayed and checked line by line against the task
/// ([`chronocooked_env::trace::verify_recording`]), so an edited reward, observation or
/// info field is refused rather than scored. Errors name the line (and the field).
pub fn records_from_trace(text: &str) -> Result<Vec<EvalRecord>, String> {
    let lines: Vec<(usize, TraceLine)> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, line)| {
            serde_json::from_str(line)
                .map(|t| (i + 1, t))
                .map_err(|e| format!("line {}: {e}", i + 1))
        })
        .collect::<Result<_, _>>()?;
    chronocooked_env::trace::verify_recording(&lines)?;
    let mut out: Vec<EvalRecord> = Vec::new();
    for (n, t) in lines {
        match t.action {
            None => {
                let config = t.task_config().map_err(|e| format!("line {n}: {e}"))?;
                config
                    .validate()
                    .map_err(|e| format!("line {n}: config: {e}"))?;
                // The task as played, every parameter of the recording's reset line (its
                // anchors, its ovens, its priors), so the metrics score the episode against
                // the rules it was played under, not the registered defaults.
                let condition = config
                    .played_condition(t.info.td, t.info.never_ready)
                    .map_err(|e| format!("line {n}: {e}"))?;
                out.push(EvalRecord {
                    condition,
                    episode: EpisodeRecord {
                        td: t.info.td,
                        start: (t.info.agent.0 as usize, t.info.agent.1 as usize),
                        seed: 0,
                        reward: 0.0,
                        success: false,
                        actions: Vec::new(),
                        infos: Vec::new(),
                        ovens: Vec::new(),
                    },
                });
            }
            Some(a) => {
                let rec = out
                    .last_mut()
                    .ok_or_else(|| format!("line {n}: step before any reset line"))?;
                rec.episode.actions.push(a);
                rec.episode.infos.push(t.info);
                rec.episode.ovens.extend(t.ovens);
                rec.episode.reward += t.reward;
                if is_success(&t.info, t.reward) {
                    rec.episode.success = true;
                }
            }
        }
    }
    for (k, r) in out.iter().enumerate() {
        r.validate()
            .map_err(|e| format!("episode {}: {e}", k + 1))?;
    }
    Ok(out)
}
