#!/usr/bin/env bash
# One binary, one answer whatever the CPU's optional instructions. glibc x86-64 picks
# an FMA variant of exp on CPUs with FMA and a non-FMA one under
# GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA; they round exp(-2.73/120) (the Verlet damping factor of
# tests/scenes/cross/damped_exp.toml) 1 ulp apart, so a state that used the libm's exp got two
# hashes here. fixstep::det::exp gives one. Also runs the loader's hypot cause scene both ways.
#   fma_exp_test.sh FIXSTEP SOURCE_DIR
set -u
fixstep=$1 src=$2
. "$(dirname "$0")/lib.sh"
field() { grep -Eo "(^| )$1=[^ ]+" | head -1 | cut -d= -f2; }  # field NAME < line

for case in "damped_exp.toml 600" "hypot_rest.toml 1000"; do
  set -- $case
  scene=$src/tests/scenes/cross/$1 steps=$2
  fma=$("$fixstep" run "$scene" --steps "$steps" | field state_hash)
  plain=$(GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA "$fixstep" run "$scene" --steps "$steps" |
    field state_hash)
  [ -n "$fma" ] && [ "$fma" = "$plain" ] \
    && ok "$1 at $steps ticks: one hash with FMA exp and without ($fma)" \
    || fail "$1 at $steps ticks: hash $fma with FMA, $plain with hwcaps=-FMA"
done
finish
