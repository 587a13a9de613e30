"""A network match of the native airhockey program (demos/airhockey), made for the browser
checks as tests/airhockey_match.sh plays one: a host and a joiner, both scripted bots
(--bot, headless), over loopback (the host on a port the system picks, --host 0, which it
prints), each writing the match's confirmed inputs with --record. Both recordings must be
byte-identical: the one the check replays in the page is then the recording of either peer."""
import filecmp
import os
import re
import secrets
import subprocess
import time

PORT_WAIT_S = 10   # the host prints its port at once; give a loaded machine time
MATCH_WAIT_S = 60  # a headless bot match of 600 ticks takes about a second on loopback


def wait_port(log_path, host):
    """The port the host printed ("hosting on 127.0.0.1:PORT"), waiting up to PORT_WAIT_S
    seconds; RuntimeError when the host exits or prints none."""
    deadline = time.monotonic() + PORT_WAIT_S
    while time.monotonic() < deadline:
        with open(log_path, encoding="utf-8", errors="replace") as f:
            m = re.search(r"hosting on [0-9.]+:(\d+)", f.read())
        if m:
            return m.group(1)
        if host.poll() is not None:
            break
        time.sleep(0.05)
    with open(log_path, encoding="utf-8", errors="replace") as f:
        raise RuntimeError(f"the airhockey host printed no port: {f.read().strip()!r}")


def record_match(airhockey, out_dir, ticks=600, session="lockstep"):
    """Plays a bot match of `ticks` ticks (`session`: lockstep or rollback) between two
    `airhockey` processes on 127.0.0.1 and returns the path of the host's recording,
    out_dir/airhockey_match.rec (the joiner's is airhockey_match.join.rec). Raises
    RuntimeError, with what the peers printed, when a peer fails or times out, or when the two
    recordings differ."""
    host_rec = os.path.join(out_dir, "airhockey_match.rec")
    join_rec = os.path.join(out_dir, "airhockey_match.join.rec")
    host_log = os.path.join(out_dir, "airhockey_match.host.out")
    # The match's token (docs/NETWORK.md, "Connecting"): a random one, given to both peers.
    token = secrets.token_hex(16)
    common = ["--session", session, "--bot", "--ticks", str(ticks), "--token", token]
    with open(host_log, "w", encoding="utf-8") as log:
        host = subprocess.Popen([airhockey, "--host", "0", *common, "--record", host_rec],
                                stdout=log, stderr=subprocess.STDOUT)
    try:
        port = wait_port(host_log, host)
        joiner = subprocess.run([airhockey, "--join", f"127.0.0.1:{port}", *common, "--record",
                                 join_rec], capture_output=True, text=True, timeout=MATCH_WAIT_S)
        host_status = host.wait(timeout=MATCH_WAIT_S)
    except subprocess.TimeoutExpired as e:
        raise RuntimeError(f"the airhockey match did not end within {MATCH_WAIT_S} s") from e
    finally:
        if host.poll() is None:
            host.kill()
            host.wait()
    with open(host_log, encoding="utf-8", errors="replace") as f:
        host_out = f.read().strip()
    if host_status != 0 or joiner.returncode != 0:
        raise RuntimeError(f"the airhockey match: host exited {host_status} ({host_out!r}), "
                           f"joiner {joiner.returncode} "
                           f"({(joiner.stdout + joiner.stderr).strip()!r})")
    if not filecmp.cmp(host_rec, join_rec, shallow=False):
        raise RuntimeError(f"the airhockey match: the peers' recordings differ ({host_rec}, "
                           f"{join_rec})")
    return host_rec
