//! Corrupt input files are errors naming the problem, never panics: truncated and garbage
//! NPZ archives, activity datasets, evaluation records, sweep files.

use chronocooked_present::export::npz::{NpyArray, NpyData, npz_bytes, read_npz};

fn arrays() -> Vec<NpyArray> {
    vec![
        NpyArray {
            name: "activity".into(),
            shape: vec![2, 3],
            data: NpyData::F32(vec![0.5, 1.0, -2.0, 3.25, f32::NAN, 6.0]),
        },
        NpyArray {
            name: "td".into(),
            shape: vec![2],
            data: NpyData::I64(vec![4, 12]),
        },
        NpyArray {
            name: "success".into(),
            shape: vec![2],
            data: NpyData::U8(vec![1, 0]),
        },
        NpyArray {
            name: "fit".into(),
            shape: vec![1, 1],
            data: NpyData::F64(vec![0.125]),
        },
    ]
}

#[test]
fn npz_round_trips_every_dtype() {
    let bytes = npz_bytes(&arrays()).unwrap();
    let back = read_npz(&bytes).unwrap();
    assert_eq!(back.len(), 4);
    for (a, b) in arrays().iter().zip(&back) {
        assert_eq!((a.name.as_str(), &a.shape), (b.name.as_str(), &b.shape));
        match (&a.data, &b.data) {
            (NpyData::F32(x), NpyData::F32(y)) => {
                assert!(
                    x.iter()
                        .zip(y)
                        .all(|(p, q)| p == q || (p.is_nan() && q.is_nan()))
                )
            }
            (x, y) => assert_eq!(x, y),
        }
    }
    // The `.npy` entries are what numpy writes: magic, version, the header dict.
    let at = bytes.windows(6).position(|w| w == b"\x93NUMPY").unwrap();
    let header = String::from_utf8_lossy(&bytes[at..at + 128]);
    assert!(header.contains("'descr': '<f4'"), "{header}");
    assert!(header.contains("'shape': (2, 3)"), "{header}");
}

#[test]
fn truncated_and_garbage_npz_are_errors() {
    let bytes = npz_bytes(&arrays()).unwrap();
    for cut in [0, 10, 100, bytes.len() / 2, bytes.len() - 1] {
        assert!(read_npz(&bytes[..cut]).is_err(), "cut at {cut}");
    }
    assert!(read_npz(b"this is not a zip archive at all").is_err());
    // Flip bytes inside the first array's data: a CRC or header error, not a panic.
    let mut bad = bytes.clone();
    let at = bad.windows(6).position(|w| w == b"\x93NUMPY").unwrap();
    for b in &mut bad[at..at + 40] {
        *b ^= 0x5a;
    }
    assert!(read_npz(&bad).is_err());
}

#[test]
fn a_shape_that_does_not_fit_its_data_is_an_error() {
    let mut a = arrays();
    a[0].shape = vec![4, 4];
    let e = npz_bytes(&a).unwrap_err();
    assert!(e.contains("activity") && e.contains("16"), "{e}");
}

#[test]
fn corrupt_eval_records_name_the_file_and_line() {
    use chronocooked_env::integrity::write_recorded;
    let dir = tempfile::tempdir().unwrap();
    // Without its SHA-256 record a records file is not read at all.
    std::fs::write(dir.path().join("records.jsonl"), "{\"condition\": 3}\n").unwrap();
    let e = chronocooked_analysis::evaluation::protocol::read_records(dir.path()).unwrap_err();
    assert!(
        e.contains("records.jsonl") && e.contains("SHA256SUMS"),
        "{e}"
    );
    // Recorded but malformed: the error names the file and the line.
    write_recorded(&dir.path().join("records.jsonl"), b"{\"condition\": 3}\n").unwrap();
    let e = chronocooked_analysis::evaluation::protocol::read_records(dir.path()).unwrap_err();
    assert!(e.contains("records.jsonl") && e.contains("line 1"), "{e}");
    let e = chronocooked_present::eval_folder::read_eval_info(dir.path()).unwrap_err();
    assert!(e.contains("eval.json"), "{e}");
    write_recorded(&dir.path().join("eval.json"), b"{\"model\": ").unwrap();
    let e = chronocooked_present::eval_folder::read_eval_info(dir.path()).unwrap_err();
    assert!(e.contains("eval.json"), "{e}");
}

#[test]
fn corrupt_sweep_files_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (i, text) in [
        "models = [",
        "name = 3\n",
        "\u{0}\u{1}garbage",
        "tasks = [\"NoSuchTask-v9\"]\n",
    ]
    .iter()
    .enumerate()
    {
        let path = dir.path().join(format!("s{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let e = chronocooked_pipeline::sweep::SweepFile::load(&path);
        assert!(e.is_err(), "{text:?} was accepted");
    }
}

/// A sweep that would name one job folder twice (a repeated seed, task, model or size, or
/// two entries for one model) or whose name is not a plain folder name is refused, naming
/// the field and the value.
#[test]
fn sweep_files_that_name_a_job_twice_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let head = "tasks = [\"FixedInterval-v0\"]\n";
    for (i, (text, field, value)) in [
        ("models = [\"ddm\"]\nseeds = [1, 2, 1]\n", "seeds", "1"),
        (
            "models = [\"ddm\", \"sbf\", \"ddm\"]\nseeds = [1]\n",
            "models",
            "ddm",
        ),
        (
            "models = [\"lstm\"]\nsizes = [8, 8]\nseeds = [1]\n",
            "sizes",
            "8",
        ),
        (
            "models = [\"lstm\", \"lstm125\"]\nsizes = [125]\nseeds = [1]\n",
            "models",
            "lstm125",
        ),
        (
            "name = \"../elsewhere\"\nmodels = [\"ddm\"]\nseeds = [1]\n",
            "name",
            "../elsewhere",
        ),
    ]
    .iter()
    .enumerate()
    {
        let path = dir.path().join(format!("s{i}.toml"));
        std::fs::write(&path, format!("{head}{text}")).unwrap();
        let e = chronocooked_pipeline::sweep::SweepFile::load(&path)
            .and_then(|s| s.jobs().map(|_| s))
            .err()
            .unwrap_or_else(|| panic!("{text:?} was accepted"))
            .to_string();
        assert!(e.contains(field) && e.contains(value), "{text:?}: {e}");
    }
    std::fs::write(
        dir.path().join("ok.toml"),
        format!("{head}models = [\"ddm\", \"lstm\"]\nsizes = [8, 125]\nseeds = [1, 2]\n"),
    )
    .unwrap();
    let ok = chronocooked_pipeline::sweep::SweepFile::load(&dir.path().join("ok.toml")).unwrap();
    assert_eq!(ok.jobs().unwrap().len(), 6);
}
