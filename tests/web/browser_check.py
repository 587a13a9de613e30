#!/usr/bin/env python3
"""The web page in a real browser: Debian's chromium, headless, on SwiftShader (software
WebGL2), the site served on 127.0.0.1 only. For every shipped scene (assets/scenes/*.toml):

  (a) the page steps the scene for FRAMES frames of a 60 fps virtual clock; its state hash and
      summary line (ticks, t, state_hash, energy, dissipated, balance) must equal, character for
      character, what the native `fixstep run SCENE --steps N` prints for the same N ticks;
  (b) the browser's screenshot of its last frame must be a real frame (not blank) and match the
      native OSMesa frame `fixstep render SCENE --frames FRAMES` of the same tick within the
      tolerance below (the rasterisers differ: llvmpipe and SwiftShader round edges, points and
      the font's quads differently);
  (c) the recording the page made of its run must replay natively (`fixstep replay`, every
      stored hash verified), and a native recording (`fixstep run --record`) must replay in the
      page with every hash verified and the native final hash.

Then the overlay test card (web/overlay_card.hpp: every shape a game draws, a view style of its
own) drawn by the page over default.toml (overlay=card) against its native golden frame
(tests/golden/frames/overlay_card_frame_000060.png), with the tolerance of (b).

Then the games (--no-games skips them), the page's game=NAME, NAME being demos/airhockey,
demos/peggle, demos/pinball, demos/slingshot and demos/stacker as their programs' fixstep::app::run plays them:
game=NAME&frames=GAME_FRAMES headless (the autopilot playing; airhockey's against the
computer, as the program without --host / --join) must end in the state hash and summary lines
the native `NAME --frames GAME_FRAMES` prints, and airhockey's and peggle's last frames must
match the native `--last-frame PNG` with the tolerance of (b) (each at its program's size:
1280x720, airhockey 960x600); game=NAME&replay= of assets/recordings/NAME.rec must verify
every stored hash in the page with the native `NAME --replay`'s final hash, count and summary,
and slingshot's last frame played back must match the native `slingshot --replay --last-frame
PNG` (slingshot has no autopilot: its frames= run, the level at rest, is compared by state
only; its replay's frame has a shot in it). A network match (tests/web/native_match.py: two
native airhockey bots, host and joiner, over loopback, their recordings byte-identical) is
replayed the same way, game=airhockey&replay= of the host's recording: every stored hash (one a
tick) verified in the page as `airhockey --replay` verifies it, and its last frame against the
native one. A slingshot recording refused by game=peggle and by game=airhockey, and the match's
by game=peggle, are rows of the bad inputs below.

Then the input (--no-input skips it): the interactive page driven by DOM key and mouse events
(tests/web/input_check.html), game=peggle played by them (tests/web/game_input_check.html: the
pointer aims, a click shoots, r restarts), and a native recording with input
(assets/inputs/default_push.toml: pushes, a button, a drag) replayed in the page with every hash
verified.

Then the long "cause" runs (--long): the page steps a scene N ticks without drawing (ticks=N)
and must report the native `fixstep run --steps N` summary: projectile.toml at 40 000 ticks and
default.toml at 10^5 (subnormals), and the cross-platform cause scenes in tests/scenes/cross (exp's
FMA/non-FMA difference, a loader input whose hypot differs between libms, the shape solver's
stress scene at 1200 ticks), cross/NAME.toml.

Then the bad inputs (--no-bad-inputs skips them): every row of tests/web/bad_inputs_page.tsv,
the page's rows of docs/BAD_INPUTS.md, loaded as index.html?QUERY must show exactly
"error: MESSAGE" as its result.

Exits 0 when everything matched, 1 naming each failure otherwise.
Usage: browser_check.py --fixstep build/ci/bin/fixstep --site build/web/site [--out DIR]
"""
import argparse
import html
import http.server
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp_pipe  # noqa: E402
import native_match  # noqa: E402
import png_image  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Screenshot tolerance against the OSMesa frame (b). Measured on the 12 shipped scenes at
# 640x360 (docs/ROBUSTNESS.md, "The browser checks"): same frame, mean difference 0.016 to 0.30
# levels, at most 0.0013 % of pixels differing by more than 64 levels (SwiftShader and llvmpipe
# cover a few anti-aliased edge pixels differently). The frame before (1/60 s earlier)
# differs by 1.35 to 3.2 levels and in 0.56 % to 1.4 % of pixels: both limits below fail it.
MAX_MEAN_DIFFERENCE = 0.75   # levels per channel value, 0..255
PIXEL_THRESHOLD = 64         # levels: a pixel "differs" when some channel differs by more
MAX_DIFFERING_FRACTION = 0.001
MIN_CONTENT_FRACTION = 0.01  # of pixels not the background colour


