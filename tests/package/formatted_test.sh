#!/usr/bin/env bash
# formatted_test.sh SOURCE_DIR CLANG_FORMAT
# Every C++ file of the project as .clang-format lays it out: a change that skipped the
# formatter fails here, with the files and lines it would move.
set -euo pipefail
cd "$1"
find analyzer bench decoders fuzz plugins python tests examples \
    \( -name '*.cpp' -o -name '*.h' \) -print0 |
    xargs -0 "$2" --style=file --dry-run --Werror
