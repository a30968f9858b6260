#!/usr/bin/env bash
# self_contained_test.sh SOURCE_DIR
# What a stranger's clone relies on: the README's test command is the one CI runs, the
# front-door documents stay short, and nothing points outside the repository.
set -euo pipefail
src="$1"
cd "$src"
fail=0
complain() { echo "self_contained_test: $*" >&2; fail=1; }

readme_cmd="$(grep -m1 '^apt-get update -qq' README.md || true)"
ci_cmd="$(grep -m1 '^apt-get update -qq' .ci/run || true)"
[ -n "$ci_cmd" ] || complain ".ci/run has no 'apt-get update -qq ...' command line"
[ "$readme_cmd" = "$ci_cmd" ] || complain "README.md's test command differs from .ci/run's"

for f in README.md bench/README.md fuzz/README.md; do
    n=$(wc -l <"$f")
    [ "$n" -lt 200 ] || complain "$f has $n lines (keep it under 200)"
done

# Work-diary references and folders outside the repository.
hits="$(grep -rnIiE 'stop [0-9]+' --exclude-dir=build* --exclude-dir=.git . || true)"
[ -z "$hits" ] || complain "numbered work notes ('stop N') in: $hits"
outside='share''d/'  # spelt in two pieces so that this line does not match itself
hits="$(grep -rnI "$outside" analyzer decoders tests cmake .ci || true)"
[ -z "$hits" ] || complain "references to a shared folder outside the repository: $hits"
exit $fail
