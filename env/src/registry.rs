//! The self-describing task registry: versioned ids → documented default configurations.
//! Each family declares its task in its own file (`task::family`); this module finds them.

use crate::error::EnvError;
use crate::markdown::Table;
use crate::task::{family, params};

pub use crate::task::TaskSpec;

/// Every registered task.
pub fn all_tasks() -> &'static [TaskSpec] {
    family::registered_tasks()
}

/// Tasks carrying `tag`.
pub fn tasks_with_tag(tag: &str) -> Vec<&'static TaskSpec> {
    all_tasks()
        .iter()
        .filter(|t| t.tags.contains(&tag))
        .collect()
}

/// Looks up a task by id (case-insensitive; the `-v0` suffix may be omitted).
pub fn find_task(id: &str) -> Result<&'static TaskSpec, EnvError> {
    let want = id.trim().to_ascii_lowercase();
    all_tasks()
        .iter()
        .find(|t| {
            let tid = t.id.to_ascii_lowercase();
            tid == want || tid.strip_suffix("-v0") == Some(want.as_str())
        })
        .ok_or_else(|| EnvError::UnknownTask {
            id: id.to_string(),
            known: all_tasks()
                .iter()
                .map(|t| t.id)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The guide's table (docs/tasks.md) of every registered task's own parameters, then the common ones
/// (generated; a test compares it with docs/tasks.md). It lives with the registry, which
/// knows every task, so that the parameter tables (`task::params`) need not know the registry.
pub fn parameters_markdown() -> String {
    let mut table = Table::new([
        "task",
        "key (aliases)",
        "type",
        "default",
        "allowed",
        "meaning",
    ]);
    let mut line = |task: &str, r: &params::ParamRow| {
        let aliases = if r.aliases.is_empty() {
            String::new()
        } else {
            format!(" ({})", r.aliases.join(", "))
        };
        table.row([
            task.to_string(),
            format!("`{}`{aliases}", r.key),
            r.kind.clone(),
            format!("`{}`", r.default),
            r.allowed.clone(),
            r.doc.clone(),
        ]);
    };
    let mut common = Vec::new();
    for t in all_tasks() {
        let config = t.default_config();
        for r in params::rows(&config) {
            if params::COMMON.iter().any(|c| c.key == r.key) {
                if common.is_empty() || !common.iter().any(|c: &params::ParamRow| c.key == r.key) {
                    common.push(r);
                }
            } else {
                line(&format!("`{}`", t.id), &r);
            }
        }
    }
    for r in &common {
        line("every task", r);
    }
    table.render()
}
