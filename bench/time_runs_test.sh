#!/usr/bin/env bash
# time_runs.py, as bench/run.sh uses it: warm-up rounds run untimed, every round runs each
# command once in turn (the order is checked through a log the commands append to), and
# --json holds one time and one CPU time per timed run, each command after the first is
# compared with it round by round (--split apart). Bad options: one line, status 2.
# No timing is judged here.
#
#   time_runs_test.sh SOURCE_DIR [PYTHON]
set -euo pipefail
tr="$1/bench/time_runs.py"
py="${2:-python3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
log="$tmp/log"
"$py" "$tr" -n 3 -w 1 --json "$tmp/t.json" sh -c "echo a >>$log" --- sh -c "echo b >>$log" >/dev/null
order="$(tr -d '\n' <"$log")"
[ "$order" = "abababab" ] || { echo "FAIL: runs in the order '$order', expected abababab" >&2; exit 1; }
"$py" - "$tmp/t.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))["results"]
# In the order given, each named by its words.
assert [x["command"].split()[:4] for x in r] == [["sh", "-c", "echo", "a"], ["sh", "-c", "echo", "b"]], r
for x in r:
    assert len(x["times"]) == 3 and len(x["cpu"]) == 3, x
    assert all(t > 0 for t in x["times"]) and all(c >= 0 for c in x["cpu"]), x
PY
# Round by round against the first: every round on one side of --split (no timing judged:
# the splits are beyond any run's time, or at none).
out="$("$py" "$tr" -n 3 --split 1e9 true --- true)"
grep -qx '  2\. against 1\., round by round: first under 1e+09 ms: x[0-9.]* (median of 3); at or over: - (no rounds)' <<<"$out" ||
    { echo "FAIL: --split 1e9: '$out'" >&2; exit 1; }
out="$("$py" "$tr" -n 3 --split 0 true --- true)"
grep -qx '  2\. against 1\., round by round: first under 0 ms: - (no rounds); at or over: x[0-9.]* (median of 3)' <<<"$out" ||
    { echo "FAIL: --split 0: '$out'" >&2; exit 1; }
out="$("$py" "$tr" -n 2 true --- true --- true)"
[ "$(grep -c 'against 1\., round by round: x[0-9.]* (median of 2)$' <<<"$out")" = 2 ] ||
    { echo "FAIL: paired lines: '$out'" >&2; exit 1; }
for bad in "-n x true" "-w -1 true" "-n 0 true" "--split x true"; do
    # shellcheck disable=SC2086
    if "$py" "$tr" $bad >/dev/null 2>"$tmp/err"; then
        echo "FAIL: time_runs.py $bad succeeded" >&2
        exit 1
    else
        status=$?
    fi
    [ "$status" = 2 ] && [ "$(wc -l <"$tmp/err")" = 1 ] ||
        { echo "FAIL: time_runs.py $bad: status $status, '$(cat "$tmp/err")'" >&2; exit 1; }
done
echo "time_runs.py: order, --json, paired ratios and bad options as expected"
