#!/usr/bin/env bash
# Runs every libFuzzer target of a CONTACTSIM_FUZZ build from the seed
# corpus (a valid message of every op), with the given libFuzzer flags
# (e.g. -runs=20000 in CI, -max_total_time=300 for `make fuzz`), and
# prints the executions per target. A crash leaves its input as
# BUILD/fuzz/crash-* and fails the run.
#   scripts/fuzz.sh BUILD_DIR [libFuzzer flags...]
set -euo pipefail
build=$(cd "$1" && pwd); shift
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$build/bin
work=$build/fuzz
rm -rf "$work/seeds"
mkdir -p "$work"
"$bin/contactsim-fuzz-seeds" "$work/seeds" >/dev/null
export ASAN_OPTIONS=${ASAN_OPTIONS:-allocator_may_return_null=1:detect_leaks=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
status=0
for target in "$bin"/fuzz_*; do
  name=$(basename "$target")
  # a decoder target fuzz_decode_<channel> starts from that channel's seeds
  case $name in
    fuzz_server_apply) seeds=apply ;;
    fuzz_decode_*) seeds=$(echo "${name#fuzz_decode_}" | tr '[:lower:]' '[:upper:]') ;;
    *) seeds= ;;
  esac
  if [ -z "$seeds" ] || [ ! -d "$work/seeds/$seeds" ]; then
    echo "fuzz: no seeds for $name" >&2; exit 1
  fi
  corpus=$work/corpus-$name
  mkdir -p "$corpus"
  # inputs that once failed run first, every time (tests/fuzz/regressions)
  regressions=$repo/tests/fuzz/regressions/$seeds
  [ -d "$regressions" ] || regressions=

  log=$work/$name.log
  if (cd "$work" && "$target" -artifact_prefix="$work/" -max_len=4096 -print_final_stats=1 "$@" \
        "$corpus" "$work/seeds/$seeds" $regressions >"$log" 2>&1); then
    runs=$(grep -a -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
    echo "fuzz: $name ok, ${runs:-?} executions, corpus $(ls "$corpus" | wc -l) inputs"
  else
    echo "fuzz: $name FAILED (log: $log)"; tail -40 "$log"
    status=1
  fi
done
exit $status
