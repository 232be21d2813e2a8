# The harness of the end-to-end shell tests (sourced): `check "what" command...` runs the command
# and records ok/FAIL; `report` prints the tally and exits non-zero when anything failed;
# `exited_saying N pattern...` holds when the last run exited with N ($rc) and its output ($err)
# matches every pattern (grep, basic regular expressions).
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
exited_saying() {
    test "$rc" -eq "$1" || return 1
    shift
    for pattern in "$@"; do grep -q -- "$pattern" <<<"$err" || return 1; done
}
