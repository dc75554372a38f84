//! `agreement.json`: how many published numbers agree with the lab under each rule (per
//! table × source × rule), and a **negative control** — the same rules applied to
//! deliberately mismatched pairs (the paper's LSTM125 numbers against the lab's reservoir
//! CTRNN125 and against its trained CTRNN125, the paper's CTRNN125 against the lab's LSTM125, the same at size 256, the paper's size-8 numbers
//! against the lab's size 256 or 125), beside the faithful pairs on the same numbers — so a reader
//! sees how often each rule agrees by chance.

use super::bisection::BisectionModel;
use super::compare::{ComparisonRow, Z_AGREE, compare_numbers, paper_model};
use super::fi::FiModel;
use super::multitimer::MtCell;
use super::reference::{
    APPENDIX_PREFIX, PaperNumber, appendix_fi_numbers, appendix_numbers, lab_model,
    multitimer_2_10_numbers, numbers,
};
use chronocooked_env::markdown::Table;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The two rules, as `agreement.json` names them.
pub const RULES: [&str; 2] = ["old", "z"];

/// Verdict counts of one group of comparison rows under one rule.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Counts {
    /// Rows.
    pub rows: usize,
    /// `yes`.
    pub yes: usize,
    /// `no` (including one side NaN, the other not).
    pub no: usize,
    /// `n/a` (too few runs or TDs for a verdict).
    pub na: usize,
    /// `both-nan`.
    pub both_nan: usize,
    /// `yes / (yes + no)` (NaN when both are 0).
    pub rate: f64,
}

impl Counts {
    /// Counts of the verdicts `v`.
    pub fn of<'a>(v: impl IntoIterator<Item = &'a str>) -> Self {
        let mut c = Counts::default();
        for x in v {
            c.rows += 1;
            match x {
                "yes" => c.yes += 1,
                "no" => c.no += 1,
                "both-nan" => c.both_nan += 1,
                _ => c.na += 1,
            }
        }
        c.rate = if c.yes + c.no == 0 {
            f64::NAN
        } else {
            c.yes as f64 / (c.yes + c.no) as f64
        };
        c
    }
}

/// The verdict of `r` under `rule` (`old` or `z`).
pub fn verdict<'a>(r: &'a ComparisonRow, rule: &str) -> &'a str {
    if rule == "old" { &r.agree } else { &r.agree_z }
}

/// Counts of one table × source × rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TableCounts {
    /// Table (`all` = every table of that source).
    pub table: String,
    /// `paper` or `notebook`.
    pub source: String,
    /// `old` or `z`.
    pub rule: String,
    /// The counts.
    #[serde(flatten)]
    pub counts: Counts,
}

/// One pairing of the negative control (or its faithful counterpart) under one rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ControlCounts {
    /// Which pairing (`paper LSTM125 vs lab ctrnn-reservoir125`, …).
    pub pairing: String,
    /// `false` = deliberately mismatched (a negative control), `true` = the faithful pairing
    /// of the same paper numbers.
    pub matched: bool,
    /// `paper`, `notebook` or `all`.
    pub source: String,
    /// `old` or `z`.
    pub rule: String,
    /// The counts.
    #[serde(flatten)]
    pub counts: Counts,
}

/// Everything `agreement.json` holds.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Agreement {
    /// The rules in words.
    pub rules: BTreeMap<String, String>,
    /// Per table × source × rule, and `all` per source × rule.
    pub counts: Vec<TableCounts>,
    /// The negative control (mismatched) and the faithful pairs on the same numbers.
    pub negative_control: Vec<ControlCounts>,
    /// What the control can and cannot show.
    pub notes: Vec<String>,
}

