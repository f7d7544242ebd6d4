#!/usr/bin/env bash
# Fuzzes car's loaders with libFuzzer (issue 28, docs/RELIABILITY.md): builds test/fuzz/fuzz_*.cpp with clang in
# .ws-asan/ (tools/sanitize.sh's ASan+UBSan build; -DCAR_FUZZ=ON adds libFuzzer's coverage hooks), seeds each target from test/data/ and
# runs them one after the other on one core (nice 10; FUZZ_NICE=19 to take only idle CPU; FUZZ_FORK=N runs N
# children of libFuzzer's -fork at once, N cores, for one target; the CPU seconds are those of all N).
# Each fuzzing run appends its summary (target, commit, CPU s, inputs, cov/ft, corpus, findings) to
# test/fuzz/runs.tsv (committed; FUZZ_RUNS=FILE elsewhere; --smoke writes test/fuzz/out/runs.tsv, git-ignored).
# Usage: tools/fuzz.sh [--smoke] [--cov] [SECONDS] [TARGET...]
#   --smoke    60 s per target (CI's smoke); SECONDS per target otherwise (default 600)
#   --no-build run what .ws-asan/ holds
#   --regressions  fuzz nothing: run every input that once broke the rule (test/fuzz/regressions/TARGET/) through its
#              target once, deterministic (CI's gate); exits 1 when one breaks it again
#   --recheck  only re-measure the timeouts already in test/fuzz/out/ (see recheck below), fuzz nothing
#   --save     afterwards, minimise each corpus (-merge=1) into test/fuzz/corpus/TARGET/ (committed)
#   --cov      afterwards, the lines of src/model and src/description the corpora execute (llvm-cov)
# The rule (test/fuzz/fuzz_common.hpp): an input loads or is refused with FILE[:LINE]: ELEMENT: REASON; never a
# crash, a hang over 1 s, over 2 GB, or a non-finite state after the steps. Exits 1 when a target found an input
# that breaks it (saved under test/fuzz/out/TARGET/); exits 2 when something could not run: clang, the build, a
# target that executed nothing (no binary, zero inputs; its CPU seconds are not counted) or a regression target
# without its binary. .ci/run lets a finding of the smoke pass (1) and fails on 2.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT/car"
# shellcheck source=tools/sanitizers/workspace.sh
source "$ROOT/tools/sanitizers/workspace.sh"
ensure_clang || { echo "sanitizers: could not install clang 14"; exit 2; }
ALL=(urdf sdf_world sdf_model spawn ros_control flatten)
secs=600 cov=0 build=1 recheck_only=0 save=0 regressions_only=0 targets=()
for a in "$@"; do
  case "$a" in
    --smoke) secs=60 ;;
    --cov) cov=1 ;;
    --no-build) build=0 ;;
    --recheck) recheck_only=1 ;;
    --regressions) regressions_only=1 ;;
    --save) save=1 ;;
    [0-9]*) secs="$a" ;;
    *) targets+=("$a") ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=("${ALL[@]}")
