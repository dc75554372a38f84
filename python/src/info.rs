//! The Rust [`Info`] on the Python side: a dict of plain Python values (scalar env) or a
//! dict of numpy arrays `[N]` (vector env).
//!
//! Codes used by the array form: `counter` −1 none, 0 main, 1 short, 2 long (multi-anchor:
//! the counter number 1…4, named `anchor1`… in the dict form); `carrying`
//! 0 nothing, 1 onion, 2 soup; `events` the event bit set (`EVENT_FLAGS`); `agent` `[N, 2]`
//! (row, col).

use chronocooked_env::{Carry, Counter, Events, Info, OvenSet};
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A serialisable Rust value as plain Python objects (dicts, lists, numbers; through JSON).
pub(crate) fn to_py<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let json =
        serde_json::to_string(value).map_err(|e| crate::errors::runtime_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (json,))
}

fn counter_name(c: Option<Counter>) -> Option<String> {
    c.map(|c| match c {
        Counter::Main => "main".into(),
        Counter::Short => "short".into(),
        Counter::Long => "long".into(),
        Counter::Anchor(i) => format!("anchor{i}"),
    })
}

fn counter_code(c: Option<Counter>) -> i8 {
    match c {
        None => -1,
        Some(Counter::Main) => 0,
        Some(Counter::Short) => 1,
        Some(Counter::Long) => 2,
        Some(Counter::Anchor(i)) => i as i8,
    }
}

fn carry_name(c: Carry) -> &'static str {
    match c {
        Carry::Nothing => "nothing",
        Carry::Onion => "onion",
        Carry::Soup => "soup",
    }
}

fn carry_code(c: Carry) -> i8 {
    match c {
        Carry::Nothing => 0,
        Carry::Onion => 1,
        Carry::Soup => 2,
    }
}

/// `{name: bit}` of the event flags (the `events` bit set of the vector env's info).
pub fn event_flags(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for (bit, name) in Events::NAMES {
        d.set_item(name, bit)?;
    }
    Ok(d)
}

/// The info of one step as a dict of plain Python values (timers in steps, −1 = off); in
/// the multi-oven task with `ovens`, every oven's state (`td`, `timer`, `on_time`,
/// `off_time`, `delivered`: lists of one value per oven).
pub fn info_dict<'py>(
    py: Python<'py>,
    i: &Info,
    ovens: Option<&OvenSet>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("timestep", i.timestep)?;
    d.set_item("td", i.td)?;
    d.set_item("oven_timer", i.oven_timer)?;
    d.set_item("timer_at_action", i.timer_at_action)?;
    d.set_item("oven_state", i.oven_state)?;
    d.set_item("oven_off_time", i.oven_off_time)?;
    d.set_item("counter", counter_name(i.counter))?;
    d.set_item("events", i.events.names())?;
    d.set_item("next_to_oven", i.next_to_oven)?;
    d.set_item("agent", (i.agent.0, i.agent.1))?;
    d.set_item("carrying", carry_name(i.carrying))?;
    d.set_item("never_ready", i.never_ready)?;
    d.set_item("manual_stop_time", i.manual_stop_time)?;
    d.set_item("sink_count", i.sink_count)?;
    d.set_item("last_sink_timer", i.last_sink_timer)?;
    if let Some(ovens) = ovens {
        let n = ovens.n as usize;
        let o = PyDict::new(py);
        o.set_item("td", ovens.td[..n].to_vec())?;
        o.set_item("timer", ovens.timer[..n].to_vec())?;
        o.set_item("on_time", ovens.on_time[..n].to_vec())?;
        o.set_item("off_time", ovens.off_time[..n].to_vec())?;
        o.set_item("delivered", ovens.delivered[..n].to_vec())?;
        d.set_item("ovens", o)?;
    }
    Ok(d)
}

/// The infos of N envs as a dict of fresh numpy arrays `[N]` (`agent`: `[N, 2]`).
pub fn info_arrays<'py>(py: Python<'py>, infos: &[Info]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let col_i64 = |f: fn(&Info) -> i64| infos.iter().map(f).collect::<Vec<i64>>();
    d.set_item(
        "timestep",
        col_i64(|i| i64::from(i.timestep)).into_pyarray(py),
    )?;
    d.set_item("td", col_i64(|i| i64::from(i.td)).into_pyarray(py))?;
    d.set_item(
        "oven_timer",
        col_i64(|i| i64::from(i.oven_timer)).into_pyarray(py),
    )?;
    d.set_item(
        "timer_at_action",
        col_i64(|i| i64::from(i.timer_at_action)).into_pyarray(py),
    )?;
    d.set_item(
        "oven_state",
        infos
            .iter()
            .map(|i| i.oven_state as i8)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "oven_off_time",
        col_i64(|i| i64::from(i.oven_off_time)).into_pyarray(py),
    )?;
    d.set_item(
        "counter",
        infos
            .iter()
            .map(|i| counter_code(i.counter))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "events",
        infos
            .iter()
            .map(|i| i.events.0)
            .collect::<Vec<u16>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "next_to_oven",
        infos
            .iter()
            .map(|i| i.next_to_oven)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    let agent: Vec<i64> = infos
        .iter()
        .flat_map(|i| [i64::from(i.agent.0), i64::from(i.agent.1)])
        .collect();
    let agent: Bound<'py, PyArray2<i64>> = agent.into_pyarray(py).reshape([infos.len(), 2])?;
    d.set_item("agent", agent)?;
    d.set_item(
        "carrying",
        infos
            .iter()
            .map(|i| carry_code(i.carrying))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "never_ready",
        infos
            .iter()
            .map(|i| i.never_ready)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "manual_stop_time",
        col_i64(|i| i64::from(i.manual_stop_time)).into_pyarray(py),
    )?;
    d.set_item(
        "sink_count",
        col_i64(|i| i64::from(i.sink_count)).into_pyarray(py),
    )?;
    d.set_item(
        "last_sink_timer",
        col_i64(|i| i64::from(i.last_sink_timer)).into_pyarray(py),
    )?;
    Ok(d)
}
