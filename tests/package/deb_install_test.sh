#!/usr/bin/env bash
# deb_install_test.sh BUILD_DIR SOURCE_DIR CPACK
# Builds the .deb with CPack, extracts it into a temporary root and runs the installed
# `decode` from there: its libraries and plugins must come from that root alone.
set -euo pipefail
build="$1" src="$2" cpack="$3"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/busdecode-deb.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "deb_install_test: $*" >&2; exit 1; }

"$cpack" --config "$build/CPackConfig.cmake" -G DEB -B "$tmp/out" >"$tmp/cpack.log" 2>&1 ||
    { cat "$tmp/cpack.log" >&2; fail "cpack -G DEB failed"; }
debs=("$tmp"/out/busdecode_*.deb)
[ -f "${debs[0]}" ] || fail "no busdecode_*.deb in $tmp/out"
deb="${debs[0]}"
info="$(dpkg-deb --info "$deb")"
grep -q "Package: busdecode" <<<"$info" || fail "control file has no Package: busdecode"

root="$tmp/root"
dpkg-deb -x "$deb" "$root"
decode="$root/usr/bin/decode"
[ -x "$decode" ] || fail "no usr/bin/decode in the package"
for f in usr/share/doc/busdecode/LICENSE usr/share/doc/busdecode/contract.md \
    usr/share/doc/busdecode/examples/bissc_1mhz_26bit.vcd usr/bin/decode-monitor; do
    [ -e "$root/$f" ] || fail "no $f in the package"
done
ls "$root"/usr/lib*/busdecode/plugins/busdecode_bissc.so >/dev/null 2>&1 ||
    ls "$root"/usr/lib/*/busdecode/plugins/busdecode_bissc.so >/dev/null 2>&1 ||
    fail "no busdecode_bissc.so plugin in the package"

# The core library from the extracted root, not from the build tree.
core="$(ldd "$decode" | awk '/libbusdecode_core/ { print $3 }')"
case "$core" in "$root"/*) ;; *) fail "decode links $core, not the package's library" ;; esac

export -n BUSDECODE_PLUGIN_PATH
unset BUSDECODE_PLUGIN_PATH
list="$("$decode" --list)" || fail "decode --list failed"
for id in bissc spi ssi tmc8100 tmcl uart; do
    grep -q "^$id  " <<<"$list" || fail "decode --list does not list $id"
done

example="$root/usr/share/doc/busdecode/examples/bissc_1mhz_26bit.vcd"
golden="$src/captures/bissc_1mhz_26bit.golden.jsonl"
QT_DEBUG_PLUGINS=1 "$decode" "$example" --proto bissc --format jsonl >"$tmp/out.jsonl" \
    2>"$tmp/err" || { cat "$tmp/err" >&2; fail "decoding the example failed"; }
cmp -s "$tmp/out.jsonl" "$golden" || fail "the example's output differs from $golden"
grep -q "$root/usr/lib.*busdecode_bissc.so\" loaded library" "$tmp/err" ||
    fail "the bissc plugin was not loaded from the package's root"
# Live acquisition is a module of its own, loaded from the package's root for --scan.
if ls "$build"/lib/busdecode/busdecode_live.so >/dev/null 2>&1; then
    live=no
    for f in "$root"/usr/lib*/busdecode/busdecode_live.so "$root"/usr/lib/*/busdecode/busdecode_live.so; do
        [ -f "$f" ] && live=yes
    done
    [ $live = yes ] || fail "no busdecode_live.so in the package"
    LD_DEBUG=files "$decode" --scan >"$tmp/scan" 2>"$tmp/scan.err" ||
        { cat "$tmp/scan.err" >&2; fail "decode --scan failed"; }
    grep -q "^demo" "$tmp/scan" || fail "decode --scan does not list libsigrok's demo device"
    grep -q "file=$root/usr/lib.*busdecode_live.so" "$tmp/scan.err" ||
        fail "the live module was not loaded from the package's root"
fi
# Every library a binary, plugin or module of the package loads from the system belongs
# to a Debian package its Depends names.
depends="$(dpkg-deb --field "$deb" Depends)"
named="$(tr ',' '\n' <<<"$depends" | sed 's/^ *//; s/ .*//')"  # the package names alone
while IFS= read -r elf; do  # its own NEEDED entries, where ldd finds them
    needed="$(readelf -d "$elf" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')"
    ldd "$elf" 2>/dev/null | awk -v needed="$needed" '
        BEGIN { n = split(needed, list, "\n"); for (i = 1; i <= n; i++) want[list[i]] = 1 }
        $2 == "=>" && $3 ~ /^\// && ($1 in want) { print $3 }'
done < <(find "$root" -type f \( -name '*.so*' -o -path '*/bin/*' \)) | sort -u |
    while IFS= read -r lib; do
        case "$lib" in "$root"/*) continue ;; esac
        owner="$(dpkg -S "$(readlink -f "$lib")" 2>/dev/null | head -1 | cut -d: -f1)" ||
            owner=""
        [ -n "$owner" ] || owner="$(dpkg -S "$lib" 2>/dev/null | head -1 | cut -d: -f1)"
        [ -n "$owner" ] || fail "$lib, which the package loads, belongs to no Debian package"
        # A sanitizer build's own runtimes: such a build is tested, never shipped.
        case "$owner" in libasan* | libubsan* | liblsan* | libtsan*) continue ;; esac
        grep -qxF "$owner" <<<"$named" ||
            fail "the package loads $lib (from $owner), which its Depends does not name: $depends"
    done
python="$(find "$root" -name '_busdecode*.so' | head -1)"
if [ -n "$python" ]; then
    grep -q "python3 (>= " <<<"$depends" || fail "the Python module ships, python3 is not in Depends"
fi
echo "deb_install_test: $(basename "$deb") installs, lists and decodes from $root"
