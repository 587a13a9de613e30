#!/usr/bin/env bash
# Replays that are verified and self-contained, end to end:
#   replay_verify_test.sh FIXSTEP SOURCE_DIR
# - `render --replay` verifies every stored hash before its first frame: a recording with a
#   flipped input bit exits 4 naming the file, the tick and both hashes, and writes nothing;
# - flags that would change the recorded world or its stepping are refused with --replay (2);
# - a recording carries its scene (format 3): it replays and renders after the scene file is
#   deleted or edited; --scene still picks a file, saying so; a damping split is recorded;
# - an embedded scene cut short, edited, not loading or of another world: exit 5, located;
# - a version 2 recording (tests/golden/recordings) replays by its scene path as before.
# Prints "ok - ..." / "FAIL - ...".
set -u
fixstep=$1
src=$2
. "$(dirname "$0")/lib.sh"

run_() {  # run_ OUT ARGS...: fixstep ARGS, stdout and stderr into OUT; returns its status
  local out=$1
  shift
  "$fixstep" "$@" >"$out" 2>&1
}

# FNV-1a (64-bit) of a file's bytes, 16 hex digits: the checksum of an embedded scene.
fnv1a() {
  python3 -c 'import sys
h = 14695981039346656037
for b in open(sys.argv[1], "rb").read():
    h = ((h ^ b) * 1099511628211) % 2**64
print(f"{h:016x}")' "$1"
}
# with_scene REC SCENE OUT: REC with its embedded scene replaced by SCENE's bytes (one line per
# line, a valid section: size and checksum recomputed; SCENE ends with a newline, has no '\' or
# control character).
with_scene() {
  {
    sed -n '1,2p' "$1"
    echo "scene_text $(wc -c <"$2") $(fnv1a "$2")"
    sed 's/^/|/' "$2"
    sed -n '/^definition /,$p' "$1"
  } >"$3"
}

mkdir -p "$work/s" "$work/elsewhere"
cp "$src/assets/scenes/default.toml" "$work/s/scene.toml"
(cd "$work/s" && "$fixstep" run scene.toml --steps 300 --input "$src/assets/inputs/default_push.toml" \
  --record session.rec --hash-every 1 >"$work/run.out" 2>&1) || { fail "run --record"; cat "$work/run.out"; finish; }
recorded=$(hash_of "$work/run.out")
rec=$work/s/session.rec
head -1 "$rec" | grep -qx 'fixstep-recording 3' && ok "run --record writes format 3" || fail "format: $(head -1 "$rec")"

# --- render --replay verifies every stored hash before drawing --------------------------------
# one bit of the push at tick 60 flipped (15 -> 7.5): the state after 61 ticks differs; the
# two frames rendered reach tick 2 only, so only verifying the whole recording finds it
sed 's/^tick 60 push=0,15 /tick 60 push=0,7.5 /' "$rec" >"$work/flipped.rec"
cmp -s "$rec" "$work/flipped.rec" && fail "flipped.rec unchanged"
run_ "$work/flip_render.out" render --replay "$work/flipped.rec" --out "$work/flip_frames" --frames 2 --size 64x36
[ $? -eq 4 ] && ok "render --replay of a flipped input bit exits 4" || { fail "render --replay of a flipped bit"; cat "$work/flip_render.out"; }
expect "render --replay names the file, the tick and both hashes" \
  'flipped\.rec: replay diverged at tick 61: state_hash [0-9a-f]{16} recorded, [0-9a-f]{16} replayed \(the states matched at tick 60\); the recording was edited' \
  "$work/flip_render.out"
expect "render --replay says what it wrote" 'nothing was written' "$work/flip_render.out"
[ ! -e "$work/flip_frames" ] && ok "no frame directory for a diverging recording" || fail "frames written: $(ls "$work/flip_frames")"
run_ "$work/flip_video.out" render --replay "$work/flipped.rec" --video "$work/flip.mp4" --frames 2 --size 64x36
[ $? -eq 4 ] && [ ! -e "$work/flip.mp4" ] && [ ! -e "$work/flip.mp4.frames.csv" ] \
  && ok "render --replay --video of a diverging recording: exit 4, no video" || { fail "video of a diverging recording"; ls "$work"; }
