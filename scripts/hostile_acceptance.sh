#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Acceptance run of the second round of hostile inputs (docs/reliability.md, "Threat model";
# results in docs/validation/reliability-round2.md): each case of classes A-M runs the railtab
# program (or the Python module) in a folder of its own, under a 4 GB address-space limit and a
# kill timeout, and prints one line: CLASS | case | exit status | seconds | verdict | message.
# A case fails when it hangs (killed by the timeout), crashes (status >= 128), runs a command (a
# file named pwned* appears), leaves a file outside the requested output, exits otherwise than
# expected, or does not name its input in the message. Exit status 1 when a case fails.
# Usage: bash scripts/hostile_acceptance.sh HOSTILE_DIR WORK_DIR
#   HOSTILE_DIR: the round's inputs (README there, ids A-M); WORK_DIR: emptied, then filled.
#   RAILTAB (default build/release/generator/railtab) and PYTHONPATH_RAILTAB (default
#   build/release/python) name the program and the built Python package.
set -u
[ $# -eq 2 ] || { sed -n '3,13p' "$0" >&2; exit 2; }
R=$(cd "$(dirname "$0")/.." && pwd); K=$(cd "$1" && pwd); W=$(realpath -m "$2")
B=$(realpath "${RAILTAB:-$R/build/release/generator/railtab}")
PY=$(realpath "${PYTHONPATH_RAILTAB:-$R/build/release/python}")
[ -x "$B" ] || { echo "hostile_acceptance: $B not built" >&2; exit 2; }
rm -rf "$W"; mkdir -p "$W"
ulimit -v 4000000
fail=0
report() {  # class case rc secs verdict message (a Python traceback: its last line)
  local m=$(echo "$6" | head -1)
  [[ $m == Traceback* ]] && m=$(echo "$6" | grep -v '^ ' | tail -1)
  printf '%s | %s | %s | %s | %s | %s\n' "$1" "$2" "$3" "$4" "$5" "$(echo "$m" | cut -c1-200)"
  [ "$5" = ok ] || fail=1
}
# run CLASS CASE DIR TIMEOUT EXPECT_RC NEEDLE ALLOWED_NEW_FILES... -- cmd...
# EXPECT_RC: "12" = 1 or 2, "0" = success; NEEDLE must appear in stderr (the input named) unless "".
run() {
  local cls=$1 name=$2 dir=$3 to=$4 want=$5 needle=$6; shift 6
  local allowed=()
  while [ "$1" != "--" ]; do allowed+=("$1"); shift; done; shift
  (cd "$dir" && find . -mindepth 1 | sort > "$W/.before")
  local t0=$(date +%s.%N)
  (cd "$dir" && timeout -s KILL "$to" "$@" > "$W/.out" 2> "$W/.err"); local rc=$?
  local secs=$(echo "$(date +%s.%N) - $t0" | bc | xargs printf '%.1f')
  (cd "$dir" && find . -mindepth 1 | sort > "$W/.after")
  local new=$(comm -13 "$W/.before" "$W/.after" | sed 's|^\./||')
  local verdict=ok
  if [ $rc -eq 137 ]; then verdict="HANG"; elif [ $rc -ge 128 ]; then verdict="CRASH($rc)"; fi
  if [ "$verdict" = ok ]; then
    case $want in
      12) [ $rc -eq 1 ] || [ $rc -eq 2 ] || verdict="rc $rc, wanted 1 or 2" ;;
      0) [ $rc -eq 0 ] || verdict="rc $rc, wanted 0" ;;
    esac
  fi
  if [ "$verdict" = ok ] && [ -n "$needle" ] && ! grep -qF -- "$needle" "$W/.err"; then verdict="message lacks '$needle'"; fi
  if [ -n "$(find "$W" -name 'pwned*' 2> /dev/null)" ]; then verdict="COMMAND RAN"; fi
  while IFS= read -r f; do
    [ -n "$f" ] || continue
    local ok_file=0
    for a in "${allowed[@]}"; do [[ $f == $a ]] && ok_file=1; done
    [ $ok_file = 1 ] || verdict="left $f"
  done <<< "$new"
  report "$cls" "$name" "$rc" "$secs" "$verdict" "$(cat "$W/.err")"
}