# Debian's chromium, headless, WebGL2 on SwiftShader, nothing fetched but the page.
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--use-angle=swiftshader",
                  "--enable-unsafe-swiftshader", "--disable-gpu-sandbox", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync", "--hide-scrollbars"]


def chromium(url, out_png, width, height, budget_ms, wall_s=600):
    """Loads `url` in headless Chromium until the virtual-time budget is spent; returns the DOM
    (text) and writes the screenshot of a width x height window to out_png (if given). A browser
    still running after wall_s seconds is killed and reported as a RuntimeError."""
    profile = tempfile.mkdtemp(prefix="fixstep-chromium-")
    cmd = ["chromium", *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
           f"--virtual-time-budget={budget_ms}", f"--window-size={width},{height}",
           "--dump-dom"]
    if out_png:
        cmd.append(f"--screenshot={out_png}")
    try:
        done = subprocess.run(cmd + [url], capture_output=True, text=True, timeout=wall_s)
    except subprocess.TimeoutExpired as e:
        raise RuntimeError(f"chromium did not finish {url} within {wall_s} s") from e
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return done.stdout


def element(dom, ident):
    m = re.search(rf'<pre id="{ident}">(.*?)</pre>', dom, re.S)
    return html.unescape(m.group(1)) if m else None


# The forms a page's result takes once final (web/page_dom.cpp, page_runs.cpp, page_game.cpp,
# page_app.cpp). Anything else is a page still at work: "loading" (index.html's text), "running:
# ...", "fetching the input script", or the empty text of a <pre> the parser has made but not yet
# filled.
FINAL_RESULT = re.compile(r"(tick=|verified ticks=|diverged at tick |error: )")


def page_settled(result):
    """True once the page's result is final (FINAL_RESULT)."""
    return isinstance(result, str) and FINAL_RESULT.match(result) is not None


def page_texts(browser, url, ids, wall_s=600):
    """Loads `url` in a tab of `browser` (cdp_pipe.Browser) on the real clock, waits until its
    result settles (page_settled; at most wall_s seconds), and returns the text of each element
    of `ids` (None for one the page lacks), all read at the moment the result was seen settled,
    so the result returned is the one judged. For pages that need no screenshot: one Chromium
    serves them all (a Chromium started per page cost about 4 s of CPU)."""
    assert ids[0] == "result"
    texts = "[" + ", ".join(f"document.getElementById('{i}')?.textContent ?? null"
                            for i in ids) + "]"
    browser.open(url)
    try:
        values = browser.wait_for(texts, lambda v: isinstance(v, list) and page_settled(v[0]),
                                  wall_s)
        return values if isinstance(values, list) else [None] * len(ids)
    finally:
        browser.close_tab()


def check_settle(args, site, failures):
    """page_texts's own reading, on tests/web/settle_check.html (a result empty for a second,
    then "loading", then final): it must return the final result and the summary written with
    it, not the empty text of a page still being parsed."""
    texts = page_texts(args.browser, f"{site.url}/tests/settle_check.html", ["result", "summary"],
                       60)
    expected = ["tick=5 state_hash=0123456789abcdef", "settled summary"]
    if texts != expected:
        failures.append(f"settle: page_texts read {texts!r}, expected {expected!r}")
    print(f"settle: page_texts waited for {texts[0]!r}", flush=True)


def native(fixstep, *args):
    done = subprocess.run([fixstep, *args], capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        raise RuntimeError(f"fixstep {' '.join(args)} failed ({done.returncode}): "
                           f"{done.stderr.strip()}")
    return done.stdout


def summary_of(stdout):
    m = re.search(r"^ticks=\d+ .*$", stdout, re.M)
    return m.group(0) if m else None


class Site:
    """The site folder on 127.0.0.1 (a free port), and recordings under /rec/ from `rec_dir`."""

    def __init__(self, site, rec_dir):
        class Handler(http.server.SimpleHTTPRequestHandler):
            def __init__(self, *a, **k):
                super().__init__(*a, directory=site, **k)

            def translate_path(self, path):
                if path.startswith("/rec/"):
                    return os.path.join(rec_dir, os.path.basename(path.split("?")[0]))
                if path.startswith("/tests/"):  # the test pages beside this script
                    return os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                        os.path.basename(path.split("?")[0]))
                return super().translate_path(path)

            def log_message(self, *a):
                pass

        self.rec_dir = rec_dir
        self.server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()