WS="$ROOT/.ws-asan"   # the ASan+UBSan build of tools/sanitize.sh, with -DCAR_FUZZ=ON
BIN="$WS/devel/lib/car"
JOBS="${JOBS:-1}"
# [s] wall time per input before libFuzzer calls it a hang: the rule's 1 s; FUZZ_TIMEOUT=3 on a machine so busy
# that a process gets a third of a core (each timeout is re-measured in CPU time below either way)
TIMEOUT="${FUZZ_TIMEOUT:-1}"
NICE="${FUZZ_NICE:-10}"
# libFuzzer's -fork jobs: children fuzzing the one target at once, sharing its corpus
FORK="${FUZZ_FORK:-1}"
# the table of runs: one row per target and run (test/fuzz/RUNS.md explains the columns)
if [ "$secs" -eq 60 ] && [ -z "${FUZZ_RUNS:-}" ]; then RUNS="$ROOT/car/test/fuzz/out/runs.tsv"; else RUNS="${FUZZ_RUNS:-$ROOT/car/test/fuzz/runs.tsv}"; fi
RUNS_HEADER="start_utc\ttarget\tcommit\tnice\twall_s\tcpu_s\tinputs\tcov\tft\tcorpus_files\tfindings\tnote"
record_run() {  # record_run TARGET START WALL CPU INPUTS LOG CORPUS FINDINGS NOTE
  local last cov ft files commit
  # libFuzzer's last status line: `#N: cov: C ft: F corp: K ...` (-fork) or `#N ... cov: C ft: F corp: K/...`
  last=$(grep -E '^#[0-9]+.*cov: [0-9]+ ft: [0-9]+' "$6" | tail -n 1)
  cov=$(echo "$last" | sed -nE 's/.*cov: ([0-9]+).*/\1/p'); ft=$(echo "$last" | sed -nE 's/.* ft: ([0-9]+).*/\1/p')
  files=$(find "$7" -maxdepth 1 -type f | wc -l)
  # the commit fuzzed (HEAD when the run began), marked -dirty when car/ differs from it (the build is of the work tree)
  commit="${commit0:-$(git -C "$ROOT" rev-parse --short=12 HEAD)}"
  [ -z "$(git -C "$ROOT" status --porcelain -- car/src car/include car/test/fuzz/*.cpp car/test/fuzz/*.hpp)" ] || commit+="-dirty"
  mkdir -p "$(dirname "$RUNS")"
  [ -s "$RUNS" ] || printf "$RUNS_HEADER\n" > "$RUNS"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$2" "$1" "$commit" "$NICE" "$3" "$4" "${5:-0}" \
    "${cov:--}" "${ft:--}" "$files" "$8" "$9" >> "$RUNS"
  echo "fuzz: $1: row added to $RUNS"
}

# ---- build ---------------------------------------------------------------------------------------------------
make_workspace "$WS"
set +u; source /opt/ros/noetic/setup.bash 2>/dev/null; set -u
fuzz_targets=(); for t in "${ALL[@]}"; do fuzz_targets+=("fuzz_$t"); done
if [ $build -eq 0 ]; then
  :
elif [ ! -f "$WS/build/Makefile" ]; then
  (cd "$WS" && CC=clang-14 CXX=clang++-14 catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCATKIN_ENABLE_TESTING=ON -DCAR_SANITIZE=address,undefined -DCAR_FUZZ=ON -j"$JOBS" "${fuzz_targets[@]}" > build.log 2>&1) || { tail -n 40 "$WS/build.log"; exit 2; }
else
  make -C "$WS/build" -j"$JOBS" "${fuzz_targets[@]}" > "$WS/build.log" 2>&1 || { tail -n 40 "$WS/build.log"; exit 2; }
fi

