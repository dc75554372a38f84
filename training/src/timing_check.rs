//! The consistency check of a timing agent read from `agent.json`: against the agent its
//! run's config builds (same model, task layout and feature count), so an agent with cut
//! weight vectors, out-of-range cell indices or a different timer is refused before use.

use chronocooked_models::TimingAgent;
use serde_json::Value;

fn check_learner(agent: &TimingAgent, fresh: &TimingAgent) -> Result<(), String> {
    let (l, f) = (&agent.learner, &fresh.learner);
    if l.actions != f.actions {
        return Err(format!(
            "field `learner.actions`: {} (allowed: {})",
            l.actions, f.actions
        ));
    }
    if l.features != f.features {
        return Err(format!(
            "field `learner.features`: {} (allowed: {}, the model's feature count)",
            l.features, f.features
        ));
    }
    let c = &l.config;
    if !(c.alpha > 0.0 && c.alpha <= 1.0) {
        return Err(format!(
            "field `learner.config.alpha`: {} (allowed: (0, 1])",
            c.alpha
        ));
    }
    for (name, v) in [("gamma", c.gamma), ("lambda", c.lambda)] {
        if !(0.0..=1.0).contains(&v) {
            return Err(format!(
                "field `learner.config.{name}`: {v} (allowed: [0, 1])"
            ));
        }
    }
    if !l.q_init.is_finite() {
        return Err("field `learner.q_init`: not a finite number".into());
    }
    if agent.oven_cells != fresh.oven_cells {
        return Err(format!(
            "field `oven_cells`: {:?} (allowed: {:?}, the task's ovens)",
            agent.oven_cells, fresh.oven_cells
        ));
    }
    // State index × action: a bound on every weight block's key.
    let max_key = u64::from(agent.state_count()).saturating_mul(l.actions as u64);
    for (key, w) in &l.weights {
        if w.len() != l.features {
            return Err(format!(
                "field `learner.weights.{key}`: {} values (allowed: exactly {}, one per feature)",
                w.len(),
                l.features
            ));
        }
        if u64::from(*key) >= max_key {
            return Err(format!(
                "field `learner.weights`: key {key} (allowed: below {max_key}, a state-action pair of the layout)"
            ));
        }
        if let Some(i) = w.iter().position(|x| !x.is_finite()) {
            return Err(format!(
                "field `learner.weights.{key}`: value {i} is not a finite number"
            ));
        }
    }
    Ok(())
}

/// Compares the shape of a loaded value with the fresh one at `path`: objects keep the
/// fresh object's keys, non-empty fresh arrays keep their length, numbers stay numbers.
/// Maps that start empty (learned memories) and arrays that start empty are not compared.
fn same_shape(path: &str, loaded: &Value, fresh: &Value) -> Result<(), String> {
    match (fresh, loaded) {
        (Value::Object(f), Value::Object(l)) => {
            for (k, fv) in f {
                let sub = format!("{path}.{k}");
                match l.get(k) {
                    Some(lv) => same_shape(&sub, lv, fv)?,
                    None if fv.is_null() => {}
                    None => return Err(format!("field `{sub}`: missing")),
                }
            }
            Ok(())
        }
        (Value::Array(f), Value::Array(l)) => {
            if f.is_empty() {
                return Ok(());
            }
            if f.len() != l.len() {
                return Err(format!(
                    "field `{path}`: {} values (allowed: exactly {})",
                    l.len(),
                    f.len()
                ));
            }
            for (i, (lv, fv)) in l.iter().zip(f).enumerate() {
                same_shape(&format!("{path}[{i}]"), lv, fv)?;
            }
            Ok(())
        }
        (Value::Number(_), Value::Number(_)) => Ok(()),
        (Value::Null, _) | (_, Value::Null) => Ok(()),
        (Value::Bool(_), Value::Bool(_)) | (Value::String(_), Value::String(_)) => Ok(()),
        (f, l) => Err(format!(
            "field `{path}`: {} (allowed: {})",
            kind(l),
            kind(f)
        )),
    }
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "an object",
    }
}

/// Checks `agent` (read from a file) against `fresh`, the untrained agent its config
/// builds: the model name, the task layout it reads (percept parser, choice and button
/// cells), the learner's sizes with every weight block of the feature count and finite, and
/// the timer of the same kind and shape. Returns the first problem, naming the field.
pub fn check_agent(agent: &TimingAgent, fresh: &TimingAgent) -> Result<(), String> {
    if agent.name != fresh.name {
        return Err(format!(
            "field `name`: {} (allowed: {}, the model of config.json)",
            agent.name, fresh.name
        ));
    }
    if agent.parser != fresh.parser {
        return Err(format!(
            "field `parser`: {:?} (allowed: {:?}, the layout of config.json's task)",
            agent.parser, fresh.parser
        ));
    }
    if agent.choice_cells != fresh.choice_cells || agent.button_cells != fresh.button_cells {
        return Err(
            "fields `choice_cells`/`button_cells`: not the cells of config.json's task layout"
                .into(),
        );
    }
    if agent.shows_ready != fresh.shows_ready || agent.judges != fresh.judges {
        return Err("fields `shows_ready`/`judges`: not those of config.json's task".into());
    }
    check_learner(agent, fresh)?;
    let value = |t: &TimingAgent| serde_json::to_value(&t.timer).unwrap_or(Value::Null);
    same_shape("timer", &value(agent), &value(fresh))?;
    for (name, v) in [
        ("config.epsilon", agent.config.epsilon),
        ("config.probe", agent.config.probe),
        ("config.opportunity_cost", agent.config.opportunity_cost),
    ] {
        if !(0.0..=1.0).contains(&v) {
            return Err(format!("field `{name}`: {v} (allowed: [0, 1])"));
        }
    }
    if !(agent.config.response_cost.is_finite() && agent.reward_rate.is_finite()) {
        return Err("fields `config.response_cost`/`reward_rate`: not finite numbers".into());
    }
    Ok(())
}