def check_scene(scene, args, site, out, failures):
    w, h = args.size.split("x")
    name = scene[:-5]
    shot = os.path.join(out, f"{name}_browser.png")
    url = (f"{site.url}/index.html?scene={scene}&frames={args.frames}&fps=60&size={args.size}"
           f"&headless=1&record=1")
    dom = chromium(url, shot, int(w), int(h), args.budget_ms)
    result, summary = element(dom, "result"), element(dom, "summary")
    m = re.fullmatch(r"tick=(\d+) state_hash=([0-9a-f]{16})", result or "")
    if not m:
        failures.append(f"{scene}: the page did not finish: result {result!r}")
        return
    ticks, page_hash = m.group(1), m.group(2)
    # (a) the state after the same ticks, natively
    native_summary = summary_of(native(args.fixstep, "run", f"assets/scenes/{scene}", "--steps",
                                       ticks))
    if summary != native_summary:
        failures.append(f"{scene}: (a) page {summary!r} != native {native_summary!r}")
    # (b) the last frame against OSMesa's
    frames_dir = os.path.join(out, f"{name}_native")
    native(args.fixstep, "render", f"assets/scenes/{scene}", "--out", frames_dir, "--frames",
           str(args.frames), "--fps", "60", "--size", args.size, "--overwrite")
    frame = os.path.join(frames_dir, f"frame_{args.frames - 1:06d}.png")
    browser_img, native_img = png_image.decode_png(shot), png_image.decode_png(frame)
    content = png_image.content_fraction(browser_img)
    mean, differing = png_image.compare(browser_img, native_img, PIXEL_THRESHOLD)
    verdict = "ok"
    if content < MIN_CONTENT_FRACTION:
        verdict = "BLANK"
        failures.append(f"{scene}: (b) the browser frame is blank ({content:.4f} of pixels drawn)")
    elif mean > MAX_MEAN_DIFFERENCE or differing > MAX_DIFFERING_FRACTION:
        verdict = "DIFFERENT"
        failures.append(f"{scene}: (b) the browser frame differs from OSMesa's: mean {mean:.3f} "
                        f"levels, {differing:.4%} of pixels by > {PIXEL_THRESHOLD}")
    # (c) the page's recording natively, and a native recording in the page
    page_rec = os.path.join(out, f"{name}_page.rec")
    with open(page_rec, "w") as f:
        f.write(element(dom, "recording") or "")
    replayed = native(args.fixstep, "replay", page_rec, "--scene", f"assets/scenes/{scene}")
    if f"ticks={ticks} state_hash={page_hash}" not in replayed:
        failures.append(f"{scene}: (c) the page's recording replays natively as {replayed!r}")
    native_rec = os.path.join(out, "rec", f"{name}.rec")
    recorded = summary_of(native(args.fixstep, "run", f"assets/scenes/{scene}", "--steps", ticks,
                                 "--record", native_rec))
    replay_result, = page_texts(
        args.browser, f"{site.url}/index.html?replay=/rec/{name}.rec&headless=1&size={args.size}",
        ["result"])
    replay_result = replay_result or ""
    native_hash = re.search(r"state_hash=([0-9a-f]{16})", recorded).group(1)
    if not re.fullmatch(rf"verified ticks={ticks} state_hash={native_hash} hashes=\d+",
                        replay_result):
        failures.append(f"{scene}: (c) the native recording in the page: {replay_result!r}")
    print(f"{scene}: ticks={ticks} state_hash={page_hash} frame: {content:.3f} drawn, mean "
          f"{mean:.3f}, {differing:.4%} > {PIXEL_THRESHOLD} ({verdict}); page {replay_result}",
          flush=True)


