#!/bin/sh
# SPDX-License-Identifier: MIT
# run-tests.sh [NAME=VALUE | BINARY]...: runs every Criterion test binary from the repository root,
# then prints one total line "tests: N passed, N failed, N skipped". A NAME=VALUE argument is
# exported to the binaries after it (e.g. PT_BVH_WIDTH=2 to run the BVH tests on another layout).
# Exit status is non-zero if any test failed or crashed. Criterion's synthesis line leaves skipped tests out (its
# "Tested" counts only those that ran), so the skips come from its JSON report (--json=FILE).
set -u
passed=0; failed=0; skipped=0; status=0
for t in "$@"; do
    case $t in
        *=*) export "$t"; echo "== with $t"; continue ;;
    esac
    echo "== $t"
    log=$(mktemp); report=$(mktemp)
    "$t" --jobs 2 --json="$report" 2>&1 | tee "$log"
    rc=$?
    line=$(grep -o 'Tested: [0-9]* | Passing: [0-9]* | Failing: [0-9]* | Crashing: [0-9]*' "$log" | tail -1)
    if [ -z "$line" ]; then
        echo "run-tests: $t printed no synthesis (exit $rc)"
        failed=$((failed + 1)); status=1
    else
        p=$(echo "$line" | sed 's/.*Passing: \([0-9]*\).*/\1/')
        f=$(echo "$line" | sed 's/.*Failing: \([0-9]*\).*/\1/')
        c=$(echo "$line" | sed 's/.*Crashing: \([0-9]*\).*/\1/')
        passed=$((passed + p)); failed=$((failed + f + c))
        [ "$f" -ne 0 ] || [ "$c" -ne 0 ] && status=1
    fi
    # The report's first "skipped" is the binary's total (the suites' follow).
    s=$(grep -o '"skipped": *[0-9]*' "$report" | head -1 | grep -o '[0-9]*$')
    if [ -n "$s" ] && [ "$s" -ne 0 ]; then
        echo "run-tests: $t skipped $s:" $(grep -B2 '"status": "SKIPPED"' "$report" |
            sed -n 's/.*"name": "\(.*\)".*/\1/p')
        skipped=$((skipped + s))
    fi
    rm -f "$log" "$report"
done
echo "tests: $passed passed, $failed failed, $skipped skipped"
exit $status