/// Per table × source × rule counts of `rows`, then `all` per source × rule.
pub fn table_counts(rows: &[ComparisonRow]) -> Vec<TableCounts> {
    let mut keys: Vec<(String, String)> = rows
        .iter()
        .map(|r| (r.table.clone(), r.source.clone()))
        .collect();
    keys.dedup();
    let mut seen = Vec::new();
    keys.retain(|k| {
        let new = !seen.contains(k);
        seen.push(k.clone());
        new
    });
    // `all`: the main text's tables; `appendix`: the appendix's sizes 8 and 256 together.
    for src in ["paper", "notebook"] {
        keys.push(("all".into(), src.into()));
        if rows
            .iter()
            .any(|r| r.source == src && r.table.starts_with(APPENDIX_PREFIX))
        {
            keys.push(("appendix".into(), src.into()));
        }
    }
    let in_group = |r: &ComparisonRow, table: &str| match table {
        "all" => !r.table.starts_with(APPENDIX_PREFIX),
        "appendix" => r.table.starts_with(APPENDIX_PREFIX),
        t => r.table == t,
    };
    let mut out = Vec::new();
    for (table, source) in keys {
        for rule in RULES {
            let v = rows
                .iter()
                .filter(|r| r.source == source && in_group(r, &table))
                .map(|r| verdict(r, rule));
            out.push(TableCounts {
                table: table.clone(),
                source: source.clone(),
                rule: rule.into(),
                counts: Counts::of(v),
            });
        }
    }
    out
}

/// Control counts of `rows` (one pairing) per source (and `all`) × rule.
pub fn control_counts(pairing: &str, matched: bool, rows: &[ComparisonRow]) -> Vec<ControlCounts> {
    let mut out = Vec::new();
    for source in ["paper", "notebook", "all"] {
        for rule in RULES {
            let v = rows
                .iter()
                .filter(|r| source == "all" || r.source == source)
                .map(|r| verdict(r, rule));
            out.push(ControlCounts {
                pairing: pairing.into(),
                matched,
                source: source.into(),
                rule: rule.into(),
                counts: Counts::of(v),
            });
        }
    }
    out
}

/// The paper numbers of model `m`.
fn of_model(nums: &[PaperNumber], m: &str) -> Vec<PaperNumber> {
    nums.iter()
        .filter(|p| paper_model(p) == m)
        .copied()
        .collect()
}

/// The negative control and the faithful pairs on the same numbers, from the lab's analysed
/// models. The size control pairs the paper's size-8 numbers with the lab's size 256 where
/// it has run (`lstm256`, `ctrnn-reservoir256` among the analysed bisection models), else
/// with its size 125 as a stand-in.
pub fn negative_control(
    fi: &[FiModel],
    bis: &[BisectionModel],
    mt: &[MtCell],
) -> Vec<ControlCounts> {
    let mut all = numbers();
    all.extend(appendix_numbers());
    all.extend(appendix_fi_numbers());
    all.extend(multitimer_2_10_numbers());
    let has = |m: &str| bis.iter().any(|b| b.model == m) || fi.iter().any(|f| f.model == m);
    let lstm_big: &'static str = if has("lstm256") { "lstm256" } else { "lstm125" };
    let ctrnn_big: &'static str = if has("ctrnn-reservoir256") {
        "ctrnn-reservoir256"
    } else {
        "ctrnn-reservoir125"
    };
    // (paper model, lab model): faithful when the lab model is the paper model's counterpart
    // (`lab_model`), else a deliberate mismatch.
    let pairs: [(&str, &'static str); 13] = [
        ("LSTM125", "lstm125"),
        ("LSTM125", "ctrnn-reservoir125"),
        ("LSTM125", "ctrnn125"),
        ("CTRNN125", "ctrnn-reservoir125"),
        ("CTRNN125", "lstm125"),
        ("LSTM256", "lstm256"),
        ("LSTM256", "ctrnn-reservoir256"),
        ("CTRNN256", "ctrnn-reservoir256"),
        ("CTRNN256", "lstm256"),
        ("LSTM8", lstm_big),
        ("CTRNN8", ctrnn_big),
        ("LSTM8", "lstm8"),
        ("CTRNN8", "ctrnn-reservoir8"),
    ];
    let mut out = Vec::new();
    for (paper, lab) in pairs {
        let trained = if lab == "ctrnn125" {
            " (trained CTRNN)"
        } else {
            ""
        };
        let name = format!("paper {paper} vs lab {lab}{trained}");
        let rows = compare_numbers(&of_model(&all, paper), &|_| Some(lab), fi, bis, mt);
        out.extend(control_counts(&name, lab_model(paper) == Some(lab), &rows));
    }
    out
}