def check_overlay_card(args, site, out, failures):
    """The overlay test card (web/overlay_card.hpp: every DrawList shape in world and screen
    coordinates, its own background, no grid, the HUD bottom right) over default.toml at frame 60
    (frames=61&overlay=card) against the native golden frame of the same card
    (tests/golden/frames/overlay_card_frame_000060.png, drawn by test_golden_frames), within the
    scenes' tolerance."""
    if args.size != "640x360" or args.frames != 61:
        print("overlay card: skipped (its golden frame is frame 60 at 640x360)", flush=True)
        return
    shot = os.path.join(out, "overlay_card_browser.png")
    url = (f"{site.url}/index.html?scene=default.toml&frames=61&fps=60&size=640x360"
           f"&headless=1&overlay=card")
    dom = chromium(url, shot, 640, 360, args.budget_ms)
    result = element(dom, "result") or ""
    if not re.fullmatch(r"tick=\d+ state_hash=[0-9a-f]{16}", result):
        failures.append(f"overlay card: the page did not finish: result {result!r}")
        return
    golden = os.path.join(ROOT, "tests", "golden", "frames", "overlay_card_frame_000060.png")
    verdict = compare_frame("overlay card", shot, golden, failures, "OSMesa's")
    print(f"overlay card: {verdict}", flush=True)


# Each game's frame size, px: its app::Settings' (the programs have no --size), which the page
# takes too when given no size=.
GAME_SIZES = {"airhockey": (960, 600), "peggle": (1280, 720), "slingshot": (1280, 720),
              "stacker": (1280, 720), "pinball": (1280, 720), "platformer": (1280, 720)}


def native_game(args, game, *options):
    """Runs the native game program (beside the fixstep CLI) and returns its standard output."""
    program = os.path.join(os.path.dirname(args.fixstep), game)
    done = subprocess.run([program, *options], capture_output=True, text=True, cwd=ROOT)
    if done.returncode != 0:
        raise RuntimeError(f"{game} {' '.join(options)} failed ({done.returncode}): "
                           f"{done.stderr.strip()}")
    return done.stdout


def compare_frame(label, shot, reference_png, failures, reference="the native one"):
    """The browser's screenshot `shot` against a reference frame (`reference` names it in the
    message): not blank, and within the tolerance of (b). Returns the verdict for the log."""
    browser_img, native_img = png_image.decode_png(shot), png_image.decode_png(reference_png)
    content = png_image.content_fraction(browser_img)
    mean, differing = png_image.compare(browser_img, native_img, PIXEL_THRESHOLD)
    verdict = "ok"
    if content < MIN_CONTENT_FRACTION:
        verdict = "BLANK"
        failures.append(f"{label}: the browser frame is blank ({content:.4f} drawn)")
    elif mean > MAX_MEAN_DIFFERENCE or differing > MAX_DIFFERING_FRACTION:
        verdict = "DIFFERENT"
        failures.append(f"{label}: the browser frame differs from {reference}: mean "
                        f"{mean:.3f} levels, {differing:.4%} of pixels by > {PIXEL_THRESHOLD}")
    return (f"{content:.3f} drawn, mean {mean:.3f}, {differing:.4%} > {PIXEL_THRESHOLD} "
            f"({verdict})")


def check_game_frames(game, args, site, out, failures, frame=True):
    """game=GAME&frames=N headless against the native `GAME --frames N --last-frame PNG`: the
    same state hash and summary lines (the engine's and the game's), and with `frame` the last
    frame within the tolerance of (b)."""
    frames = args.game_frames
    shot = os.path.join(out, f"game_{game}_browser.png")
    url = f"{site.url}/index.html?game={game}&frames={frames}&headless=1"
    if frame:
        dom = chromium(url, shot, *GAME_SIZES[game], args.budget_ms)
        result, summary = element(dom, "result"), element(dom, "summary")
    else:
        result, summary = page_texts(args.browser, url, ["result", "summary"])
    result, summary = result or "", summary or ""
    if not re.fullmatch(r"tick=\d+ state_hash=[0-9a-f]{16}", result):
        failures.append(f"game={game}: the page did not finish: result {result!r}")
        return
    native_png = os.path.join(out, f"game_{game}_native.png")
    printed = native_game(args, game, "--frames", str(frames),
                          *(["--last-frame", native_png] if frame else [])).strip()
    native_hash = re.search(r"state_hash=([0-9a-f]{16})", printed)
    if summary != printed or not native_hash or not result.endswith(native_hash.group(0)):
        failures.append(f"game={game} frames={frames}: page {result!r} {summary!r} != native "
                        f"{printed!r}")
    verdict = "frame: " + compare_frame(f"game={game}", shot, native_png, failures) if frame else ""
    print(f"game={game} frames={frames}: {result}; {summary.splitlines()[-1]}; {verdict}",
          flush=True)


