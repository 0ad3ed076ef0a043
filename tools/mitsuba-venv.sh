#!/bin/sh
# SPDX-License-Identifier: MIT
# Sourced by tools/make-references.sh and tools/bench-vs-mitsuba.sh: creates the virtualenv
# .venv-mitsuba (gitignored) with Mitsuba from PyPI on first use, and sets VENV.
VENV=.venv-mitsuba
MITSUBA_VERSION=3.9.1 # the version the committed references were made with (tests/references/README.md)

if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import mitsuba, numpy" 2>/dev/null; then
    echo "creating $VENV with mitsuba==$MITSUBA_VERSION" >&2
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install -q "mitsuba==$MITSUBA_VERSION" numpy
fi
