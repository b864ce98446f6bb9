#!/usr/bin/env bash
# Fuzz one C++ harness (bridge_plugin/fuzz) for a fixed time and write its figures.
usage() {
  cat <<'USAGE'
usage: scripts/fuzz_campaign.sh [options] HARNESS SECONDS

Builds the libFuzzer harnesses (clang, ASan + UBSan) into build/cpp_fuzz, then fuzzes
fuzz_HARNESS for SECONDS, niced, seeded with protocol/vectors and the harness's regression
inputs (bridge_plugin/fuzz/regressions/HARNESS). Writes its figures as JSON and prints them.
HARNESS: request, reply, structure, utf8, params, keys, or all (each in turn, SECONDS each).

  --corpus DIR    where the corpus grows (default: build/fuzz_corpus/HARNESS; kept between
                  campaigns, so a second one starts where the first stopped)
  --crashes DIR   where crashing inputs go (default: build/fuzz_crashes/HARNESS)
  --stats FILE    the figures, JSON (default: build/fuzz_stats/HARNESS.json)
  --max-len N     the longest input tried, bytes (default 16384)
  --build-only    build fuzz_HARNESS (build/cpp_fuzz/fuzz_HARNESS) and stop; SECONDS unused
  -h, --help      this text

Exit status: 0 no crash, 1 a crash (its input is in the crashes folder: replay it with
build/cpp_fuzz/fuzz_HARNESS FILE, then keep it under bridge_plugin/fuzz/regressions/HARNESS),
2 bad usage, 3 no clang/libFuzzer or build failure, 130/143 interrupted.

Example: scripts/fuzz_campaign.sh reply 600
USAGE
}
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
HARNESSES=(request reply structure utf8 params keys)
BUILD="$ROOT/build/cpp_fuzz"
corpus="" crashes="" stats="" max_len=16384 build_only=0
die_usage() { echo "fuzz_campaign: $1 (see --help)" >&2; exit 2; }
positional=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --build-only) build_only=1; shift ;;
    --corpus|--crashes|--stats|--max-len)
      [ $# -ge 2 ] || die_usage "option $1 needs a value"
      case "$1" in
        --corpus) corpus="$2" ;; --crashes) crashes="$2" ;; --stats) stats="$2" ;;
        --max-len) max_len="$2" ;;
      esac
      shift 2 ;;
    -*) die_usage "unknown option $1" ;;
    *) positional+=("$1"); shift ;;
  esac
