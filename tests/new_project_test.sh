#!/usr/bin/env bash
# `fixstep new` as a new user meets it: the installed fixstep writes a
# project, which builds against the installed package (found through PATH, as after an
# install), renders headless, records the autopilot's actions, and replays it: a replay
# verifies, a tampered recording is refused naming the tick where the states part, and `new`
# refuses a directory that is not empty. Run by examples/consumer/check.sh (.ci/run) with the
# prefix it installed into.
# Usage: bash tests/new_project_test.sh BUILD_DIR [PREFIX]
#   BUILD_DIR: a configured and built fixstep tree; PREFIX: where it is already installed
#   (default: installed here into a temporary prefix).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: new_project_test.sh BUILD_DIR [PREFIX]}" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "new_project: FAIL: $*" >&2; exit 1; }
prefix=${2:-}
if [[ -z $prefix ]]; then
  prefix=$work/prefix
  cmake --install "$build" --prefix "$prefix" >/dev/null
fi
export PATH="$prefix/bin:$PATH"
cd "$work"

# 1. The project: the template's files, byte for byte, named after the directory.
fixstep new grabber > new.log || fail "fixstep new grabber: $(cat new.log)"
for f in main.cpp scene.toml; do
  cmp -s "$src/cli/template/$f" "grabber/$f" || fail "grabber/$f is not the template's"
done
grep -q '^project(grabber LANGUAGES CXX)' grabber/CMakeLists.txt ||
  fail "grabber/CMakeLists.txt does not name the project grabber"
grep -q 'cmake -B build && cmake --build build' new.log || fail "new printed no build command"
echo "new_project: fixstep new grabber: $(head -1 new.log)"

# 1b. The template is as long as docs/LIBRARY.md says, and every member of its game type is used
# somewhere besides its declaration (no member declared and left unused).
lines=$(wc -l <"$src/cli/template/main.cpp")
grep -q "a \`main.cpp\` ($lines lines)" "$src/docs/LIBRARY.md" ||
  fail "docs/LIBRARY.md does not say main.cpp is $lines lines: $(grep -o 'main.cpp` ([0-9]* lines)' "$src/docs/LIBRARY.md")"
members=$(sed -n '/^struct Catch {/,/^  void setup/p' "$src/cli/template/main.cpp" |
  grep -E '^  [A-Za-z_:<>]+ [a-z_]' | grep -v '(' | sed -E 's/^  [A-Za-z_:<>]+ //; s/\/\/.*//; s/[{}=;]|[0-9]+//g; s/,/ /g')
[[ -n $members ]] || fail "no members found in the template's game type"
for m in $members; do
  uses=$(grep -ow "$m" "$src/cli/template/main.cpp" | wc -l)
  ((uses >= 2)) || fail "the template declares $m and never uses it"
done
echo "new_project: main.cpp $lines lines; members used: $(echo $members)"

# 2. It builds against the installed package as its README says (cmake finds fixstep by PATH).
(cd grabber && cmake -B build -G Ninja >cmake.log 2>&1 && cmake --build build >>cmake.log 2>&1) ||
  fail "the project does not build: $(tail -20 grabber/cmake.log)"
game=$work/grabber/build/grabber

# 3. Headless frames: 60 PNGs that move and are more than one colour (a one-colour 1280x720
# frame deflates to under 20 KB even at zlib's fastest level; this scene's are 45 KB and more).
"$game" --out frames --frames 60 > render.log || fail "grabber --out: $(cat render.log)"
[[ $(ls frames | grep -c '^frame_[0-9]*\.png$') == 60 ]] || fail "expected 60 frames: $(ls frames)"
cmp -s frames/frame_000000.png frames/frame_000059.png && fail "frame 59 is frame 0: nothing moved"
for f in frames/frame_000000.png frames/frame_000059.png; do
  [[ $(head -c 4 "$f" | od -An -c | tr -d ' ') == '211PNG' ]] || fail "$f is not a PNG"
  (($(stat -c %s "$f") > 30000)) || fail "$f is $(stat -c %s "$f") bytes: blank?"
done
echo "new_project: grabber --out frames --frames 60: 60 PNGs"

# 4. A headless recording of the autopilot holds the game's walk axis both ways and presses of
# its jump action (bit 0).
"$game" --frames 300 --record r.rec > record.log || fail "grabber --record: $(cat record.log)"
for walk in " axis.0=1$" " axis.0=-1$" " pressed=1 "; do
  grep -Eq -- "$walk" r.rec || fail "the recording holds no '$walk' (the walk axis, the jump)"
