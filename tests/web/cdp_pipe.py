"""Headless Chromium driven through the DevTools protocol over a pipe (--remote-debugging-pipe:
the browser reads JSON messages, each ended by a NUL byte, from its fd 3 and writes its own to
fd 4; https://chromedevtools.github.io/devtools-protocol/), for pages that must run on the real
clock: headless Chromium's --dump-dom does not wait for them, and its virtual time runs no
animation frames. Python 3 standard library only.
"""
import json
import os
import shutil
import subprocess
import tempfile
import time


class Browser:
    """One headless Chromium (the flags of browser_check.py) with a DevTools pipe."""

    def __init__(self, flags):
        self._to_browser_r, self._to_browser_w = os.pipe()
        self._from_browser_r, self._from_browser_w = os.pipe()
        self._profile = tempfile.mkdtemp(prefix="fixstep-chromium-")
        reads, writes = self._to_browser_r, self._from_browser_w

        def fds():
            os.dup2(reads, 3)
            os.dup2(writes, 4)
            os.set_inheritable(3, True)  # dup2 onto itself would keep close-on-exec
            os.set_inheritable(4, True)

        self._proc = subprocess.Popen(
            ["chromium", *flags, f"--user-data-dir={self._profile}", "--remote-debugging-pipe",
             "about:blank"], preexec_fn=fds, close_fds=False, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        os.close(self._to_browser_r)
        os.close(self._from_browser_w)
        self._next_id, self._buffer, self._session, self._target = 0, b"", None, None

    def _send(self, method, params=None, session=True):
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params or {}}
        if session and self._session:
            message["sessionId"] = self._session
        os.write(self._to_browser_w, json.dumps(message).encode() + b"\0")
        while True:  # the reply to this message; events in between are dropped
            while b"\0" not in self._buffer:
                chunk = os.read(self._from_browser_r, 65536)
                if not chunk:
                    raise RuntimeError(f"chromium closed its DevTools pipe during {method}")
                self._buffer += chunk
            raw, self._buffer = self._buffer.split(b"\0", 1)
            reply = json.loads(raw)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})

    def open(self, url):
        """Opens `url` in a new tab, which the other calls then address."""
        self._target = self._send("Target.createTarget", {"url": url}, session=False)["targetId"]
        self._session = self._send("Target.attachToTarget",
                                   {"targetId": self._target, "flatten": True}, session=False)[
                                       "sessionId"]

    def close_tab(self):
        """Closes the tab open() opened last (its page and WebGL context go with it)."""
        self._send("Target.closeTarget", {"targetId": self._target}, session=False)
        self._session = None

    def evaluate(self, expression):
        """The value of a JavaScript expression in the tab."""
        result = self._send("Runtime.evaluate", {"expression": expression,
                                                 "returnByValue": True})
        return result.get("result", {}).get("value")

    def wait_for(self, expression, done, timeout_s):
        """Polls a JavaScript expression until done(value) is true; returns the last value it
        had (done or not) after at most timeout_s seconds (real time)."""
        deadline = time.monotonic() + timeout_s
        while True:
            value = self.evaluate(expression)
            if done(value) or time.monotonic() >= deadline:
                return value
            time.sleep(0.05)

    def wait_for_title(self, prefix, timeout_s):
        """Polls document.title until it starts with `prefix`; returns it, or None after
        timeout_s seconds (real time)."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            title = self.evaluate("document.title") or ""
            if title.startswith(prefix):
                return title
            time.sleep(0.1)
        return None

    def close(self):
        try:
            self._send("Browser.close", session=False)
        except (RuntimeError, OSError):
            pass
        try:
            self._proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._proc.kill()
            self._proc.wait()
        os.close(self._to_browser_w)
        os.close(self._from_browser_r)
        shutil.rmtree(self._profile, ignore_errors=True)