def check_game_script(game, script, frames, args, site, out, failures):
    """game=GAME&frames=N&input= of an input script (assets/inputs/SCRIPT) against the native
    `GAME --frames N --input SCRIPT --last-frame PNG`: the same state hash and summary lines (the
    game's score among them), and the last frame within the tolerance of (b)."""
    served = f"{game}_{os.path.basename(script)}"
    shutil.copyfile(os.path.join(ROOT, script), os.path.join(site.rec_dir, served))
    url = f"{site.url}/index.html?game={game}&frames={frames}&input=/rec/{served}&headless=1"
    shot = os.path.join(out, f"game_{game}_script_browser.png")
    dom = chromium(url, shot, *GAME_SIZES[game], args.budget_ms)
    result, summary = element(dom, "result") or "", element(dom, "summary") or ""
    native_png = os.path.join(out, f"game_{game}_script_native.png")
    printed = native_game(args, game, "--frames", str(frames), "--input",
                          os.path.join(ROOT, script), "--last-frame", native_png).strip()
    native_hash = re.search(r"state_hash=([0-9a-f]{16})", printed)
    if summary != printed or not native_hash or not result.endswith(native_hash.group(0)):
        failures.append(f"game={game} input={script}: page {result!r} {summary!r} != native "
                        f"{printed!r}")
    verdict = compare_frame(f"game={game} input", shot, native_png, failures)
    print(f"game={game} input={script}: {result}; {summary.splitlines()[-1] if summary else ''}; "
          f"frame: {verdict}", flush=True)


def check_game_replay(game, args, site, out, failures, frame=False, recording=None):
    """game=GAME&replay= of `recording` (default assets/recordings/GAME.rec): every stored hash
    verified in the page, with the final hash, the count of hashes and the summary lines of the
    native `GAME --replay`; with `frame`, the page's last frame of the recording played back
    against the native `--last-frame PNG` (tolerance of (b)). Returns the page's result."""
    recording = recording or os.path.join("assets", "recordings", f"{game}.rec")
    served = f"{game}_game.rec"
    if os.path.dirname(os.path.abspath(recording)) != os.path.abspath(site.rec_dir):
        shutil.copyfile(os.path.join(ROOT, recording), os.path.join(site.rec_dir, served))
    else:  # already under /rec/
        served = os.path.basename(recording)
    url = f"{site.url}/index.html?game={game}&replay=/rec/{served}&headless=1"
    shot = os.path.join(out, f"game_{served[:-4]}_replay_browser.png")
    native_png = os.path.join(out, f"game_{served[:-4]}_replay_native.png")
    if frame:
        dom = chromium(url, shot, *GAME_SIZES[game], args.budget_ms)
        result, summary = element(dom, "result"), element(dom, "summary")
    else:
        result, summary = page_texts(args.browser, url, ["result", "summary"])
    result, summary = result or "", summary or ""
    printed = native_game(args, game, "--replay", recording,
                          *(["--last-frame", native_png] if frame else [])).strip()
    lines = printed.splitlines()
    m = re.search(r"ticks=(\d+) .*state_hash=([0-9a-f]{16})", lines[0])
    verified = re.fullmatch(r"verified=(\d+)", lines[-1])
    expected = (f"verified ticks={m.group(1)} state_hash={m.group(2)} hashes={verified.group(1)}"
                if m and verified else None)
    if result != expected or summary != "\n".join(lines[:-1]):
        failures.append(f"game={game} replay: page {result!r} {summary!r} != native {printed!r}")
    verdict = "frame: " + compare_frame(f"game={game} replay", shot, native_png, failures) if frame else ""
    print(f"game={game} replay of {recording}: page {result}; {verdict}", flush=True)
    return result


MATCH_TICKS = 600  # as tests/airhockey_match.sh


def match_recording(args, rec_dir):
    """The recording of a native airhockey match (native_match.record_match) under /rec/, as
    rec_dir/airhockey_match.rec: made once, for the match check and the bad inputs."""
    rec = os.path.join(rec_dir, "airhockey_match.rec")
    if not os.path.exists(rec):
        airhockey = os.path.join(os.path.dirname(args.fixstep), "airhockey")
        native_match.record_match(airhockey, rec_dir, MATCH_TICKS)
    return rec


