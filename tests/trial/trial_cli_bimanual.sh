#!/usr/bin/env bash
# grip trial runs a bimanual candidate file with --bimanual and reports both grippers (closing
# forces, path ends and D1/D2 per gripper); a bimanual file without --bimanual, or a unimanual one with it,
# is refused in one line naming the file, and nothing is written.
set -euo pipefail
grip=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$grip" -q synth --object plate --gripper parallel-jaw --bimanual --count 1 --seed 1 \
  --out "$dir/two.txt" >/dev/null
"$grip" -q synth --object plate --gripper parallel-jaw --count 1 --seed 1 --out "$dir/one.txt" >/dev/null

"$grip" trial --candidates "$dir/two.txt" --bimanual --threads 1 --report "$dir/r.json" 2>/dev/null
grep -q '"bimanual": true' "$dir/r.json" || { echo "FAIL: the report is not bimanual"; exit 1; }
line=$(grep '"id": 0' "$dir/r.json")
# Four closing forces over both grippers, then two per gripper with each gripper's path ends and
# D1/D2.
forces=$(grep -o '"closing_forces": \[[^]]*\]' <<<"$line")
[ "$(grep -c . <<<"$forces")" -eq 3 ] || { echo "FAIL: expected 3 closing_forces lists"; exit 1; }
[ "$(head -1 <<<"$forces" | tr -cd , | wc -c)" -eq 3 ] || { echo "FAIL: not 4 forces"; exit 1; }
grep -q '"grippers": \[{"closing_forces": \[[^],]*, [^],]*\], "closing_at_path_end": \[[a-z]*, [a-z]*\], "d1": ' <<<"$line" ||
  { echo "FAIL: no per-gripper fields"; exit 1; }
"$grip" trial --candidates "$dir/one.txt" --threads 1 --report "$dir/u.json" 2>/dev/null
if grep -q -e bimanual -e grippers "$dir/u.json"; then echo "FAIL: unimanual report has bimanual fields"; exit 1; fi

refused() {  # refused FILE EXPECTED-TEXT ARGS...
  local file=$1 expected=$2; shift 2
  if "$grip" trial --candidates "$dir/$file" --report "$dir/bad.json" "$@" 2>"$dir/err"; then
    echo "FAIL: $file $* was accepted"; exit 1
  fi
  if [ -e "$dir/bad.json" ]; then echo "FAIL: $file $* wrote a report"; exit 1; fi
  if [ "$(grep -c . "$dir/err")" -ne 1 ] || ! grep -q -- "$expected" "$dir/err"; then
    echo "FAIL: $file $*: expected one line with '$expected', got:"; cat "$dir/err"; exit 1
  fi
}
refused two.txt "two.txt: the candidates are bimanual (two grippers each); pass --bimanual"
refused one.txt "one.txt: the candidates are unimanual (one gripper each), not bimanual" --bimanual
echo "ok"