# --- A: shell command through gnuplot titles
d=$W/A; mkdir -p $d; cp $K/gnuplot_backquote.toml $d/
run A "chart-geometry, scene name with backquotes" $d 120 0 "" 'out' 'out/*' -- $B chart-geometry --scene gnuplot_backquote.toml --out out -q
[ -s $d/out/geometry.png ] || report A "geometry.png drawn" - - "no PNG" ""
for c in chart-pressure chart-stability; do
  run A "$c, scene name with backquotes" $d 300 0 "" 'out*' 'out*/*' -- $B $c --scene gnuplot_backquote.toml --out out_$c -q
done
sed 's/name = "tiny"/name = "s`touch pwned_by_sim_name`$(touch pwned_dollar)@x"/; s/running_distance = 1e300/running_distance = 1000.0/' $K/sim_running_distance_huge.toml > $d/sim_name.toml
cp $K/sim_contact.toml $d/
run A "simulate, simulation name with backquotes, \$() and @" $d 600 0 "" 'simout' 'simout/*' -- $B simulate sim_name.toml --out simout --threads 2 -q --duration 0.05
n=$(grep -l '[`@]' $d/out*/*.gp $d/simout/*/*.gp 2> /dev/null | wc -l)
report A "gnuplot scripts holding a backquote or @" - - "$([ $n = 0 ] && echo ok || echo "$n scripts")" "$n of $(ls $d/out*/*.gp $d/simout/*/*.gp 2> /dev/null | wc -l)"

# --- B: --resume through a linked OUTPUT.partial
d=$W/B1; mkdir -p $d; cp $K/small.toml $d/; echo "precious data" > $d/victim.txt; ln -s victim.txt $d/out.h5.partial
run B "symlinked OUTPUT.partial" $d 120 12 "out.h5.partial" -- $B generate small.toml -o out.h5 --threads 1 --resume -q
grep -q "precious data" $d/victim.txt || report B "victim unchanged (symlink)" - - "VICTIM CHANGED" ""
d=$W/B2; mkdir -p $d; cp $K/small.toml $d/; echo "precious data" > $d/victim.txt; ln $d/victim.txt $d/out.h5.partial
run B "hard-linked OUTPUT.partial" $d 120 12 "out.h5.partial" -- $B generate small.toml -o out.h5 --threads 1 --resume -q
grep -q "precious data" $d/victim.txt || report B "victim unchanged (hard link)" - - "VICTIM CHANGED" ""

# --- C: -o one of the scene's profiles
d=$W/C; mkdir -p $d; cp $R/tests/data/profiles/{Car7216_0001r.whl,avg_HR.BAN} $d/
printf '[scene]\nname = "worn"\n[profiles]\nwheel = "Car7216_0001r.whl"\nrail = "avg_HR.BAN"\n[contact]\nnormal_model = "hertz"\n[grid]\ny = { start = -0.004, stop = 0.004, count = 3 }\nload = 80e3\n' > $d/worn.toml
sum=$(md5sum < $d/avg_HR.BAN)
run C "-o a profile of the scene" $d 120 12 "avg_HR.BAN" -- $B generate worn.toml -o avg_HR.BAN --threads 1 -q
[ "$(md5sum < $d/avg_HR.BAN)" = "$sum" ] || report C "profile unchanged" - - "PROFILE CHANGED" ""

# --- D: Python write_simpack
d=$W/D; mkdir -p $d; mkfifo $d/f.prw; echo precious > $d/victim.txt; ln -s victim.txt $d/z.prw.tmp
run D "write_simpack onto a FIFO" $d 60 12 "f.prw" -- env PYTHONPATH=$PY /usr/bin/python3 -c 'import railtab; railtab.Profile.s1002().write_simpack("f.prw")'
[ -p $d/f.prw ] || report D "FIFO left a FIFO" - - "FIFO REPLACED" ""
run D "write_simpack beside a planted z.prw.tmp link" $d 60 0 "" 'z.prw' -- env PYTHONPATH=$PY /usr/bin/python3 -c 'import railtab; railtab.Profile.s1002().write_simpack("z.prw")'
grep -q precious $d/victim.txt || report D "victim unchanged" - - "VICTIM CHANGED" ""

