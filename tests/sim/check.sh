# The harness of the end-to-end shell tests (sourced): `check "what" command...` runs the command
# and records ok/FAIL; `report` prints the tally and exits non-zero when anything failed.
failures=0
passes=0
check() {
    local what=$1; shift
    if "$@"; then echo "ok   $what"; passes=$((passes + 1)); else echo "FAIL $what"; failures=$((failures + 1)); fi
}
report() {
    echo "$passes passed, $failures failed"
    exit $((failures > 0))
}
