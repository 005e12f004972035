#!/bin/sh
# Runs the command-line examples of the README as written (the fenced block after the line
# "<!-- cli-examples ... -->") and checks each one's exit status: the status its "# exit N"
# comment gives, 0 without one.
# Usage: readme_examples.sh SOURCE_DIR BIPEDNAV WORK_DIR
#   WORK_DIR gets links to the repository's scenarios/, config/ and tests/ (the examples' paths are
#   relative to the repository root) and receives their outputs.
src=$1
bin=$2
work=$3
mkdir -p "$work/bin" || exit 1
for d in scenarios config tests; do ln -sfn "$src/$d" "$work/$d"; done
ln -sf "$bin" "$work/bin/bipednav"
PATH="$work/bin:$PATH"
export PATH
cd "$work" || exit 1
examples=$(awk '/<!-- cli-examples/ { on = 1; next } on && /^```sh/ { inside = 1; next }
                inside && /^```/ { exit } inside { print }' "$src/README.md")
[ -n "$examples" ] || { echo "readme_examples: no examples found in $src/README.md" >&2; exit 1; }
failed=0
count=0
printf '%s\n' "$examples" > examples.txt
while IFS= read -r line; do
  case $line in '' | '#'*) continue ;; esac
  want=$(printf '%s\n' "$line" | sed -n 's/.*# exit \([0-9]\).*/\1/p')
  [ -n "$want" ] || want=0
  sh -c "$line" > example.log 2>&1 < /dev/null
  status=$?
  count=$((count + 1))
  if [ "$status" = "$want" ]; then
    echo "ok (exit $status): $line"
  else
    echo "FAILED (exit $status, expected $want): $line" >&2
    tail -n 5 example.log >&2
    failed=1
  fi
done < examples.txt
echo "$count examples run"
exit "$failed"
