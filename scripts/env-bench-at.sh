#!/usr/bin/env bash
# Env stepping at several commits, for bisecting a speed change of the kitchen: for each
# commit, a worktree gets a tiny example that calls `chronocooked_env::bench::run` (FI, one
# env and 256 envs, codes observation, 2 s each), built for the env crate alone (≈ 25 s
# after the first), then every build runs ROUNDS times in turn. Prints M steps/s per
# commit and round.
#
#   bash scripts/env-bench-at.sh WORK_DIR ROUNDS COMMIT [COMMIT ...]
#   e.g. bash scripts/env-bench-at.sh /tmp/envbench 2 1cf7d35 509e8dd 4b068b0 HEAD
set -euo pipefail
work=$(realpath -m "$1") rounds=$2
shift 2
mkdir -p "$work/bin"
src="$work/src"
[[ -d "$src" ]] || git worktree add --detach "$src" HEAD > /dev/null
for c in "$@"; do
  sha=$(git rev-parse --short "$c")
  (
    cd "$src"
    git checkout -q --detach "$sha"
    mkdir -p env/examples
    cat > env/examples/envbench.rs <<'RS'
fn main() {
    let rows = chronocooked_env::bench::run("FixedInterval-v0", &[], 256, 2.0).unwrap();
    for r in rows.iter().filter(|r| r.encoding == "codes") {
        print!("{} {:.1}  ", r.mode, r.steps_per_sec / 1e6);
    }
    println!();
}
RS
    CARGO_TARGET_DIR="$work/target" cargo build -q --release --locked -p chronocooked-env --example envbench
    rm -rf env/examples
  )
  cp "$work/target/release/examples/envbench" "$work/bin/$sha"
done
for ((r = 1; r <= rounds; r++)); do
  for c in "$@"; do
    sha=$(git rev-parse --short "$c")
    echo "$sha round $r: $("$work/bin/$sha")"
  done
done