# --- E: --threads 100000
d=$W/E; mkdir -p $d; cp $K/small.toml $K/sim_contact.toml $d/; cp $K/sim_running_distance_huge.toml $d/sim.toml
run E "generate --threads 100000" $d 120 12 "--threads" -- $B generate small.toml -o t.h5 --threads 100000 -q
run E "simulate --threads 100000" $d 120 12 "--threads" -- $B simulate sim.toml --out o --threads 100000 -q
run E "generate --threads 1024 -q (capped, quiet)" $d 300 0 "" 't.h5' -- $B generate small.toml -o t.h5 --threads 1024 -q
[ -s $W/.err ] && report E "stderr empty with -q and --threads 1024" - - "stderr: $(head -c 200 $W/.err)" ""

# --- F: merge with a FIFO shard
d=$W/F; mkdir -p $d; cp $K/small.toml $d/
(cd $d && $B generate small.toml -o s1.h5 --shard 1/2 --threads 1 -q && $B generate small.toml -o s2.h5 --shard 2/2 --threads 1 -q && mkfifo s3.h5)
run F "merge m.h5 s1.h5 FIFO" $d 10 12 "s3.h5" -- $B merge m.h5 s1.h5 s3.h5 -q

# --- G: merged table answers as the single run near a jump
(cd $d && $B merge m.h5 s1.h5 s2.h5 -q && $B generate small.toml -o full.h5 --threads 1 -q)
g=ok
for y in 0.0003 -0.0003 0.0011 0.0029 -0.0031; do
  a=$(cd $d && $B query full.h5 --y $y --load 70000 --wheel left --json); b=$(cd $d && $B query m.h5 --y $y --load 70000 --wheel left --json | sed 's/"table": "m.h5"/"table": "full.h5"/')
  [ "$a" = "$b" ] || g="answers differ at y = $y"
done
report G "merged vs single run, query at 5 y incl. 0.3 mm" - - "$g" "$(cd $d && h5diff -q full.h5 m.h5 2>&1; h5diff --exclude-attribute / -q full.h5 m.h5 > /dev/null && echo 'h5diff --exclude-attribute /: identical')"
(cd $d && h5diff --exclude-attribute / -q full.h5 m.h5) || report G "h5diff --exclude-attribute / full.h5 m.h5" - - "DIFFER" ""

# --- H: writers never exit 0 with a table their lookup refuses
d=$W/H; mkdir -p $d; cp $K/scene_y_subnormal.toml $K/small.toml $d/
sed 's/count = 61/count = 601/' $K/big.toml > $d/big.toml  # 61 y nodes finish before the kill on this machine
run H "scene y = [0, 5e-324, 1e-323]" $d 120 12 "scene_y_subnormal.toml" -- $B generate scene_y_subnormal.toml -o sub.h5 --threads 1 -q
/usr/bin/python3 -c "
t=open('$d/small.toml').read().replace('name = \"small\"','name = \"small\"\ndescription = \"' + 'd'*1500000 + '\"'); open('$d/longdesc.toml','w').write(t)"
run H "1.5 MB description" $d 120 12 "longdesc.toml" -- $B generate longdesc.toml -o long.h5 --threads 1 -q
(cd $d && { $B generate big.toml -o big.h5 --threads 1 --resume -q & p=$!; sleep 2; kill -TERM $p; wait $p; } ) 2> /dev/null
if [ -f $d/big.h5.partial ]; then
  /usr/bin/python3 $K/ckpt_tamper.py $d/big.h5.partial $d/big.h5.partial nan 0
  run H "NaN checkpoint record, checksum recomputed" $d 600 12 "big.h5.partial" 'big.h5.partial' -- $B generate big.toml -o big.h5 --threads 2 --resume -q
else report H "NaN checkpoint record" - - "no checkpoint left (run finished too fast)" ""; fi

# --- I: monotone cubic near 1e306
d=$W/I; mkdir -p $d
run I "monotone-cubic on |values| ~ 1e306" $d 60 0 "" -- $B query $K/monotone_cubic_nan_rr1e306.h5 --y -0.004 --load 60000 --creepage -0.002,-0.001,0 --method monotone-cubic --wheel left --json
/usr/bin/python3 -c "
import json,math,sys; q=json.load(open('$W/.out'))['queries'][0]
bad=[k for c in q.get('contacts',[]) for k,v in c.items() if isinstance(v,float) and not math.isfinite(v)]
print('non-finite:', bad); sys.exit(1 if bad else 0)" > /dev/null || report I "every output finite" - - "NaN or inf in the answer" "$(head -c 300 $W/.out)"