run_ "$work/flip_replay.out" replay "$work/flipped.rec"
[ $? -eq 4 ] && ok "replay of the flipped bit exits 4" || fail "replay of the flipped bit"
expect "replay names the file too" 'flipped\.rec: replay diverged at tick 61:' "$work/flip_replay.out"

# --- flags that would change the recorded world are refused -----------------------------------
for flag in "--dt 0.02" "--integrator rk4" "--precision f32" "--substeps 2" "--damping-split per_step"; do
  # shellcheck disable=SC2086 # the flag and its value
  run_ "$work/flag.out" render --replay "$rec" --out "$work/flag_frames" --frames 2 --size 64x36 $flag
  status=$?
  name=${flag%% *}
  [ $status -eq 2 ] && grep -q "^fixstep render: $name cannot be used with --replay: a recording replays the world it was recorded with" "$work/flag.out" \
    && [ ! -e "$work/flag_frames" ] && ok "render --replay $flag: exit 2 naming $name" \
    || { fail "render --replay $flag: exit $status"; cat "$work/flag.out"; }
done
run_ "$work/ok_flags.out" render --replay "$rec" --out "$work/ok_flags" --frames 2 --size 64x36 --allow-unstable -q
[ $? -eq 0 ] && ok "render --replay takes --allow-unstable and --quiet (they change no state)" || { fail "allowed flags"; cat "$work/ok_flags.out"; }

# --- the recording carries its scene ----------------------------------------------------------
sed 's/^mass = 1.0 /mass = 1.5 /' "$work/s/scene.toml" >"$work/s/edited.toml"
cmp -s "$work/s/scene.toml" "$work/s/edited.toml" && fail "edited.toml unchanged"
cp "$work/s/edited.toml" "$work/s/scene.toml"
(cd "$work/s" && run_ "$work/edited.out" replay session.rec)
[ $? -eq 0 ] && [ "$(hash_of "$work/edited.out")" = "$recorded" ] \
  && ok "a recording replays after its scene file is edited (the recorded state)" || { fail "replay after an edit"; cat "$work/edited.out"; }
rm "$work/s/scene.toml"
(cd "$work/elsewhere" && run_ "$work/deleted.out" replay ../s/session.rec)
[ $? -eq 0 ] && [ "$(hash_of "$work/deleted.out")" = "$recorded" ] \
  && ok "a recording replays after its scene file is deleted" || { fail "replay after deletion"; cat "$work/deleted.out"; }
expect "the summary names the scene as recorded" '^scene=scene\.toml integrator=semi_implicit_euler' "$work/deleted.out"
(cd "$work/elsewhere" && run_ "$work/deleted_render.out" render --replay ../s/session.rec \
  --out "$work/deleted_frames" --frames 20 --size 64x36)
[ $? -eq 0 ] && ok "render --replay works without the scene file" || { fail "render --replay without the file"; cat "$work/deleted_render.out"; }
awk 'NR == FNR { if ($1 == "hash") h[$2] = $3; next }
     FNR > 1 { split($0, f, ","); if (f[2] > 0) { n++; if (h[f[2]] != f[5]) bad++ } }
     END { exit !(n >= 19 && bad == 0) }' "$rec" FS=, "$work/deleted_frames/frames.csv" \
  && ok "its frames are of the recorded states (frames.csv hashes)" || fail "render --replay hashes"
run_ "$work/explicit.out" replay "$rec" --scene "$work/s/edited.toml"
[ $? -eq 6 ] && ok "--scene FILE is used instead of the carried scene (edited: exit 6)" || { fail "--scene"; cat "$work/explicit.out"; }
expect "--scene says which scene is used" 'note: .*session\.rec carries the scene it was recorded with \(scene\.toml\); replaying with .*edited\.toml, given on the command line, instead' "$work/explicit.out"
expect "the mismatch says the recording carries its scene" 'without --scene: the recording carries it' "$work/explicit.out"

# --- a damping split given on the command line is recorded ------------------------------------
cp "$src/assets/scenes/default.toml" "$work/s/scene.toml"
(cd "$work/s" && run_ "$work/split_run.out" run scene.toml --steps 50 --damping-split per_step --record split.rec)
(cd "$work/s" && run_ "$work/split.out" replay split.rec)
[ $? -eq 0 ] && [ "$(hash_of "$work/split.out")" = "$(hash_of "$work/split_run.out")" ] \
  && ok "run --damping-split per_step --record replays" || { fail "damping split replay"; cat "$work/split.out"; }