def check_match_replay(args, site, out, failures):
    """A network match's recording (two native bots over loopback, both peers' recordings
    identical) replayed in the page with game=airhockey: every stored hash, one a tick, verified
    as `airhockey --replay` verifies it, the same final state and score, and its last frame
    against the native one."""
    rec = match_recording(args, site.rec_dir)
    result = check_game_replay("airhockey", args, site, out, failures, True, rec)
    if not re.fullmatch(rf"verified ticks={MATCH_TICKS} state_hash=[0-9a-f]{{16}} "
                        rf"hashes={MATCH_TICKS + 1}", result or ""):
        failures.append(f"airhockey match replay: not every tick's hash verified: {result!r}")


def check_input_replay(args, site, out, failures):
    """A native recording with input (assets/inputs/default_push.toml: every body pushed right,
    then up, the action button tapped, the ball dragged) replayed in the page: every stored hash
    verified and the native final hash, so input recorded natively means the same in wasm."""
    rec = os.path.join(out, "rec", "default_input.rec")
    recorded = summary_of(native(args.fixstep, "run", "assets/scenes/default.toml", "--steps",
                                 "300", "--input", "assets/inputs/default_push.toml",
                                 "--record", rec)) or ""
    native_hash = re.search(r"state_hash=([0-9a-f]{16})", recorded)
    if not native_hash:
        raise RuntimeError(f"fixstep run --input --record printed no summary: {recorded!r}")
    native_hash = native_hash.group(1)
    result, = page_texts(args.browser, f"{site.url}/index.html?replay=/rec/default_input.rec"
                         f"&headless=1&size={args.size}", ["result"])
    result = result or ""
    if not re.fullmatch(rf"verified ticks=300 state_hash={native_hash} hashes=301", result):
        failures.append(f"input replay: default_push.toml's recording in the page: {result!r} "
                        f"(native state_hash={native_hash})")
    print(f"input replay: default.toml with assets/inputs/default_push.toml, native "
          f"state_hash={native_hash}; page {result}", flush=True)


def check_input(args, site, failures):
    """tests/web/input_check.html: the interactive page on the real clock, driven by DOM key and
    mouse events (restart, pause, single step, a drag, rewind); the dragged state must differ
    from the undisturbed one at the same tick."""
    browser = cdp_pipe.Browser(CHROMIUM_FLAGS + ["--window-size=700,600"])
    try:
        browser.open(f"{site.url}/tests/input_check.html")
        title = browser.wait_for_title("input:", 60)
        report = browser.evaluate("document.getElementById('result').textContent") or ""
    finally:
        browser.close()
    undisturbed = re.search(r"state_hash=([0-9a-f]{16})", native(
        args.fixstep, "run", "assets/scenes/projectile.toml", "--steps", "2")).group(1)
    dragged = re.search(r"dragged tick=2 state_hash=([0-9a-f]{16})", report)
    if title != "input: done":
        failures.append(f"input: {title or 'no result in 60 s'}: {report}")
    elif not dragged or dragged.group(1) == undisturbed:
        failures.append(f"input: the drag did not change the state ({undisturbed}): {report}")
    print("input:", report.replace("\n", "; "), flush=True)


def check_game_input(args, site, failures):
    """tests/web/game_input_check.html: game=peggle played interactively on the real clock by
    DOM mouse and key events (the pointer aims, a click shoots, r restarts)."""
    browser = cdp_pipe.Browser(CHROMIUM_FLAGS + ["--window-size=700,600"])
    try:
        browser.open(f"{site.url}/tests/game_input_check.html")
        title = browser.wait_for_title("game input:", 60)
        report = browser.evaluate("document.getElementById('result').textContent") or ""
    finally:
        browser.close()
    if title != "game input: done":
        failures.append(f"game input: {title or 'no result in 60 s'}: {report}")
    print("game input:", report.replace("\n", "; "), flush=True)


def check_long(spec, args, site, failures):
    scene, ticks = spec.split(":")
    result, summary = page_texts(
        args.browser, f"{site.url}/index.html?scene={scene}&ticks={ticks}&headless=1&size=320x180",
        ["result", "summary"])
    path = f"tests/scenes/{scene}" if scene.startswith("cross/") else f"assets/scenes/{scene}"
    native_summary = summary_of(native(args.fixstep, "run", path, "--steps", ticks))
    ok = summary == native_summary
    if not ok:
        failures.append(f"{scene} ticks={ticks}: page {summary!r} (result {result!r}) != "
                        f"native {native_summary!r}")
    print(f"{scene} ticks={ticks}: {'same' if ok else 'DIFFERENT'}: {summary}", flush=True)


