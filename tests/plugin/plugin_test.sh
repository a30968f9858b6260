#!/usr/bin/env bash
# Installs busdecode into a temporary prefix, builds the example plugin against the
# installed headers and CMake package, and decodes with it through BUSDECODE_PLUGIN_PATH.
set -euo pipefail
build_dir=$1
src_dir=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build_dir" --prefix "$tmp/prefix" >/dev/null
cmake -S "$src_dir/plugins/example" -B "$tmp/pulse" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/pulse" >/dev/null
out=$(BUSDECODE_PLUGIN_PATH="$tmp/pulse" "$tmp/prefix/bin/decode" "$src_dir/tests/plugin/pulses.vcd" \
      --proto pulse --opt min_ns=20 --format jsonl)
echo "$out"
expected='{"proto":"pulse","type":"pulse","start_ns":100,"end_ns":150,"width_ns":50,"errors":[]}
{"proto":"pulse","type":"pulse","start_ns":400,"end_ns":410,"width_ns":10,"errors":["short"]}
{"proto":"pulse","type":"pulse","start_ns":1000,"end_ns":1250,"width_ns":250,"errors":[]}'
if [ "$out" != "$expected" ]; then
  echo "unexpected output; expected:"; echo "$expected"; exit 1
fi
# Its metadata lists "pulse" (pulse_plugin.json), the built-in plugins' list theirs: a run
# asking for pulse loads its plugin and no other (Qt names each library it loads).
loaded=$(QT_DEBUG_PLUGINS=1 BUSDECODE_PLUGIN_PATH="$tmp/pulse" "$tmp/prefix/bin/decode" \
         "$src_dir/tests/plugin/pulses.vcd" --proto pulse 2>&1 >/dev/null |
         grep -o 'busdecode_[a-z0-9]*\.so" loaded library' | sort -u || true)
if [ "$loaded" != 'busdecode_pulse.so" loaded library' ]; then
  echo "a run asking for pulse loaded: $loaded"; exit 1
fi
# --list shows the plugin's declaration
list=$(BUSDECODE_PLUGIN_PATH="$tmp/pulse" "$tmp/prefix/bin/decode" --list)
grep -q "^pulse  Pulse widths" <<<"$list" || { echo "--list does not show the plugin"; exit 1; }
# A plugin built against another version of the interface (here: the same example, its
# installed plugin.h saying 1.0) is refused with a warning that says why, not loaded:
# its calls into decode would not match.
cp -r "$tmp/prefix" "$tmp/old_prefix"
header=$(find "$tmp/old_prefix" -name plugin.h -path '*busdecode*' | head -1)
sed -i 's|"org.busdecode.DecoderPlugin/[0-9.]*"|"org.busdecode.DecoderPlugin/1.0"|' "$header"
grep -q 'DecoderPlugin/1.0"' "$header" || { echo "could not rewrite $header"; exit 1; }
cmake -S "$src_dir/plugins/example" -B "$tmp/old_pulse" -G Ninja -DCMAKE_PREFIX_PATH="$tmp/old_prefix" >/dev/null
cmake --build "$tmp/old_pulse" >/dev/null
old_list=$(BUSDECODE_PLUGIN_PATH="$tmp/old_pulse" "$tmp/prefix/bin/decode" --list 2>"$tmp/old.err")
cat "$tmp/old.err"
grep -q "not a busdecode plugin (it does not implement org.busdecode.DecoderPlugin/" "$tmp/old.err" ||
  { echo "no warning for a plugin of another interface version"; exit 1; }
if grep -q "^pulse " <<<"$old_list"; then echo "a plugin of another interface version was loaded"; exit 1; fi
echo "plugin test passed"
