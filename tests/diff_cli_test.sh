#!/usr/bin/env bash
# `fixstep diff A.rec B.rec`, end to end:
#   diff_cli_test.sh FIXSTEP SOURCE_DIR [AIRHOCKEY]
# - a recording against itself: exit 0, "identical";
# - one push flipped at tick 60 (its hashes left as recorded): exit 4, inputs first differ at
#   tick 60, the replayed states at tick 61, naming body 0 ("bob") and its field;
# - one stored hash edited at tick 31 (a peer whose state diverged): exit 4, equal inputs, the
#   hashes differ at 31 exactly, the verdict names the edited file's peer, either way round;
# - hashes every 10 ticks: the window of ticks is given;
# - another scene's recording: exit 6; recordings of a game's rules: compared without replay;
# - a missing file, a directory, a cut file: exit 5 naming the file; one argument: exit 2;
# - a game's --diff (airhockey, when built): replayed with its rules, the mallet named.
# Prints "ok - ..." / "FAIL - ...".
set -u
fixstep=$1
src=$2
airhockey=${3:-}
. "$(dirname "$0")/lib.sh"

diff_() {  # diff_ OUT A B: fixstep diff A B, stdout and stderr into OUT; returns its status
  local out=$1
  shift
  "$fixstep" diff "$@" >"$out" 2>&1
}

cd "$work" || exit 1
cp "$src/assets/scenes/default.toml" scene.toml
"$fixstep" run scene.toml --steps 300 --input "$src/assets/inputs/default_push.toml" \
  --record a.rec --hash-every 1 -q || { fail "run --record"; finish; }
"$fixstep" run scene.toml --steps 300 --input "$src/assets/inputs/default_push.toml" \
  --record sparse.rec --hash-every 10 -q || { fail "run --record --hash-every 10"; finish; }

diff_ same.out a.rec a.rec
[ $? -eq 0 ] && ok "a recording against itself: exit 0" || { fail "itself"; cat same.out; }
expect "it says identical" '^verdict: identical: equal inputs and stored hashes over 300 ticks$' same.out

sed 's/^tick 60 push=0,15 /tick 60 push=0,7.5 /' a.rec >flipped.rec
cmp -s a.rec flipped.rec && fail "flipped.rec unchanged"
diff_ flipped.out a.rec flipped.rec
[ $? -eq 4 ] && ok "a flipped input: exit 4" || { fail "flipped"; cat flipped.out; }
expect "the inputs first differ at tick 60" '^inputs: first differ at tick 60 \(equal before it\)$' flipped.out
expect "the replayed states first differ at tick 61 at a named body and field" \
  '^replayed here: the states first differ: body 0 \("bob"\) [a-z]+: .* m(/s)? \(bits 0x[0-9a-f]{16} against 0x[0-9a-f]{16}\) at tick 61$' \
  flipped.out
expect "the flipped recording's own hashes are not reproduced from tick 61" \
  '^flipped\.rec: its stored hashes are not reproduced here from tick 61 on' flipped.out
expect "an error line on standard error" '^fixstep: error: a\.rec and flipped\.rec differ: the inputs first differ at tick 60' flipped.out

sed 's/^hash 31 \(.\)/hash 31 f/' a.rec >desync.rec
[ "$(grep '^hash 31 ' a.rec | cut -c9)" = f ] && sed -i 's/^hash 31 f/hash 31 0/' desync.rec
cmp -s a.rec desync.rec && fail "desync.rec unchanged"
diff_ desync.out a.rec desync.rec
[ $? -eq 4 ] && ok "a peer's state diverged: exit 4" || { fail "desync"; cat desync.out; }
expect "equal inputs" '^inputs: equal over the 300 ticks both recorded$' desync.out
expect "the hashes first differ at tick 31, exactly" '^stored hashes: first differ at tick 31 \(exact: equal at tick 30\)$' desync.out
expect "the verdict names the diverged peer" \
  "the state of desync\.rec's peer diverged at tick 31, not its inputs" desync.out
diff_ desync_swapped.out desync.rec a.rec
expect "either way round" "a\.rec's hashes are reproduced here, desync\.rec's are not from tick 31 on" \
  desync_swapped.out