BAD_INPUTS = os.path.join(ROOT, "tests", "web", "bad_inputs_page.tsv")


def bad_input_rows():
    """The rows of bad_inputs_page.tsv: (description, query, message) without comments."""
    rows = []
    with open(BAD_INPUTS, encoding="utf-8") as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line.startswith("#"):
                continue
            fields = line.split("\t")
            if len(fields) != 3:
                raise ValueError(f"{BAD_INPUTS}: not DESCRIPTION<TAB>QUERY<TAB>MESSAGE: {line!r}")
            rows.append(tuple(fields))
    return rows


def write_bad_recordings(args, rec_dir):
    """The recordings the replay= rows fetch under /rec/ (see bad_inputs_page.tsv)."""
    base = os.path.join(rec_dir, "projectile_20.rec")
    native(args.fixstep, "run", "assets/scenes/projectile.toml", "--steps", "20", "--record",
           base, "--hash-every", "1", "-q")
    with open(base, encoding="utf-8") as f:
        lines = f.read().splitlines(keepends=True)
    with open(os.path.join(rec_dir, "text.rec"), "w", encoding="utf-8") as f:
        f.write("hello, not a recording\n")
    with open(os.path.join(rec_dir, "cut.rec"), "w", encoding="utf-8") as f:
        f.write("".join(lines[:10]))
    # As format 2 wrote it (no embedded scene, no damping split): replayed from the scene it
    # names, which the page does not ship.
    v2 = ["fixstep-recording 2\n" if line.startswith("fixstep-recording ") else line
          for line in lines
          if not line.startswith(("scene_text ", "|", "damping_split "))]
    with open(os.path.join(rec_dir, "foreign.rec"), "w", encoding="utf-8") as f:
        f.write("".join("scene mine.toml\n" if line.startswith("scene ") else line
                        for line in v2))
    with open(os.path.join(rec_dir, "damaged.rec"), "w", encoding="utf-8") as f:
        f.write("".join("|dt = \\q\n" if line.startswith("|dt = 0.01") else line
                        for line in lines))
    # A game's recording for the game= rows (slingshot's, refused by game=peggle and
    # game=airhockey), and a network match's (airhockey's, refused by game=peggle).
    shutil.copyfile(os.path.join(ROOT, "assets", "recordings", "slingshot.rec"),
                    os.path.join(rec_dir, "slingshot_game.rec"))
    match_recording(args, rec_dir)
    # Format 4, naming the game rules it was recorded with: the page has no game of that name.
    with open(os.path.join(rec_dir, "rules.rec"), "w", encoding="utf-8") as f:
        f.write("".join(("fixstep-recording 4\n" if line.startswith("fixstep-recording ")
                         else line) + ("rules pong 1\n" if line.startswith("hash_every ")
                                       else "")
                        for line in lines))
    if os.path.exists(os.path.join(rec_dir, "missing.rec")):
        os.remove(os.path.join(rec_dir, "missing.rec"))


