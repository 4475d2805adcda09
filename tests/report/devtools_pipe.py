"""Reads an element's text from a page open in headless Chromium, waiting in real time.

--dump-dom returns once the page's virtual time runs out, which does not wait for work the page
awaits off the main thread (ImageDecoder's decoding): on a loaded machine the DOM can be dumped
before a script wrote its answer. Here the browser is driven over the DevTools protocol on a pipe
(--remote-debugging-pipe: JSON messages ending in NUL, commands on fd 3, replies on fd 4) and the
element is read until it holds text or the time runs out."""
import json
import os
import select
import subprocess
import time


class _Pipe:
    def __init__(self, write_fd, read_fd):
        self.write_fd, self.read_fd = write_fd, read_fd
        self.buffer, self.last_id = b"", 0

    def send(self, method, params=None, session=None):
        self.last_id += 1
        message = {"id": self.last_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self.write_fd, json.dumps(message).encode() + b"\0")
        return self.last_id

    def call(self, deadline, method, params=None, session=None):
        """The result of one command; TimeoutError past the deadline."""
        wanted = self.send(method, params, session)
        while True:
            while b"\0" in self.buffer:
                raw, self.buffer = self.buffer.split(b"\0", 1)
                message = json.loads(raw)
                if message.get("id") == wanted:
                    if "error" in message:
                        raise RuntimeError(f"{method}: {message['error']}")
                    return message["result"]
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(method)
            if select.select([self.read_fd], [], [], left)[0]:
                chunk = os.read(self.read_fd, 1 << 16)
                if not chunk:
                    raise RuntimeError("Chromium closed its DevTools pipe")
                self.buffer += chunk


def _start(exe, flags):
    to_browser, from_us = os.pipe()
    to_us, from_browser = os.pipe()

    def onto_fds_3_and_4():  # dup first: the pipe's own fds may be 3 or 4
        commands, replies = os.dup(to_browser), os.dup(from_browser)
        os.dup2(commands, 3)
        os.dup2(replies, 4)

    process = subprocess.Popen([exe, "--remote-debugging-pipe"] + flags + ["about:blank"],
                               pass_fds=(3, 4), preexec_fn=onto_fds_3_and_4,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(to_browser)
    os.close(from_browser)
    return process, _Pipe(from_us, to_us)


def element_text(exe, flags, url, element_id, timeout=120.0):
    """The text of #element_id once it is not empty, or None if it is still empty after timeout s."""
    process, pipe = _start(exe, flags)
    deadline = time.monotonic() + timeout
    read = ("(function () { var e = document.getElementById(%s); return e ? e.textContent : ''; })()"
            % json.dumps(element_id))
    try:
        target = pipe.call(deadline, "Target.createTarget", {"url": url})["targetId"]
        session = pipe.call(deadline, "Target.attachToTarget",
                            {"targetId": target, "flatten": True})["sessionId"]
        while True:
            got = pipe.call(deadline, "Runtime.evaluate", {"expression": read, "returnByValue": True},
                            session)
            text = got.get("result", {}).get("value") or ""
            if text:
                return text
            time.sleep(0.1)
    except TimeoutError:
        return None
    finally:
        try:
            pipe.send("Browser.close")
        except OSError:
            pass
        try:
            process.wait(10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        os.close(pipe.write_fd)
        os.close(pipe.read_fd)