/// `agreement.json` of a comparison and the lab's analysed models.
pub fn agreement(
    rows: &[ComparisonRow],
    fi: &[FiModel],
    bis: &[BisectionModel],
    mt: &[MtCell],
) -> Agreement {
    let mut rules = BTreeMap::new();
    rules.insert(
        "old".into(),
        "paper value inside the lab's 95% interval: lab ± t(0.975, n−1)·sd·√(1/n + 1/4) for \
         means, the χ² 95% interval of the lab's SD for SDs"
            .into(),
    );
    rules.insert(
        "z".into(),
        format!(
            "|z| ≤ {Z_AGREE}, z = (lab − paper)/√(lab_sd²/n + paper_sd²/n_paper); the paper's \
             term only where it prints an SD (WF, DL: 4 runs), else the lab's standard error \
             alone; SD rows: z = ln(lab_sd/paper_sd)/√(1/(2(n−1)) + 1/(2(n_paper−1))); counts must be equal"
        ),
    );
    Agreement {
        rules,
        counts: table_counts(rows),
        negative_control: negative_control(fi, bis, mt),
        notes: vec![
            "rate = yes / (yes + no); `no` includes a number on one side and NaN on the other"
                .into(),
            "the size control pairs the paper's size 8 with the lab's size 256 where it has \
             run, else with its size 125 (named in the pairing)"
                .into(),
            "the appendix prints NaN for every size-8 WF and DL (tab:wf_supp, tab:dl_supp), so \
             the size control's finite numbers are the FI notebook's size-8 FOC means and R² \
             (source notebook); its 'paper' rows can only be `no` (lab finite) or `both-nan`"
                .into(),
        ],
    }
}

fn rate(c: &Counts) -> String {
    if c.rate.is_finite() {
        format!("{:.0}%", 100.0 * c.rate)
    } else {
        "–".into()
    }
}

/// The agreement section of `tables.md`: every table × source under both rules, then the
/// negative control.
pub fn agreement_markdown(m: &mut String, a: &Agreement) {
    let agree = |c: &Counts| format!("{} of {} ({})", c.yes, c.yes + c.no, rate(c));
    use std::fmt::Write as _;
    let _ = writeln!(
        m,
        "\n## Agreement with the paper under both rules\n\nOld rule: {}. Discriminating rule: \
         {}. Cells: yes / (yes + no), then n/a and both-NaN rows.\n",
        a.rules.get("old").map_or("", |s| s.as_str()),
        a.rules.get("z").map_or("", |s| s.as_str())
    );
    let mut table = Table::new([
        "table",
        "source",
        "rows",
        "old rule: agree",
        "z rule: agree",
        "n/a",
        "both NaN",
    ])
    .right(2..7);
    let find = |t: &str, s: &str, r: &str| {
        a.counts
            .iter()
            .find(|c| c.table == t && c.source == s && c.rule == r)
    };
    for c in a.counts.iter().filter(|c| c.rule == "old") {
        let Some(z) = find(&c.table, &c.source, "z") else {
            continue;
        };
        table.row([
            c.table.clone(),
            c.source.clone(),
            c.counts.rows.to_string(),
            agree(&c.counts),
            agree(&z.counts),
            format!("{} / {}", c.counts.na, z.counts.na),
            c.counts.both_nan.to_string(),
        ]);
    }
    m.push_str(&table.render());
    let _ = writeln!(
        m,
        "\nNegative control (mismatched pairs: agreement here is agreement by chance) beside \
         the faithful pairs on the same numbers:\n"
    );
    let mut table = Table::new([
        "pairing",
        "matched",
        "source",
        "rows",
        "old rule: agree",
        "z rule: agree",
    ])
    .right(3..6);
    // Pairings without a number in this study (e.g. a study of one task) are left out.
    for c in a
        .negative_control
        .iter()
        .filter(|c| c.rule == "old" && c.counts.rows > 0)
    {
        let Some(z) = a
            .negative_control
            .iter()
            .find(|x| x.pairing == c.pairing && x.source == c.source && x.rule == "z")
        else {
            continue;
        };
        table.row([
            c.pairing.clone(),
            if c.matched { "yes" } else { "no" }.to_string(),
            c.source.clone(),
            c.counts.rows.to_string(),
            agree(&c.counts),
            agree(&z.counts),
        ]);
    }
    m.push_str(&table.render());
    for n in &a.notes {
        let _ = writeln!(m, "\n* {n}");
    }
}
