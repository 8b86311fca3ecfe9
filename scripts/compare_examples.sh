#!/usr/bin/env bash
# Compares two `marsden` binaries on the repository's problem files, bit for bit:
#
#   scripts/compare_examples.sh OLD_BIN NEW_BIN [WORK_DIR]
#
# * every examples/*.toml and every run fixture of crates/marsden-cli/tests/fixtures/ is run by
#   both binaries into separate output directories (`--out`): every file written must be
#   byte-identical, except summary.json, which must be equal in every field but its timings
#   (`wall_seconds`, `jit_compile_seconds`);
#   the exit statuses and stderr must match (the output directory's name replaced);
# * stdout of `check`, `systems`, `order`, the sweeps and every `--help` must be identical;
# * every bad fixture (tests/fixtures/bad/) must give the same exit status and stderr.
#
# Prints one line per difference and a closing `N passed, N failed`; exits 1 on any difference.
set -u
work=${3:-$(mktemp -d)}
mkdir -p "$work/bin-old" "$work/bin-new"
# Both named `marsden`: clap prints the program's name in its usage lines.
ln -sf "$(realpath "$1")" "$work/bin-old/marsden"
ln -sf "$(realpath "$2")" "$work/bin-new/marsden"
old=$work/bin-old/marsden
new=$work/bin-new/marsden
cd "$(dirname "$0")/.."
passed=0
failed=0

ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "DIFFERENT: $*"; }

# Runs "$@" with each binary; compares exit status, stdout (unless $skip_stdout) and stderr
# with the output directories renamed to OUT.
both() {
    local label=$1
    shift
    for side in old new; do
        local bin=${!side}
        local out="$work/$side/$label"
        rm -rf "$out"
        mkdir -p "$out"
        local args=()
        for a in "$@"; do args+=("${a//@OUT@/$out/files}"); done
        "$bin" "${args[@]}" >"$out/stdout" 2>"$out/stderr"
        echo $? >"$out/status"
        sed -i "s#$out/files#OUT#g" "$out/stderr" "$out/stdout"
    done
    local o="$work/old/$label" n="$work/new/$label"
    cmp -s "$o/status" "$n/status" || { bad "$label: exit status $(cat "$o/status") vs $(cat "$n/status")"; return; }
    cmp -s "$o/stderr" "$n/stderr" || { bad "$label: stderr"; diff "$o/stderr" "$n/stderr" | head -5; return; }
    if [ -z "${skip_stdout:-}" ]; then
        cmp -s "$o/stdout" "$n/stdout" || { bad "$label: stdout"; diff "$o/stdout" "$n/stdout" | head -5; return; }
    fi
    ok
}

# Compares the files two runs wrote: bytes, except summary.json without its timings
# (wall_seconds, jit_compile_seconds); the top-level fields that differ go to stderr.
same_files() {
    local label=$1
    local o="$work/old/$label/files" n="$work/new/$label/files"
    [ -d "$o" ] || [ -d "$n" ] || { ok; return; }
    if ! diff <(cd "$o" && ls) <(cd "$n" && ls) >/dev/null; then
        bad "$label: different file lists"
        return
    fi
    for f in "$o"/*; do
        local name=$(basename "$f")
        if [ "${name%.json}" != "$name" ] && [ "${name#summary}" != "$name" ]; then
            python3 - "$f" "$n/$name" <<'PY' || { bad "$label/$name: fields differ"; return; }
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for d in (a, b):
    d.pop("wall_seconds", None)
    d.pop("jit_compile_seconds", None)
different = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
if different:
    print("  fields: " + ", ".join(different), file=sys.stderr)
sys.exit(0 if a == b else 1)
PY
        else
            cmp -s "$f" "$n/$name" || { bad "$label/$name: bytes differ"; return; }
        fi
    done
    ok
}

fixtures=crates/marsden-cli/tests/fixtures
for file in examples/*.toml $fixtures/*.toml; do
    # Optimal control problems are solved by `marsden optimize`, which older binaries lack
    # (`marsden run` refuses them): compared by the examples test instead.
    grep -q '^\[optimal_control\]' "$file" && continue
    label=run-$(basename "$file" .toml)
    # The run's report has the wall time on stdout: compare its files and stderr instead.
    skip_stdout=1 both "$label" run "$file" --out @OUT@ --no-progress
    same_files "$label"
    both "check-$(basename "$file" .toml)" check "$file"
done
for file in $fixtures/*sweep*.toml; do
    label=sweep-$(basename "$file" .toml)
    both "$label-threads" run "$file" --out @OUT@ --threads 2
    same_files "$label-threads"
    both "$label-shard" run "$file" --out @OUT@ --shard 1/3
    same_files "$label-shard"
done
for file in $fixtures/bad/*.toml; do
    both "bad-$(basename "$file" .toml)" run "$file" --out @OUT@
    both "bad-check-$(basename "$file" .toml)" check "$file"
done
both order-pendulum order examples/pendulum.toml --methods midpoint,gauss-2 --h 0.4,0.2,0.1 --t-end 4
both order-bad-method order examples/pendulum.toml --methods midpiont
both systems systems
both systems-pendulum systems pendulum
both systems-unknown systems pendulm
both version --version
both help --help
for command in run check order systems plot; do
    both "help-$command" "$command" --help
done
both usage-no-file run
both usage-shard run examples/pendulum.toml --shard 3/3
both plot-missing plot "$work/nothing-here"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
