#!/bin/sh
# Runs a command and checks its exit status and output (the CLI convention, README "Command line").
# Usage: expect_exit.sh STATUS REGEX COMMAND [ARG...]
#   passes when COMMAND exits with STATUS and its stdout + stderr match the extended regular
#   expression REGEX (empty: anything).
expected=$1
regex=$2
shift 2
out=$("$@" 2>&1)
status=$?
printf '%s\n' "$out"
if [ "$status" != "$expected" ]; then
  echo "expect_exit: exit status $status, expected $expected: $*" >&2
  exit 1
fi
if [ -n "$regex" ] && ! printf '%s\n' "$out" | grep -Eq -- "$regex"; then
  echo "expect_exit: the output does not match /$regex/: $*" >&2
  exit 1
fi
exit 0