# --- J: simulate with absurd time step or distance
d=$W/J; mkdir -p $d; cp $K/sim_*.toml $d/
run J "time_step = 1e-300" $d 20 12 "time_step" -- $B simulate sim_timestep_tiny.toml --out o1 --threads 1 -q --duration 0.001
run J "running_distance = 1e300" $d 60 12 "running_distance" -- $B simulate sim_running_distance_huge.toml --out o2 --threads 1 -q

# --- K: silent coercions
d=$W/K; mkdir -p $d; cp $W/F/full.h5 $d/
run K "--roll on an equilibrium-roll table" $d 30 12 "--roll" -- $B query full.h5 --y 0.001 --load 70000 --roll 0.005 --wheel left
run K "--y ''" $d 30 12 "--y" -- $B query full.h5 --y '' --load 70000 --wheel left
run K "--creepage 0.001,,0" $d 30 12 "--creepage" -- $B query full.h5 --y 0.001 --load 70000 --creepage 0.001,,0 --wheel left
for w in '2**32' '0.7'; do
  run K "Python wheel=$w" $d 30 1 "wheel" -- env PYTHONPATH=$PY /usr/bin/python3 -c "import railtab; railtab.Table.load('full.h5').query($w, y=0.001, load=70000)"
done
for s in '-1' '1.7'; do
  run K "Python slot=$s" $d 30 1 "slot" -- env PYTHONPATH=$PY /usr/bin/python3 -c "import railtab; railtab.Table.load('full.h5').query('left', y=0.001, load=70000, slot=$s)"
done
run K "Python path with a NUL" $d 30 1 "NUL" -- env PYTHONPATH=$PY /usr/bin/python3 -c "import railtab; railtab.Table.load('full.h5\0x')"
run K "Python Table(None)" $d 30 1 "path must be a file name" -- env PYTHONPATH=$PY /usr/bin/python3 -c "import railtab; railtab.Table(None)"
run K "Python Table('x.h5') missing" $d 30 1 "x.h5" -- env PYTHONPATH=$PY /usr/bin/python3 -c "import railtab; railtab.Table('x.h5')"

# --- L: errors that name the input
d=$W/L; mkdir -p $d; cp $K/small.toml $d/
sed 's/^\[contact\]/[material]\nyoungs_modulus = 1e300\n[contact]/' $K/small.toml > $d/e300.toml
run L "Young's modulus 1e300" $d 60 12 "material.youngs_modulus" -- $B generate e300.toml -o e.h5 --threads 1 -q
grep -q "\.tmp" $W/.err && report L "no .tmp named" - - "NAMES A TEMPORARY" "$(cat $W/.err)"
sed 's/^\[contact\]/[wear]\nhardness = 1e300\n[contact]/' $K/small.toml > $d/h300.toml
run L "hardness 1e300" $d 60 12 "wear.hardness" -- $B generate h300.toml -o h.h5 --threads 1 -q
mkfifo $d/t.h5
run L "query a FIFO table" $d 10 12 "t.h5': it is a FIFO" -- $B query t.h5 --y 0 --load 70000 --wheel left
run L "inspect a FIFO table" $d 10 12 "t.h5': it is a FIFO" -- $B inspect t.h5
run L "inspect a directory" $d 10 12 "it is a directory" -- $B inspect .
run L "chart-geometry -q: stderr" $d 120 0 "" 'c' 'c/*' -- $B chart-geometry --scene small.toml --out c -q
[ -s $W/.err ] && report L "gnuplot warnings silenced by -q" - - "stderr: $(head -c 200 $W/.err)" ""

# --- M: query memory per state
d=$W/M; mkdir -p $d
/usr/bin/python3 -c "
import random; random.seed(1)
with open('$d/states.txt','w') as f:
    f.write('y\n')
    for i in range(196000): f.write(f'{random.uniform(-0.004,0.004):.6g}\n')"
run M "196,000 states from a file" $d 300 0 "" -- /usr/bin/time -v $B query $W/F/full.h5 --states states.txt --load 70000 --wheel left --json
rss=$(grep "Maximum resident" $W/.err | awk '{print $NF}')
report M "peak RSS of 196,000 states [KiB]" - - ok "$rss KiB"
exit $fail