# --- a bad embedded scene is a bad recording (exit 5), located --------------------------------
first_scene=$(grep -n '^|' "$rec" | head -1 | cut -d: -f1)
head -n $((first_scene + 5)) "$rec" >"$work/cut.rec"
run_ "$work/cut.out" replay "$work/cut.rec"
[ $? -eq 5 ] && ok "an embedded scene cut short: exit 5" || { fail "cut scene"; cat "$work/cut.out"; }
expect "the cut is located" "cut\\.rec:$((first_scene + 5)): scene_text: the file ends inside the embedded scene \\([0-9]+ of its [0-9]+ bytes read\\): the recording was cut short" "$work/cut.out"
sed "$((first_scene + 3))s/^|/|x/" "$rec" >"$work/byte.rec"
run_ "$work/byte.out" replay "$work/byte.rec"
[ $? -eq 5 ] && ok "an embedded scene with a byte changed: exit 5" || { fail "changed byte"; cat "$work/byte.out"; }
expect "the changed byte is located" "byte\\.rec:[0-9]+: scene_text: the embedded scene's bytes do not match its checksum \\(FNV-1a [0-9a-f]{16} recorded, [0-9a-f]{16} read\\)" "$work/byte.out"
printf '[world]\ndt = 0.01\n[[body]]\nmass = -1.0\nposition = [0.0, 0.0]\n' >"$work/broken.toml"
with_scene "$rec" "$work/broken.toml" "$work/broken.rec"
run_ "$work/broken.out" replay "$work/broken.rec"
[ $? -eq 5 ] && ok "an embedded scene that does not load: exit 5" || { fail "broken scene"; cat "$work/broken.out"; }
expect "its error is the scene's, located in the recording" 'broken\.rec: scene_text: the scene it carries does not load: scene\.toml \(embedded in .*broken\.rec\):4:8: body\[0\]\.mass: must be > 0' "$work/broken.out"
with_scene "$rec" "$work/s/edited.toml" "$work/other.rec"
run_ "$work/other.out" replay "$work/other.rec"
[ $? -eq 5 ] && ok "an embedded scene of another world: exit 5 (the recording is bad, not the scene)" || { fail "other world"; cat "$work/other.out"; }
expect "the other world is named by both hashes" 'other\.rec: scene_text: the scene it carries builds another world than the one recorded \(definition hash [0-9a-f]{16}, recorded [0-9a-f]{16}\)' "$work/other.out"
run_ "$work/other_render.out" render --replay "$work/other.rec" --out "$work/other_frames" --frames 2 --size 64x36
[ $? -eq 5 ] && [ ! -e "$work/other_frames" ] && ok "render --replay refuses it too, writing nothing" || fail "render --replay of another world"

# --- a version 2 recording replays by its scene path, as before --------------------------------
golden=$src/tests/golden/recordings/default_push_v2.rec
head -1 "$golden" | grep -qx 'fixstep-recording 2' && ok "the golden recording is format 2" || fail "golden format"
(cd "$src" && run_ "$work/v2.out" replay tests/golden/recordings/default_push_v2.rec)
[ $? -eq 0 ] && ok "a version 2 recording replays (scene by path)" || { fail "v2 replay"; cat "$work/v2.out"; }
expect "with every hash and its final state" '^verified 31 hashes, ticks=300 state_hash=29f421ea60325834$' "$work/v2.out"
expect "from the file it names" '^scene=assets/scenes/default\.toml ' "$work/v2.out"
(cd "$src" && run_ "$work/v2_render.out" render --replay tests/golden/recordings/default_push_v2.rec \
  --out "$work/v2_frames" --frames 2 --size 64x36)
[ $? -eq 0 ] && ok "render --replay of a version 2 recording" || { fail "v2 render"; cat "$work/v2_render.out"; }
sed 's/^scene .*/scene gone.toml/' "$golden" >"$work/gone.rec"
run_ "$work/gone.out" replay "$work/gone.rec"
[ $? -eq 1 ] && ok "a version 2 recording whose scene is gone: exit 1" || { fail "v2 gone"; cat "$work/gone.out"; }
expect "it says the recording does not carry its scene" 'the recording.s scene gone\.toml is not there .*does not carry it .*give it with --scene FILE' "$work/gone.out"

finish