def check_bad_inputs(args, site, failures):
    """Every bad input of the page (bad_inputs_page.tsv): it must stop and show exactly
    "error: MESSAGE"."""
    write_bad_recordings(args, site.rec_dir)
    rows = bad_input_rows()
    wrong = 0
    results = []
    try:
        for _, query, _ in rows:
            results += page_texts(args.browser, f"{site.url}/index.html?{query}", ["result"], 60)
    except RuntimeError as e:
        results += [str(e)] * (len(rows) - len(results))
    for (what, query, message), result in zip(rows, results):
        if result != f"error: {message}":
            wrong += 1
            failures.append(f"bad input {what!r} (index.html?{query}): the page shows {result!r}, "
                            f"expected {'error: ' + message!r}")
    print(f"bad inputs: {len(rows) - wrong} of {len(rows)} show their error", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--fixstep", required=True, help="the native fixstep CLI")
    p.add_argument("--site", required=True, help="the web build's site folder")
    p.add_argument("--out", help="where screenshots, frames and recordings go (kept)")
    p.add_argument("--frames", type=int, default=61, help="frames per scene (60 fps)")
    p.add_argument("--size", default="640x360")
    p.add_argument("--scenes", nargs="*", help="scene files (default: every shipped scene)")
    p.add_argument("--long", nargs="*", default=["projectile.toml:40000", "default.toml:100000",
                            "cross/damped_exp.toml:2000", "cross/hypot_rest.toml:2000",
                            "cross/shapes.toml:1200"],
                   help="SCENE:TICKS runs stepped without drawing")
    p.add_argument("--no-input", action="store_true", help="skip the input checks")
    p.add_argument("--no-games", action="store_true", help="skip the games (game=)")
    p.add_argument("--game-frames", type=int, default=240,
                   help="frames of each game's headless run (60 fps)")
    p.add_argument("--no-bad-inputs", action="store_true",
                   help="skip the bad inputs (tests/web/bad_inputs_page.tsv)")
    p.add_argument("--budget-ms", type=int, default=600000, help="virtual time per page load")
    args = p.parse_args()
    args.fixstep = os.path.abspath(args.fixstep)
    out = os.path.abspath(args.out or tempfile.mkdtemp(prefix="fixstep-web-"))
    os.makedirs(os.path.join(out, "rec"), exist_ok=True)
    site = Site(os.path.abspath(args.site), os.path.join(out, "rec"))
    scenes = args.scenes or sorted(f for f in os.listdir(os.path.join(ROOT, "assets", "scenes"))
                                   if f.endswith(".toml"))
    failures, start = [], time.monotonic()
    checks = [("settle", lambda: check_settle(args, site, failures))]
    checks += [(scene, lambda s=scene: check_scene(s, args, site, out, failures))
               for scene in scenes]
    checks.append(("overlay card", lambda: check_overlay_card(args, site, out, failures)))
    if not args.no_games:
        # Five screenshots (each a Chromium of its own): airhockey's and peggle's autopilot runs,
        # slingshot's recorded shot (its headless run, without an autopilot, is checked by state
        # only), and the last frame of airhockey's network match.
        checks += [("game=airhockey",
                    lambda: check_game_frames("airhockey", args, site, out, failures)),
                   ("game=peggle", lambda: check_game_frames("peggle", args, site, out, failures)),
                   ("game=slingshot",
                    lambda: check_game_frames("slingshot", args, site, out, failures, False))]
        # stacker (box shapes): its autopilot run, state and last frame; its recording's hashes.
        checks += [("game=stacker", lambda: check_game_frames("stacker", args, site, out, failures)),
                   ("game=stacker replay",
                    lambda: check_game_replay("stacker", args, site, out, failures))]
        checks += [("game=peggle replay",
                    lambda: check_game_replay("peggle", args, site, out, failures)),
                   ("game=slingshot replay",
                    lambda: check_game_replay("slingshot", args, site, out, failures, True)),
                   ("airhockey match replay",
                    lambda: check_match_replay(args, site, out, failures))]
        # pinball: its autopilot run (state and frame) and its recording (flippers driven by
        # target_angle input, shapes that turn).
        checks += [("game=pinball", lambda: check_game_frames("pinball", args, site, out, failures)),
                   ("game=pinball replay",
                    lambda: check_game_replay("pinball", args, site, out, failures))]
        # Scripted games (input=): the pinball launched and flipped, the platformer's coins.
        checks += [("game=pinball input",
                    lambda: check_game_script("pinball", "assets/inputs/pinball_launch.toml", 1200,
                                              args, site, out, failures)),
                   ("game=platformer input",
                    lambda: check_game_script("platformer", "assets/inputs/platformer_run.toml",
                                              900, args, site, out, failures))]
    if not args.no_input:
        checks += [("input", lambda: check_input(args, site, failures)),
                   ("game input", lambda: check_game_input(args, site, failures)),
                   ("input replay", lambda: check_input_replay(args, site, out, failures))]
    checks += [(spec, lambda s=spec: check_long(s, args, site, failures)) for spec in args.long]
    if not args.no_bad_inputs:
        checks.append(("bad inputs", lambda: check_bad_inputs(args, site, failures)))
    # One Chromium (DevTools pipe) for every page read without a screenshot.
    window = args.size.replace("x", ",")
    args.browser = cdp_pipe.Browser(CHROMIUM_FLAGS + [f"--window-size={window}"])
    try:
        for name, check in checks:
            # A check that breaks (a page without a summary, a hung Chromium, a missing file) is
            # one failure; the others still run.
            try:
                check()
            except (RuntimeError, ValueError, OSError, AttributeError, TypeError) as e:
                failures.append(f"{name}: {e}")
    finally:
        args.browser.close()
    print(f"browser checks: {len(scenes)} scenes, {len(args.long)} long runs, "
          f"{time.monotonic() - start:.0f} s; output in {out}")
    for f in failures:
        print(f"FAIL {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