sed 's/^hash 40 \(.\)/hash 40 f/' sparse.rec >sparse_desync.rec
[ "$(grep '^hash 40 ' sparse.rec | cut -c9)" = f ] && sed -i 's/^hash 40 f/hash 40 0/' sparse_desync.rec
diff_ sparse.out sparse.rec sparse_desync.rec
[ $? -eq 4 ] && ok "hashes every 10 ticks: exit 4" || { fail "sparse"; cat sparse.out; }
expect "the window of ticks" 'first differ at tick 40, equal at tick 30: the states first differ in ticks 31 \.\. 40' sparse.out

sed 's/mass = 1.0/mass = 2.0/' scene.toml >other.toml
"$fixstep" run other.toml --steps 300 --record other.rec -q
diff_ other.out a.rec other.rec
[ $? -eq 6 ] && ok "another scene's recording: exit 6" || { fail "other scene"; cat other.out; }
expect "it says the worlds differ" 'error: a\.rec and other\.rec differ: their worlds differ: definition hash' other.out

# A game's recordings: the rules line added (format 4), one of them with a hash edited.
sed '1s/ 3$/ 4/;/^hash_every /a rules slingshot 1' a.rec >rules.rec
sed '1s/ 3$/ 4/;/^hash_every /a rules slingshot 1' desync.rec >rules_desync.rec
diff_ rules.out rules.rec rules_desync.rec
[ $? -eq 4 ] && ok "a game's recordings that differ: exit 4" || { fail "rules"; cat rules.out; }
expect "compared without replay, the game's --diff named" \
  'note: rules\.rec needs the game rules slingshot.*run the game with --diff rules\.rec rules_desync\.rec' rules.out
expect "their hashes compared" '^stored hashes: first differ at tick 31' rules.out

diff_ missing.out missing.rec a.rec
[ $? -eq 5 ] && ok "a missing recording: exit 5" || { fail "missing"; cat missing.out; }
expect "it names the file" 'missing\.rec: no such recording' missing.out
mkdir adir
diff_ dir.out a.rec adir
[ $? -eq 5 ] && ok "a directory: exit 5" || { fail "directory"; cat dir.out; }
head -c 300 a.rec >cut.rec
diff_ cut.out cut.rec a.rec
[ $? -eq 5 ] && ok "a cut recording: exit 5" || { fail "cut"; cat cut.out; }
expect "it names the cut file" '^fixstep: error: cut\.rec' cut.out
diff_ one.out a.rec
[ $? -eq 2 ] && ok "one recording only: exit 2" || { fail "one argument"; cat one.out; }

if [ -n "$airhockey" ]; then
  "$airhockey" --frames 100 --record ah.rec >/dev/null 2>&1 || fail "airhockey --record"
  # body slot 3's kinematic velocity at tick 100 changed (bodies() index 2, "mallet1")
  sed '/^tick 100 /s/velocity=3:1,[-0-9.e]*,/velocity=3:1,1.5,/' ah.rec >ah_input.rec
  cmp -s ah.rec ah_input.rec && fail "ah_input.rec unchanged"
  "$airhockey" --diff ah.rec ah_input.rec >ah.out 2>&1
  [ $? -eq 4 ] && ok "airhockey --diff of recordings that differ: exit 4" || { fail "airhockey --diff"; cat ah.out; }
  expect "airhockey --diff names the mallet" \
    '^replayed here: the states first differ: body 2 \("mallet1"\) x: .* at tick 101$' ah.out
  "$airhockey" --diff ah.rec ah.rec >ah_same.out 2>&1
  [ $? -eq 0 ] && ok "airhockey --diff of a recording and itself: exit 0" || { fail "airhockey itself"; cat ah_same.out; }
  expect "with the rules, the game's hashes are reproduced" \
    '^ah\.rec: its stored hashes are reproduced here \([0-9]+ stored hashes through tick [0-9]+\)$' ah_same.out
  "$airhockey" --diff ah.rec a.rec >ah_other.out 2>&1
  [ $? -eq 1 ] && ok "airhockey --diff of fixstep's recording: exit 1" || { fail "airhockey other"; cat ah_other.out; }
fi

finish
