#!/usr/bin/env bash
# Builds the documentation site into docs/_build/html (open docs/_build/html/index.html).
# Run after scripts/setup.sh; installs the `docs` extra (Sphinx and its extensions) into .venv
# when it is missing. The examples of the gallery run during the build (a few minutes on 2 cores).
#
#   bash scripts/docs.sh            # build; warnings are printed
#   bash scripts/docs.sh -W         # any warning fails the build (tests/test_docs.py does this)
#
# Extra arguments go to sphinx-build. FETORSION_DOCS_PYTHON names another interpreter (the tests
# use the one they run under).
set -euo pipefail
cd "$(dirname "$0")/.."

py="${FETORSION_DOCS_PYTHON:-.venv/bin/python}"
if [ ! -x "$py" ]; then
  echo "docs: $py not found: run scripts/setup.sh first" >&2
  exit 1
fi
if ! "$py" -c "import sphinx, pydata_sphinx_theme, numpydoc, sphinx_gallery, myst_parser" 2>/dev/null; then
  echo "docs: installing the docs extra into $(dirname "$(dirname "$py")")"
  "$py" -m pip install -q -e ".[docs]"
fi
# sphinx-gallery runs the examples in this process: no display, and one BLAS thread per process is
# what the examples are timed with.
export MPLBACKEND=Agg
# autosummary writes a stub per documented name into docs/_api and never removes one: a stub of a
# name that moved would fail the build (-W), so the stubs are made afresh every build
rm -rf docs/_api
exec "$py" -m sphinx -b html --keep-going "$@" docs docs/_build/html
