#!/usr/bin/env bash
# End-to-end checks of the integration_basics demo: files, the article's tables digit for
# digit, and the measured numbers of the captions against theory (computed here in awk,
# independently of the demo).
#   integration_basics_test.sh INTEGRATION_BASICS
# Each check prints "ok - ..." or "FAIL - ..."; the script exits non-zero if any failed.
set -u
demo=$1
. "$(dirname "$0")/lib.sh"

out=$work/out
"$demo" --out "$out" --size 640x360 >"$work/stdout" 2>"$work/stderr"
[ $? -eq 0 ] && ok "headless run exits 0" || { fail "headless run"; cat "$work/stderr"; }

# --- files --------------------------------------------------------------------------------
for f in a_exact_damped b_explicit_euler_damped c_semi_implicit_damped d_rk4_vs_semi_implicit_zoom \
         d_error_damped e_undamped_dt0.1_last5s e_undamped_dt0.1_energy f_undamped_dt0.25_rk4 \
         f_undamped_dt0.25_semi_implicit f_undamped_dt0.25_energy; do
  png=$out/$f.png
  # PNG signature, then IHDR width and height (big-endian) at bytes 16..23.
  if [ -s "$png" ] && [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] &&
     [ "$(od -An -tu1 -j16 -N8 "$png" | tr -s ' ' | sed 's/^ //')" = "0 0 2 128 0 0 1 104" ]; then
    ok "$f.png is a 640x360 PNG"
  else
    fail "$f.png missing or not 640x360"
  fi
done
for f in constant_force.md constant_force_dt1.csv constant_force_dt0.01.csv numbers.txt; do
  [ -s "$out/$f" ] && ok "$f written" || fail "$f missing"
done
ls "$out" | grep -q '\.tmp' && fail "temporary files left behind" || ok "no temporary files left"

# --- the constant-force tables ("Integration Basics": explicit Euler, float) ----------------
# dt = 1 s: the article's t=10 row is position 450, velocity 100 (exact: 500); semi-implicit 550.
grep -qx '10,450,100,550,100,500,100' "$out/constant_force_dt1.csv" \
  && ok "dt = 1 s at t = 10: explicit 450/100, semi-implicit 550/100, exact 500/100" \
  || fail "dt = 1 s table row t = 10"
expect_text "markdown table row t = 3 (article: position 30 velocity 30)" "| 3 | 30 | 30 | 60 | 30 | 45 | 30 |" "$work/stdout"
# dt = 1/100 s: the article's eleven printed rows, digit for digit.
while read -r t x v; do
  expect_text "article row t=$t: position = $x velocity = $v" "| $t | $x | $v |" "$work/stdout"
done <<'EOF'
9.90 489.552155 98.999062
9.91 490.542145 99.099060
9.92 491.533142 99.199059
9.93 492.525146 99.299057
9.94 493.518127 99.399055
9.95 494.512115 99.499054
9.96 495.507111 99.599052
9.97 496.503113 99.699051
9.98 497.500092 99.799049
9.99 498.498077 99.899048
10.00 499.497070 99.999046
EOF

# --- the measured numbers against theory --------------------------------------------------
num() { awk -F'[= ]' -v k="$1" '$1 == k { print $2; found = 1 } END { exit !found }' "$out/numbers.txt"; }
# check NAME MEASURED THEORY TOLERANCE [rel]: |measured - theory| <= tolerance (relative if "rel")
check() {
  if awk -v m="$2" -v t="$3" -v tol="$4" -v rel="${5:-}" 'BEGIN {
        d = m - t; if (d < 0) d = -d; s = t < 0 ? -t : t
        exit !(m != "" && (rel == "rel" ? d <= tol * s : d <= tol)) }'; then
    ok "$1: $2 (theory $3, tolerance $4${5:+ relative})"
  else
    fail "$1: measured '$2', theory $3, tolerance $4${5:+ relative}"
  fi
}
w2=15  # omega^2 = k/m, 1/s^2, the article's spring
# (b) explicit Euler on the damped spring: energy grows by |1 + dt*lambda|^2 = 1 - dt*b/m + dt^2*k/m
# per tick (lambda = -b/2m +- i*omega_d); measured as the slope of ln E (the energy also oscillates
# within each period, so one ratio would be off by ~1 %).
check "(b) explicit Euler energy growth per tick" "$(num b.explicit_growth_per_tick)" \
  "$(awk -v w2=$w2 'BEGIN { printf "%.12f", 1 - 0.01 * 0.1 + 0.0001 * w2 }')" 1e-6