done

# 5. It replays: every stored hash verified, exit 0.
"$game" --replay r.rec > replay.log || fail "grabber --replay r.rec: $(cat replay.log)"
grep -Eq '^verified=[0-9]+$' replay.log || fail "replay printed $(cat replay.log)"
grep -Fxq "$(grep '^caught=' record.log)" replay.log || fail "the replay's score is not the run's"
echo "new_project: $(head -1 record.log); $(tr '\n' ' ' < replay.log)"

"$game" --frames 300 --sync-test 8 > sync.log || fail "grabber --sync-test 8: $(cat sync.log)"
grep -q '^sync test: .*: the same$' sync.log || fail "the sync test printed $(cat sync.log)"
grep -Fxq "$(grep '^ticks=' record.log)" sync.log || fail "the sync test's state is not the run's"
"$game" --help | grep -q -- '--replay FILE' || fail "--help does not list --replay FILE"
echo "new_project: $(tail -1 sync.log)"

# 6. A tampered copy (the first tick after tick 0 that walks right made to walk left) is
# refused, naming the tick after the tampered one: the first state that differs.
line=$(grep -m1 -E '^tick [1-9][0-9]* .* axis\.0=1$' r.rec) || fail "no walk right after tick 0"
tick=$(awk '{print $2}' <<<"$line")
sed "s/^\(tick $tick .*\) axis\.0=1$/\1 axis.0=-1/" r.rec > tampered.rec
cmp -s r.rec tampered.rec && fail "the tampering changed nothing"
status=0
"$game" --replay tampered.rec > /dev/null 2> tampered.log || status=$?
[[ $status == 4 ]] || fail "the tampered replay exited $status, not 4: $(cat tampered.log)"
grep -q "diverged at tick $((tick + 1)):" tampered.log ||
  fail "the tampered replay does not name tick $((tick + 1)): $(cat tampered.log)"
echo "new_project: tampered at tick $tick: $(cat tampered.log)"

# 7. A recording cut short is refused with the reader's message.
head -n 20 r.rec > cut.rec
status=0
"$game" --replay cut.rec > /dev/null 2> cut.log || status=$?
[[ $status == 1 ]] && grep -q 'cut short' cut.log || fail "a cut recording: $status $(cat cut.log)"

# 7b. The recording names its rules (the program and its rules version): `fixstep replay` and
# `fixstep render --replay`, which have none of the game's rules, refuse it (exit 5) naming the
# program, writing nothing; the game refuses a recording of another rules version (exit 1).
grep -qx 'rules grabber 1' r.rec || fail "the recording does not name its rules: $(sed -n 1,12p r.rec)"
for cmd in "replay r.rec" "render --replay r.rec --out rules_frames"; do
  status=0
  fixstep $cmd > /dev/null 2> rules.log || status=$?
  [[ $status == 5 ]] && grep -q 'recorded by grabber with its game rules (version 1)' rules.log ||
    fail "fixstep $cmd: exit $status, $(cat rules.log)"
done
[[ ! -e rules_frames ]] || fail "render --replay of a rules recording wrote frames"
sed 's/^rules grabber 1$/rules grabber 2/' r.rec > newer_rules.rec
status=0
"$game" --replay newer_rules.rec > /dev/null 2> newer.log || status=$?
[[ $status == 1 ]] && grep -q 'needs the rules grabber version 2, and this program has grabber version 1' newer.log ||
  fail "a recording of other rules: exit $status, $(cat newer.log)"
echo "new_project: rules named and checked: $(cat rules.log)"

# 8. `fixstep new` into the existing, non-empty project: refused, naming it; nothing changed.
before=$(cd grabber && ls -l --time-style=full-iso main.cpp scene.toml CMakeLists.txt README.md)
status=0
fixstep new grabber > /dev/null 2> again.log || status=$?
[[ $status == 1 ]] && grep -q 'grabber is not empty' again.log ||
  fail "fixstep new on a non-empty directory: exit $status, $(cat again.log)"
[[ $(cd grabber && ls -l --time-style=full-iso main.cpp scene.toml CMakeLists.txt README.md) == "$before" ]] ||
  fail "fixstep new touched the existing project"
echo "new_project: OK (new, build against the install, render, record, replay, tampered refused)"
