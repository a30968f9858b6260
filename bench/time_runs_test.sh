#!/usr/bin/env bash
# time_runs.py, as bench/run.sh uses it: warm-up rounds run untimed, every round runs each
# command once in turn (the order is checked through a log the commands append to), and
# --json holds one time and one CPU time per timed run. Bad options: one line, status 2.
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
for bad in "-n x true" "-w -1 true" "-n 0 true"; do
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
echo "time_runs.py: order, --json and bad options as expected"
