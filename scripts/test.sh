#!/usr/bin/env bash
# The test command: the Rust workspace's tests, then the Python package
# (python/) installed into a venv with the README's command and its pytest
# suite. Exits non-zero on any failure; pytest collecting no test (exit 5)
# is a failure too.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo test --workspace

venv=${SCTL_VENV:-target/py-venv}
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install -q maturin numpy pytest
# `pip install ./python` (python/README.md), forced so that a rebuilt
# extension replaces an installed one of the same version.
start=$(date +%s)
"$venv/bin/python" -m pip install -q --force-reinstall --no-deps ./python
echo "test.sh: the Python package built and installed in $(( $(date +%s) - start )) s"

# The suite compares the package's answers with the sctl program that
# `cargo test` just built. It runs from the repository root so that the
# installed package, not python/sctl/, is imported.
export SCTL_BIN=${SCTL_BIN:-$PWD/target/debug/sctl}
status=0
"$venv/bin/pytest" -q python/tests || status=$?
if [ "$status" -eq 5 ]; then
  echo "test.sh: pytest collected no tests" >&2
fi
exit "$status"
