#!/bin/sh
# `rbcflow check CASE` and `rbcflow run CASE` on a case that must be refused: the same non-zero
# exit status and the same message (file, line, key and reason) after the command's name.
# Usage: check_equals_run.sh RBCFLOW CASE.toml (run in a scratch directory: a case that were
# accepted would write out/<case name> there).
exe=$1
case_file=$2
# The command's message: its first line that starts "rbcflow check: " or "rbcflow run: " (run may
# first say that it renders on a virtual display).
message() { grep -m1 '^rbcflow [a-z]*: ' | sed 's/^rbcflow [a-z]*: //'; }
c=$("$exe" check "$case_file" 2>&1 >/dev/null)
c_status=$?
r=$("$exe" run "$case_file" --quiet 2>&1 >/dev/null)
r_status=$?
echo "check (exit $c_status): $c"
echo "run   (exit $r_status): $r"
[ "$c_status" -ne 0 ] && [ "$c_status" -eq "$r_status" ] || exit 1
[ -n "$(printf '%s\n' "$c" | message)" ] && [ "$(printf '%s\n' "$c" | message)" = "$(printf '%s\n' "$r" | message)" ]
