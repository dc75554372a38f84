//! The fingerprint's compiled-in mechanism signatures are the committed study's.

use chronocooked_analysis::fingerprint::{reference_signatures, signatures_from_csv};
use chronocooked_analysis::mechanisms::MECHANISMS;

#[test]
fn the_compiled_in_signatures_equal_the_committed_study() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let text =
        std::fs::read_to_string(root.join("results/mechanisms-reference/signatures.csv")).unwrap();
    let committed: Vec<_> = signatures_from_csv(&text)
        .unwrap()
        .into_iter()
        .filter(|s| MECHANISMS.contains(&s.model.as_str()))
        .collect();
    assert_eq!(committed.len(), 40);
    assert_eq!(reference_signatures(), committed);
}
