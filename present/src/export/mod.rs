//! Export of activity datasets and evaluation records to NPZ (readable by `numpy.load`),
//! CSV, and a JSON metadata file that describes every array (shape, dtype, units, meaning),
//! the event codes, dt and model/task/seed. Files are written atomically.
//!
//! Submodules: [`npz`] — the NPZ container (zip of `.npy` arrays); [`marker`] — the
//! folder's completeness marker `export.json`, written last.

pub mod marker;
pub mod npz;

use crate::export::npz::{NpyArray, NpyData, npz_bytes};
use chronocooked_analysis::records::{ConditionKind, EvalRecord};
use chronocooked_env::fs::write_atomic;
use chronocooked_models::{ActivityDataset, Marker};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// Event codes used in exported `event_code` arrays.
pub const EVENT_CODES: [(Marker, &str); 12] = [
    (Marker::OvenOn, "oven_on"),
    (Marker::OvenReady, "oven_ready"),
    (Marker::OvenCheck, "oven_check"),
    (Marker::Pickup, "pickup"),
    (Marker::Delivery, "delivery"),
    (Marker::Reward, "reward"),
    (Marker::Sink, "sink"),
    (Marker::Button, "button"),
    (Marker::OvenOn2, "oven_on2"),
    (Marker::OvenOn3, "oven_on3"),
    (Marker::Ready, "ready"),
    (Marker::Set, "set"),
];

fn code(m: Marker) -> i64 {
    EVENT_CODES.iter().position(|(k, _)| *k == m).unwrap_or(0) as i64
}

/// A CSV table (header + rows) as text through the `csv` crate: fields are quoted when they
/// hold a comma, quote or newline (model names are user input), lines end in `\n`.
pub fn csv_text<S: AsRef<str>>(header: &[&str], rows: &[Vec<S>]) -> Result<String, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header).map_err(|e| e.to_string())?;
    for r in rows {
        w.write_record(r.iter().map(AsRef::as_ref))
            .map_err(|e| e.to_string())?;
    }
    let bytes = w.into_inner().map_err(|e| e.to_string())?;
    String::from_utf8(bytes).map_err(|e| e.to_string())
}

fn describe(arrays: &[NpyArray], docs: &[(&str, &str, &str)]) -> Value {
    let mut m = serde_json::Map::new();
    for a in arrays {
        let (unit, what) = docs
            .iter()
            .find(|d| d.0 == a.name)
            .map_or(("", ""), |d| (d.1, d.2));
        let dtype = match &a.data {
            NpyData::F32(_) => "float32",
            NpyData::F64(_) => "float64",
            NpyData::I64(_) => "int64",
            NpyData::U8(_) => "uint8",
        };
        m.insert(
            a.name.clone(),
            json!({"shape": a.shape, "dtype": dtype, "units": unit, "description": what}),
        );
    }
    Value::Object(m)
}

fn save(dir: &Path, stem: &str, arrays: &[NpyArray], meta: Value) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let buf = npz_bytes(arrays)?;
    let npz = dir.join(format!("{stem}.npz"));
    write_atomic(&npz, &buf).map_err(|e| e.to_string())?;
    let meta_path = dir.join(format!("{stem}.meta.json"));
    let text = serde_json::to_string_pretty(&meta).map_err(|e| e.to_string())?;
    write_atomic(&meta_path, text.as_bytes()).map_err(|e| e.to_string())?;
    Ok(vec![npz, meta_path])
}

/// One export folder `out` from an activity dataset and/or an evaluation's records (what
/// `chronocooked export` writes): the files of [`export_activity`] and [`export_eval`]
/// between the removal of the completeness marker and its rewrite
/// ([`marker::write_export`]). Aligned activity spans up to `window` steps after oven-on.
pub fn export_folder(
    out: &Path,
    activity: Option<&ActivityDataset>,
    records: Option<&[EvalRecord]>,
    window: usize,
) -> Result<Vec<PathBuf>, String> {
    marker::write_export(out, |out| {
        let mut files = Vec::new();
        if let Some(ds) = activity {
            files.extend(export_activity(ds, out, window)?);
        }
        if let Some(records) = records {
            files.extend(export_eval(records, out)?);
        }
        Ok(files)
    })
}