# ---- the regressions alone: each input once, in a fresh process per target -----------------------------------------
if [ $regressions_only -eq 1 ]; then
  broken=0
  for t in "${targets[@]}"; do
    inputs=(test/fuzz/regressions/"$t"/*)
    [ -e "${inputs[0]}" ] || continue
    [ -x "$BIN/fuzz_$t" ] || { echo "fuzz: $t: FAILED: no binary $BIN/fuzz_$t: its regressions did not run"; broken=2; continue; }
    if LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        "$BIN/fuzz_$t" -timeout=30 -rss_limit_mb=2048 "${inputs[@]}" > "$WS/regressions-$t.log" 2>&1; then
      echo "fuzz: $t: ${#inputs[@]} regression input(s) keep the rule"
    else
      grep -m3 -B2 -A12 'ERROR\|RULE BROKEN\|runtime error' "$WS/regressions-$t.log"
      echo "fuzz: $t: FAILED: a regression input breaks the rule again ($WS/regressions-$t.log)"
      [ $broken = 2 ] || broken=1
    fi
  done
  exit $broken
fi

# ---- seeds: test/data's robots, worlds and models, the hostile corpus (test/data/bad) -------------------------
seeds() {  # seeds TARGET DIR
  local t="$1" d="$2" f
  rm -rf "$d"; mkdir -p "$d"
  case "$t" in
    urdf) find test/data urdf -name '*.urdf' -size -256k -exec cp -t "$d" --backup=numbered {} + ;;
    sdf_world|flatten) find test/data worlds -name '*.world' -size -256k -exec cp -t "$d" --backup=numbered {} + ;;
    sdf_model) find test/data models -name '*.sdf' -size -256k -exec cp -t "$d" --backup=numbered {} + ;;
    spawn)
      # the request header (name|namespace|frame|pose, then a set_model_state) over each robot
      for f in $(find test/data -name '*.urdf' -size -64k | head -n 40) $(find test/data models -name '*.sdf' -size -64k); do
        { printf 'robot|/ns|world|0 0 0.5 0 0 0 1\n1 2 0.5 0 0 0.38 0.92 0.1 0 0 0 0 0.2\n'; cat "$f"; } \
          > "$d/$(echo "$f" | tr / _)"
      done ;;
    ros_control) cp test/fuzz/seeds/ros_control/* "$d/" ;;
  esac
}

# libFuzzer's -timeout is wall time, and on a busy machine a timeout may be the load, not the input. Each one is
# run again alone and measured in CPU time (user + sys, less the process's start): its loading (CAR_FUZZ_NO_STEP=1)
# must take under the rule's 1 s, and the whole input with its steps under 10 s (the instrumented build is 3-5
# times slower than a release build; fuzz_common.hpp caps the steps). One that passes both is kept in
# out/TARGET/load/ and not counted.
cpu_of() {  # cpu_of [ENV=V] ARGS...: CPU seconds of one run of the target
  { time env LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS=detect_leaks=0 "$@" > /dev/null 2>&1; } 2>&1 |
    awk '{print $1 + $2}'
}
recheck() {  # recheck TARGET
  local t="$1" out="$ROOT/car/test/fuzz/out/$1" f load_s all_s base_s empty
  TIMEFORMAT='%U %S'
  compgen -G "$out/timeout-*" > /dev/null || return 0
  # the process's own start (ASan, libFuzzer's tables, LLVMFuzzerInitialize's warm-up): an empty input's CPU time
  empty="$(mktemp)"
  base_s=$(cpu_of CAR_FUZZ_NO_STEP=1 "$BIN/fuzz_$t" -timeout=600 -runs=1 "$empty")
  rm -f "$empty"
  for f in "$out"/timeout-*; do
    [ -e "$f" ] || continue
    load_s=$(cpu_of CAR_FUZZ_NO_STEP=1 "$BIN/fuzz_$t" -timeout=600 -runs=1 "$f")
    all_s=$(cpu_of "$BIN/fuzz_$t" -timeout=600 -runs=1 "$f")
    echo "fuzz: $t: $(basename "$f"): loading ${load_s} CPU s, with the steps ${all_s} CPU s, start ${base_s} CPU s"
    if awk -v a="$load_s" -v b="$all_s" -v z="$base_s" 'BEGIN { exit !(a - z < 1.0 && b - z < 10.0) }'; then
      mkdir -p "$out/load"; mv "$f" "$out/load/"
    fi
  done
}

# A -fork child can hang for good on a busy machine: when an input runs past the wall-clock -timeout, libFuzzer's
# SIGALRM handler writes the unit with malloc, and if the alarm came while the input was inside ASan's allocator the
# child waits on the allocator's own lock (seen 2026-11-28: gdb showed AlarmCallback -> fwrite -> asan_malloc ->
# FutexWait under PopulateFreeArray; the child sat asleep at 0 CPU s for 15 minutes and the run with it, leaving an
# empty timeout- file). watchdog FUZZER TARGET: every 10 s, a child of the target asleep (state S) whose CPU time has
# not moved for FUZZ_STALL wall seconds (default 120; a child runs inputs without sleeping) is killed; libFuzzer's
# parent takes that as a crash of the child and goes on (-ignore_crashes=1). Each kill is a line in WS/watchdog-TARGET.log.
watchdog() {
  local parent="$1" t="$2" stall="${FUZZ_STALL:-120}" pid st cpu now
  declare -A last since
  : > "$WS/watchdog-$t.log"
  while kill -0 "$parent" 2>/dev/null; do
    now=$(date +%s)
    for pid in $(pgrep -f "^$BIN/fuzz_$t( |$)"); do
      # never the parent (it sleeps while its child works): by pid, and by its -fork flag, which children lack
      [ "$pid" != "$parent" ] || continue
      tr '\0' ' ' < "/proc/$pid/cmdline" 2>/dev/null | grep -q -- ' -fork=' && continue
      read -r st cpu < <(awk '{print $3, $14 + $15}' "/proc/$pid/stat" 2>/dev/null) || continue
      if [ "$st" != S ] || [ "${last[$pid]:-}" != "$cpu" ]; then last[$pid]=$cpu since[$pid]=$now; continue; fi
      if [ $((now - since[$pid])) -ge "$stall" ]; then
        kill -KILL "$pid" 2>/dev/null &&
          echo "$(date -u +%H:%M:%S) killed child $pid of fuzz_$t: asleep at $cpu CPU ticks for $((now - since[$pid])) s" >> "$WS/watchdog-$t.log"
      fi
    done
    sleep 10
  done
}

# ---- fuzz, one target at a time on one core --------------------------------------------------------------------
broken=0 idle=0
summary=""
for t in "${targets[@]}"; do
  # SECONDS 0: fuzz nothing (--cov or --save over the corpora there are); libFuzzer reads -max_total_time=0 as no limit
  [ "$secs" -gt 0 ] || [ $recheck_only -eq 1 ] || continue
  if [ $recheck_only -eq 1 ]; then
    recheck "$t"
    found=$(find "$ROOT/car/test/fuzz/out/$t" -maxdepth 1 -type f 2>/dev/null | wc -l)
    [ "$found" -eq 0 ] || broken=1
    summary+="$t $found findings; "
    continue
  fi
  seed="$WS/seeds/$t" corpus="$WS/corpus/$t" out="$ROOT/car/test/fuzz/out/$t"
  seeds "$t" "$seed"
  mkdir -p "$corpus" "$out"
  [ -d "test/fuzz/corpus/$t" ] && cp -n test/fuzz/corpus/"$t"/* "$corpus/" 2>/dev/null
  # every input that once broke the rule (test/fuzz/regressions/TARGET/) runs first, each run
  [ -d "test/fuzz/regressions/$t" ] && cp test/fuzz/regressions/"$t"/* "$seed/" 2>/dev/null
  dict=(); [ "$t" = ros_control ] || dict=(-dict=test/fuzz/xml.dict)
  echo "fuzz: $t for $secs s ..."
  log="$WS/fuzz-$t.log"
  if [ ! -x "$BIN/fuzz_$t" ]; then
    idle=1; summary+="$t executed nothing (no binary); "
    echo "fuzz: $t: FAILED: executed nothing: no binary $BIN/fuzz_$t"
    continue
  fi
  TIMEFORMAT='%U %S'
  start=$(date -u +%Y-%m-%dT%H:%M:%SZ) wall0=$(date +%s) commit0=$(git -C "$ROOT" rev-parse --short=12 HEAD)
  # user + sys of libFuzzer's parent and every -fork child it waited for [CPU s]
  # (the fuzzer is started as a simple command in the background, so $! is libFuzzer's parent itself, which the
  # watchdog leaves alone; `time` is around the group and prints its line last)
  cpu=$( { time {
      LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 \
      UBSAN_OPTIONS=print_stacktrace=1 nice -n "$NICE" "$BIN/fuzz_$t" -timeout="$TIMEOUT" -rss_limit_mb=2048 -max_len=65536 \
      -fork="$FORK" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
      -max_total_time="$secs" -artifact_prefix="$out/" "${dict[@]}" "$corpus" "$seed" \
      > "$log" 2>&1 &
      fuzzer=$!
      watchdog "$fuzzer" "$t" > /dev/null 2>&1 &
      wd=$!
      wait "$fuzzer"; kill "$wd"; wait "$wd"
    } > /dev/null 2>&1; } 2>&1 | tail -n 1 )
  cpu=$(echo "$cpu" | awk '{printf "%.0f", $1 + $2}')
  wall=$(( $(date +%s) - wall0 ))
  execs=$(grep -oE '^#[0-9]+' "$log" | tail -n 1 | tr -d '#')
  # libFuzzer's count of executed inputs: none (a binary that would not start, no input run) is a failure, and
  # the CPU seconds it spent are not fuzzing
  if [ "${execs:-0}" -eq 0 ]; then
    idle=1; summary+="$t executed nothing (${cpu} CPU s not counted); "
    echo "fuzz: $t: FAILED: executed nothing (0 inputs; ${cpu} CPU s not counted): $(tail -n 3 "$log" | tr '\n' ' ')"
    record_run "$t" "$start" "$wall" 0 0 "$log" "$corpus" - "executed nothing: ${cpu} CPU s not counted"
    continue
  fi
  recheck "$t"
  found=$(find "$out" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l)
  [ "$found" -eq 0 ] || { broken=1; grep -m3 -A12 'ERROR\|RULE BROKEN\|ALARM' "$log"; }
  echo "fuzz: $t: ${cpu} CPU s, ${execs:-?} inputs, $found finding(s) in $out"
  note="timeout ${TIMEOUT} s"
  [ "$FORK" -eq 1 ] || note+="; fork ${FORK}"
  stuck=$(grep -c killed "$WS/watchdog-$t.log" 2>/dev/null); [ "${stuck:-0}" -eq 0 ] || note+="; ${stuck} hung child(ren) killed by the watchdog"
  [ -d "$out/load" ] && note+="; $(find "$out/load" -type f | wc -l) wall-clock timeout(s) re-measured as load"
  record_run "$t" "$start" "$wall" "$cpu" "$execs" "$log" "$corpus" "$found" "$note"
  summary+="$t ${cpu} CPU s ${found} findings; "
done

# ---- the minimised corpora, kept in the repository as the next run's start ----------------------------------------
if [ $save -eq 1 ]; then
  for t in "${targets[@]}"; do
    rm -rf "test/fuzz/corpus/$t"; mkdir -p "test/fuzz/corpus/$t"
    LLVM_PROFILE_FILE=/dev/null ASAN_OPTIONS=detect_leaks=0 CAR_FUZZ_NO_STEP=1 nice -n "$NICE" "$BIN/fuzz_$t" -merge=1 \
      -timeout=30 "test/fuzz/corpus/$t" "$WS/corpus/$t" > "$WS/merge-$t.log" 2>&1
    echo "fuzz: $t: corpus $(ls "test/fuzz/corpus/$t" | wc -l) files, $(du -sh "test/fuzz/corpus/$t" | cut -f1)"
  done
fi

# ---- coverage of the loaders over the corpora ------------------------------------------------------------------
if [ $cov -eq 1 ]; then
  prof="$WS/prof"; rm -rf "$prof"; mkdir -p "$prof"
  objs=()
  for t in "${ALL[@]}"; do
    [ -d "$WS/corpus/$t" ] || continue
    LLVM_PROFILE_FILE="$prof/$t.profraw" ASAN_OPTIONS=detect_leaks=0 "$BIN/fuzz_$t" -runs=0 -timeout=5 \
      "$WS/corpus/$t" "$WS/seeds/$t" > "$WS/cov-$t.log" 2>&1
    objs+=(-object "$BIN/fuzz_$t")
  done
  llvm-profdata-14 merge -sparse "$prof"/*.profraw -o "$prof/all.profdata"
  # the loaders live in libcar_sim.so: it is the report's first object, the targets the others
  llvm-cov-14 report "$WS/devel/lib/libcar_sim.so" "${objs[@]}" -instr-profile="$prof/all.profdata" \
    "$WS/src/car/src/model" "$WS/src/car/src/description" 2>/dev/null | tee "$WS/coverage.txt" | tail -n 20
fi
echo "fuzz: ${summary%; }"
[ $broken -eq 0 ] && echo "fuzz: no input broke the rule" || echo "fuzz: FAILED: inputs that broke the rule are in test/fuzz/out/"
[ $idle -eq 0 ] || { echo "fuzz: FAILED: a target executed nothing (above)"; exit 2; }
exit $broken
