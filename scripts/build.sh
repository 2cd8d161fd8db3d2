#!/usr/bin/env bash
# Sourced by scripts/sweep and scripts/test: builds target/release/sweep. The workspace turns on,
# in its normal dependencies, the features that the test build's dev-dependencies turn on (see
# Cargo.toml), so `cargo build` and `cargo test --release` share one build of the dependencies.
# Says what it does when there is something to compile; silent when the binary is up to date.
root="${root:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
if [ ! -x "$root/target/release/sweep" ]; then
  echo "sweep: building the release binary (the first time takes a few minutes)..." >&2
fi
# cargo's own progress goes to stderr; its closing 'Finished' line is dropped.
if ! cargo build --release --bin sweep --manifest-path "$root/Cargo.toml" \
  2> >(grep --line-buffered -v -E '^ *Finished ' >&2); then
  echo "sweep: the build failed (cargo's messages above)" >&2
  exit 1
fi