/// Exports `dataset` into `dir`: `activity.npz`, `activity.meta.json`, `trials.csv`,
/// `units.csv`. Aligned arrays use oven-on and a window of up to `max_window` steps.
pub fn export_activity(
    dataset: &ActivityDataset,
    dir: &Path,
    max_window: usize,
) -> Result<Vec<PathBuf>, String> {
    let n = dataset.meta.n_units();
    let trials = &dataset.trials;
    let total: usize = trials.iter().map(|t| t.steps).sum();
    let mut offsets = vec![0i64];
    let mut activity = Vec::with_capacity(total * n);
    for t in trials {
        activity.extend_from_slice(&t.activity);
        offsets.push(offsets.last().copied().unwrap_or(0) + t.steps as i64);
    }
    let window = trials
        .iter()
        .filter_map(|t| {
            t.first(Marker::OvenOn)
                .map(|on| t.steps.saturating_sub(on as usize + 1))
        })
        .max()
        .unwrap_or(1)
        .clamp(1, max_window.max(1));
    let (aligned, used) = dataset.aligned(Marker::OvenOn, window - 1);
    let (mut et, mut es, mut ec) = (Vec::new(), Vec::new(), Vec::new());
    for (i, t) in trials.iter().enumerate() {
        for e in &t.events {
            et.push(i as i64);
            es.push(i64::from(e.step));
            ec.push(code(e.marker));
        }
    }
    let k = trials.len();
    let arrays = vec![
        NpyArray {
            name: "activity".into(),
            shape: vec![total, n],
            data: NpyData::F32(activity),
        },
        NpyArray {
            name: "trial_offsets".into(),
            shape: vec![k + 1],
            data: NpyData::I64(offsets),
        },
        NpyArray {
            name: "aligned".into(),
            shape: vec![used.len(), window, n],
            data: NpyData::F32(aligned),
        },
        NpyArray {
            name: "aligned_trials".into(),
            shape: vec![used.len()],
            data: NpyData::I64(used.iter().map(|&u| u as i64).collect()),
        },
        NpyArray {
            name: "td".into(),
            shape: vec![k],
            data: NpyData::I64(trials.iter().map(|t| i64::from(t.td)).collect()),
        },
        NpyArray {
            name: "start".into(),
            shape: vec![k, 2],
            data: NpyData::I64(
                trials
                    .iter()
                    .flat_map(|t| [t.start.0 as i64, t.start.1 as i64])
                    .collect(),
            ),
        },
        NpyArray {
            name: "reward".into(),
            shape: vec![k],
            data: NpyData::F32(trials.iter().map(|t| t.reward).collect()),
        },
        NpyArray {
            name: "success".into(),
            shape: vec![k],
            data: NpyData::U8(trials.iter().map(|t| u8::from(t.success)).collect()),
        },
        NpyArray {
            name: "event_trial".into(),
            shape: vec![et.len()],
            data: NpyData::I64(et),
        },
        NpyArray {
            name: "event_step".into(),
            shape: vec![es.len()],
            data: NpyData::I64(es),
        },
        NpyArray {
            name: "event_code".into(),
            shape: vec![ec.len()],
            data: NpyData::I64(ec),
        },
    ];
    let docs = [
        (
            "activity",
            "model units",
            "unit activity of every recorded step, trials concatenated: rows trial_offsets[i]..trial_offsets[i+1] are trial i; columns are units (see units)",
        ),
        (
            "trial_offsets",
            "rows",
            "first row of each trial in activity, plus the total",
        ),
        (
            "aligned",
            "model units",
            "activity aligned to oven-on: [trial, oven time 1..window, unit]; NaN after a trial ended",
        ),
        (
            "aligned_trials",
            "trial index",
            "which trial each row of aligned comes from (trials that turned the oven on)",
        ),
        ("td", "steps", "target duration of each trial"),
        ("start", "cell (row, col)", "start cell of each trial"),
        ("reward", "reward", "total reward of each trial"),
        (
            "success",
            "bool",
            "1 if the trial ended with a delivery paying the full reward available (the button reward on never-ready ovens)",
        ),
        ("event_trial", "trial index", "trial of each event marker"),
        (
            "event_step",
            "steps",
            "step (within its trial, 0 = first action) of each event marker",
        ),
        ("event_code", "code", "event kind, see event_codes"),
    ];
    let mut col = 0;
    let populations: Vec<Value> = dataset
        .meta
        .populations
        .iter()
        .map(|p| {
            let v = json!({"name": p.name, "size": p.size, "first_column": col});
            col += p.size;
            v
        })
        .collect();
    let meta = json!({
        "model": dataset.meta.model,
        "task": dataset.meta.task.id(),
        "env": dataset.meta.task.overrides(),
        "seed": dataset.meta.seed,
        "dt": dataset.meta.dt,
        "dt_unit": "model time per env step (1.0 = one step)",
        "populations": populations,
        "units": dataset.meta.unit_names(),
        "event_codes": EVENT_CODES.iter().enumerate().map(|(i, (_, n))| (i.to_string(), json!(n))).collect::<serde_json::Map<_, _>>(),
        "aligned_to": "oven_on",
        "arrays": describe(&arrays, &docs),
    });
    let mut files = save(dir, "activity", &arrays, meta)?;
    let rows: Vec<Vec<String>> = trials
        .iter()
        .enumerate()
        .map(|(i, t)| {
            vec![
                i.to_string(),
                t.td.to_string(),
                t.start.0.to_string(),
                t.start.1.to_string(),
                t.steps.to_string(),
                t.reward.to_string(),
                u8::from(t.success).to_string(),
            ]
        })
        .collect();
    let csv = csv_text(
        &[
            "trial",
            "td",
            "start_row",
            "start_col",
            "steps",
            "reward",
            "success",
        ],
        &rows,
    )?;
    write_atomic(&dir.join("trials.csv"), csv.as_bytes()).map_err(|e| e.to_string())?;
    let rows: Vec<Vec<String>> = dataset
        .meta
        .unit_names()
        .into_iter()
        .enumerate()
        .map(|(i, u)| vec![i.to_string(), u])
        .collect();
    let units = csv_text(&["column", "unit"], &rows)?;
    write_atomic(&dir.join("units.csv"), units.as_bytes()).map_err(|e| e.to_string())?;
    files.push(dir.join("trials.csv"));
    files.push(dir.join("units.csv"));
    Ok(files)
}

