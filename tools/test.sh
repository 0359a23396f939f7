#!/usr/bin/env bash
# The test command: set up, lint, format and type check, then the whole suite.
# Extra arguments go to pytest (for example: tools/test.sh tests/messages -k codec).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/tools/setup.sh"
cd "$root"
.venv/bin/ruff check .
.venv/bin/ruff format --check .
.venv/bin/python tools/typecheck.py
exec .venv/bin/pytest -n "${RFC_TEST_JOBS:-auto}" --durations=25 "$@"