done
[ "$build_only" = 1 ] && [ ${#positional[@]} -eq 1 ] && positional+=(1)
[ ${#positional[@]} -eq 2 ] || die_usage "expected HARNESS SECONDS"
harness="${positional[0]}" seconds="${positional[1]}"
[[ "$seconds" =~ ^[1-9][0-9]*$ ]] || die_usage "SECONDS must be a positive integer, got '$seconds'"
[[ "$max_len" =~ ^[1-9][0-9]*$ ]] || die_usage "--max-len must be a positive integer"
# Each step (the build, the fuzzer, one harness of `all`) runs as a job of its own process
# group, so that a signal here ends it whole: the fuzzer is asked with SIGINT (it then prints
# its figures), the build with SIGTERM.
set -m
child="" signal=""
on_signal() {
  signal=$1
  if [ -n "$child" ]; then kill "-$2" -- "-$child" 2>/dev/null || true; fi
}
trap 'on_signal 130 INT' INT
trap 'on_signal 143 TERM' TERM
# Runs "$@" as that job and waits for its end, through any signal that arrives meanwhile.
step() {
  "$@" &
  child=$!
  local rc=0
  wait "$child" || rc=$?
  while kill -0 "$child" 2>/dev/null; do wait "$child" || rc=$?; done
  child=""
  return "$rc"
}

if [ "$harness" = all ]; then
  [ -z "$corpus$crashes$stats" ] || die_usage "--corpus, --crashes and --stats name one harness's"
  status=0
  for one in "${HARNESSES[@]}"; do
    args=(--max-len "$max_len")
    [ "$build_only" = 1 ] && args+=(--build-only)
    step "$0" "${args[@]}" "$one" "$seconds" || status=$?
    [ -z "$signal" ] || exit "$signal"
    [ "$status" -ge 2 ] && exit "$status"
  done
  exit "$status"
fi
[[ " ${HARNESSES[*]} " == *" $harness "* ]] \
  || die_usage "unknown HARNESS '$harness' (one of: ${HARNESSES[*]}, all)"
corpus="${corpus:-$ROOT/build/fuzz_corpus/$harness}"
crashes="${crashes:-$ROOT/build/fuzz_crashes/$harness}"
stats="${stats:-$ROOT/build/fuzz_stats/$harness.json}"

cxx="${NAV2_PYIF_FUZZ_CXX:-}"
if [ -z "$cxx" ]; then
  for candidate in clang++-14 clang++; do
    command -v "$candidate" >/dev/null && { cxx="$candidate"; break; }
  done
fi
if [ -z "$cxx" ]; then
  echo "fuzz_campaign: no clang++: install Debian's clang-14 and libclang-rt-14-dev" \
    "(scripts/system_deps.sh does, from scripts/test.sh), or set NAV2_PYIF_FUZZ_CXX" >&2
  exit 3
fi
mkdir -p "$BUILD" "$corpus" "$crashes" "$(dirname "$stats")"
log="$(mktemp)"
finish() {  # on any exit: the step running and the log go with us
  if [ -n "$child" ]; then kill -TERM -- "-$child" 2>/dev/null || true; fi
  rm -f "$log" "$log.start"
}
trap finish EXIT
build() {
  CXX="$cxx" cmake -S "$ROOT/bridge_plugin" -B "$BUILD" -DNAV2_PYIF_CODEC_ONLY=ON \
    -DNAV2_PYIF_FUZZ=ON -DBUILD_TESTING=OFF -DNAV2_PYIF_WARNINGS_AS_ERRORS=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DNAV2_PYIF_VECTORS_DIR=$ROOT/protocol/vectors" \
    >"$log" 2>&1 && cmake --build "$BUILD" -j2 --target "fuzz_$harness" >>"$log" 2>&1
}
# One build at a time in the shared folder (two campaigns, a campaign and the suite).
exec 9>"$BUILD/.fuzz_build.lock"
flock 9
step build || {
  [ -z "$signal" ] || exit "$signal"
  tail -40 "$log" >&2
  echo "fuzz_campaign: building fuzz_$harness with $cxx failed (libFuzzer is Debian's" \
    "libclang-rt-14-dev)" >&2
  exit 3
}
flock -u 9

[ "$build_only" = 1 ] && { echo "$BUILD/fuzz_$harness"; exit 0; }

seeds=("$ROOT/protocol/vectors")
for dir in "$ROOT/bridge_plugin/fuzz/regressions/$harness" "$BUILD/fuzz_seeds/$harness"; do
  [ -d "$dir" ] && seeds+=("$dir")
done
started="$(date +%s)"
touch "$log.start"  # what is newer than this in the crashes folder, this run found
# A decoder given n bytes has no business allocating 256 MiB: libFuzzer reports it as a crash.
# The first folder is the one the corpus grows in.
fuzz() {
  exec nice -n 10 "$BUILD/fuzz_$harness" -max_total_time="$seconds" -max_len="$max_len" \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=256 -print_final_stats=1 \
    -artifact_prefix="$crashes/" "$corpus" "${seeds[@]}" >"$log" 2>&1
}
# The fuzzer is asked to stop with SIGINT, which makes it print its figures first.
trap 'on_signal 143 INT' TERM
rc=0
step fuzz || rc=$?
if [ -n "$signal" ]; then result=interrupted; elif [ "$rc" = 0 ]; then result=clean; else
  result=crash; fi
elapsed=$(( $(date +%s) - started ))

stat() { local v; v="$(sed -n "s/^stat::$1: *//p" "$log" | tail -1)"; echo "${v:-0}"; }
coverage="$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -1 || true)"
field() { local v; v="$(sed -n "s/.* $1: \([0-9]*\).*/\1/p" <<<"$coverage")"; echo "${v:-0}"; }
mapfile -t found < <(find "$crashes" -type f -newer "$log.start" | sort)
rm -f "$log.start"
crash_list="$(for f in "${found[@]}"; do printf '"%s"\n' "$f"; done | paste -sd, -)"
executions="$(stat number_of_executed_units)" per_sec="$(stat average_exec_per_sec)"
cov="$(field cov)" ft="$(field ft)"
cat >"$stats" <<JSON
{
  "harness": "$harness",
  "seconds": $elapsed,
  "result": "$result",
  "executions": $executions,
  "exec_per_sec": $per_sec,
  "cov": $cov,
  "ft": $ft,
  "corpus_units": $(find "$corpus" -type f | wc -l),
  "new_units": $(stat new_units_added),
  "peak_rss_mb": $(stat peak_rss_mb),
  "crashes": ${#found[@]},
  "crash_files": [$crash_list]
}
JSON
printf '%-10s %-11s %6ss %12s execs %7s/s  cov %6s  ft %7s  crashes %s\n' "$harness" \
  "$result" "$elapsed" "$executions" "$per_sec" "$cov" "$ft" "${#found[@]}"
if [ "$result" = crash ]; then
  grep -E 'ERROR|SUMMARY|property broken|runtime error' "$log" | head -20 >&2 || true
  tail -30 "$log" >&2
fi
case "$result" in
  clean) exit 0 ;;
  interrupted) exit "$signal" ;;
  *) exit 1 ;;
esac
