#!/bin/sh
# Feeds one numeric option a negative number, NaN and zero (README "Command line": a bad number
# exits 2 naming the option).
# Usage: numeric_flag.sh FLAG NEGATIVE_STATUS ZERO_STATUS COMMAND [ARG...]
#   runs COMMAND ARG... FLAG -1, then FLAG nan, then FLAG 0: NaN must exit 2, the others with the
#   given status (2 for most; 0 or 1 where the value is valid, e.g. --voxel 0 = no voxel grid).
#   Every exit 2 must name FLAG.
flag=$1
negative=$2
zero=$3
shift 3
failed=0
for value in -1 nan 0; do
  case $value in
    -1) want=$negative ;;
    nan) want=2 ;;
    0) want=$zero ;;
  esac
  out=$("$@" "$flag" "$value" 2>&1)
  status=$?
  shown=$(printf "%s\n" "$out" | grep -m 1 "error:" || printf "%s\n" "$out" | tail -n 1)
  printf "%s %s -> exit %s: %s\n" "$flag" "$value" "$status" "$shown"
  if [ "$status" != "$want" ]; then
    echo "numeric_flag: $flag $value: exit status $status, expected $want" >&2
    failed=1
  elif [ "$want" = 2 ] && ! printf '%s\n' "$out" | grep -Fq -- "$flag"; then
    echo "numeric_flag: $flag $value: the error does not name $flag" >&2
    failed=1
  fi
done
exit "$failed"