awk -v e="$(num b.explicit_energy_ratio)" -v x="$(num a.exact_energy_ratio)" 'BEGIN { exit !(e > 1 && x < 1) }' \
  && ok "(b) explicit Euler ends above E0 where the exact solution has lost energy" || fail "(b) energy gain"
# (c)/(d) semi-implicit Euler is first order: its first step puts it about omega*dt/2 ahead in phase,
# a leading-order estimate of its largest error of x0*omega*dt/2 = 19.4 m (5 %); RK4 far below.
check "(c) semi-implicit largest error ~ x0*omega*dt/2" "$(num c.semi_implicit_max_error)" \
  "$(awk -v w2=$w2 'BEGIN { printf "%.6f", 1000 * sqrt(w2) * 0.01 / 2 }')" 0.05 rel
awk -v r="$(num d.rk4_max_error)" -v s="$(num d.semi_implicit_max_error)" 'BEGIN { exit !(r < 1e-3 && s / r > 1e4) }' \
  && ok "(d) RK4's largest error is below 1 mm and 10^4 times smaller" || fail "(d) RK4 vs semi-implicit error"
# (e), (f) undamped over 90 s at dt = 0.1 and 0.25, theta = omega*dt:
#   RK4 energy ratio = |R(i theta)|^(2n), R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24; phase n*(arg R - theta)
#   semi-implicit frequency ratio = acos(1 - theta^2/2)/theta; mean energy E0/(1 - theta^2/4)
for fig in e f; do
  dt=$(num $fig.dt) n=$(num $fig.ticks)
  theory=$(awk -v w2=$w2 -v dt="$dt" -v n="$n" 'BEGIN {
    th = sqrt(w2) * dt; re = 1 - th^2/2 + th^4/24; im = th - th^3/6
    c = 1 - th^2/2; acos = atan2(sqrt(1 - c*c), c)
    printf "%.15g %.15g %.15g %.15g", (re*re + im*im)^n, n * (atan2(im, re) - th), acos / th, 1 / (1 - th^2/4) }')
  set -- $theory
  check "($fig) dt=$dt RK4 energy after 90 s = |R(i omega dt)|^(2n)" "$(num $fig.rk4_energy_ratio)" "$1" 1e-9 rel
  check "($fig) dt=$dt RK4 phase after 90 s = n (arg R - omega dt)" "$(num $fig.rk4_phase_error)" "$2" 1e-9
  check "($fig) dt=$dt semi-implicit frequency = acos(1 - (omega dt)^2/2)/(omega dt)" \
    "$(num $fig.semi_implicit_frequency_ratio)" "$3" 1e-5 rel
  check "($fig) dt=$dt semi-implicit mean energy = E0/(1 - (omega dt)^2/4)" \
    "$(num $fig.semi_implicit_energy_mean)" "$4" 1e-3 rel
  check "($fig) dt=$dt semi-implicit energy does not drift (second half vs first)" \
    "$(num $fig.semi_implicit_energy_mean_second_half)" "$(num $fig.semi_implicit_energy_mean_first_half)" 2e-3 rel
done
# The captions print these same numbers.
expect_text "caption states RK4's energy after 90 s at dt = 0.25" \
  "energy $(awk -v v="$(num f.rk4_energy_ratio)" 'BEGIN { printf "%.4f", v }') E0 (theory |R(i*omega*dt)|^(2n) = $(awk -v v="$(num f.rk4_energy_theory)" 'BEGIN { printf "%.4f", v }'))" \
  "$work/stdout"

# --- the window ---------------------------------------------------------------------------
env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER "$demo" --window --frames 1 >"$work/nodisp" 2>&1
[ $? -ne 0 ] && ok "--window without a display exits non-zero" || fail "--window without a display"
expect_text "--window without a display says so" "--window needs a display" "$work/nodisp"
if have_xvfb; then
  # 30 frames of a 60 fps virtual clock at time scale 4: 29 frames advance 29/60*4 s = 1.93 s,
  # 19 ticks of 0.1 s.
  with_xvfb "$demo" --window --frames 30 --fps 60 --speed 4 \
    --size 640x360 >"$work/window" 2>&1
  [ $? -eq 0 ] && ok "--window runs under Xvfb" || { fail "--window under Xvfb"; cat "$work/window"; }
  expect_text "the fixed-step loop ran 19 ticks" "t=1.90 s ticks=19" "$work/window"
else
  echo "skip - Xvfb not installed (bash .ci/install-deps installs it)"
fi

finish