/// Exports evaluation records into `dir`: `episodes.npz`, `episodes.meta.json`,
/// `episodes.csv` (one row per episode: condition, TD, start, reward, success, FOC, steps).
pub fn export_eval(records: &[EvalRecord], dir: &Path) -> Result<Vec<PathBuf>, String> {
    let kind_code = |k: ConditionKind| {
        ConditionKind::ALL
            .iter()
            .position(|x| *x == k)
            .map_or(-1, |i| i as i64)
    };
    let foc: Vec<f64> = records
        .iter()
        .map(|r| {
            chronocooked_analysis::behaviour::foc::episode_foc(&r.episode)
                .map_or(f64::NAN, f64::from)
        })
        .collect();
    let counter: Vec<i64> = records
        .iter()
        .map(|r| {
            r.episode
                .infos
                .iter()
                .find_map(|i| i.counter)
                .map_or(-1, |c| match c {
                    chronocooked_env::Counter::Main => 0,
                    chronocooked_env::Counter::Short => 1,
                    chronocooked_env::Counter::Long => 2,
                    chronocooked_env::Counter::Anchor(i) => i64::from(i),
                })
        })
        .collect();
    let k = records.len();
    let arrays = vec![
        NpyArray {
            name: "condition".into(),
            shape: vec![k],
            data: NpyData::I64(
                records
                    .iter()
                    .map(|r| kind_code(r.condition.kind))
                    .collect(),
            ),
        },
        NpyArray {
            name: "td".into(),
            shape: vec![k],
            data: NpyData::I64(records.iter().map(|r| i64::from(r.condition.td)).collect()),
        },
        NpyArray {
            name: "factor".into(),
            shape: vec![k],
            data: NpyData::F64(
                records
                    .iter()
                    .map(|r| r.condition.factor.unwrap_or(f64::NAN))
                    .collect(),
            ),
        },
        NpyArray {
            name: "start".into(),
            shape: vec![k, 2],
            data: NpyData::I64(
                records
                    .iter()
                    .flat_map(|r| [r.episode.start.0 as i64, r.episode.start.1 as i64])
                    .collect(),
            ),
        },
        NpyArray {
            name: "reward".into(),
            shape: vec![k],
            data: NpyData::F32(records.iter().map(|r| r.episode.reward).collect()),
        },
        NpyArray {
            name: "success".into(),
            shape: vec![k],
            data: NpyData::U8(
                records
                    .iter()
                    .map(|r| u8::from(r.episode.success))
                    .collect(),
            ),
        },
        NpyArray {
            name: "steps".into(),
            shape: vec![k],
            data: NpyData::I64(
                records
                    .iter()
                    .map(|r| r.episode.actions.len() as i64)
                    .collect(),
            ),
        },
        NpyArray {
            name: "foc".into(),
            shape: vec![k],
            data: NpyData::F64(foc.clone()),
        },
        NpyArray {
            name: "counter".into(),
            shape: vec![k],
            data: NpyData::I64(counter.clone()),
        },
    ];
    let docs = [
        ("condition", "code", "condition kind, see condition_codes"),
        ("td", "steps", "target duration (bisection: probe duration)"),
        (
            "factor",
            "ratio",
            "PI release factor or buffer fraction of TD; NaN when not applicable",
        ),
        ("start", "cell (row, col)", "start cell"),
        ("reward", "reward", "total episode reward"),
        (
            "success",
            "bool",
            "1 if the episode ended with a delivery paying the full reward available (the button reward on never-ready ovens)",
        ),
        ("steps", "steps", "episode length"),
        (
            "foc",
            "steps of oven time",
            "first oven check (NaN without pickup)",
        ),
        (
            "counter",
            "code",
            "delivery counter: -1 none, 0 main, 1 short, 2 long",
        ),
    ];
    let meta = json!({
        "condition_codes": ConditionKind::ALL.map(ConditionKind::as_str),
        "arrays": describe(&arrays, &docs),
    });
    let mut files = save(dir, "episodes", &arrays, meta)?;
    let rows: Vec<Vec<String>> = records
        .iter()
        .enumerate()
        .map(|(i, r)| {
            vec![
                i.to_string(),
                r.condition.kind.to_string(),
                r.condition.task.id().to_string(),
                r.condition.td.to_string(),
                r.condition.factor.map_or(String::new(), |f| f.to_string()),
                r.episode.start.0.to_string(),
                r.episode.start.1.to_string(),
                r.episode.reward.to_string(),
                u8::from(r.episode.success).to_string(),
                r.episode.actions.len().to_string(),
                if foc[i].is_finite() {
                    foc[i].to_string()
                } else {
                    String::new()
                },
                counter[i].to_string(),
            ]
        })
        .collect();
    let csv = csv_text(
        &[
            "episode",
            "condition",
            "task",
            "td",
            "factor",
            "start_row",
            "start_col",
            "reward",
            "success",
            "steps",
            "foc",
            "counter",
        ],
        &rows,
    )?;
    write_atomic(&dir.join("episodes.csv"), csv.as_bytes()).map_err(|e| e.to_string())?;
    files.push(dir.join("episodes.csv"));
    Ok(files)
}
