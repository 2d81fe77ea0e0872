"""How the served explorer finds a lost page (issue 34): the server pings each page's websocket
and drops one that has stopped answering. serve/voila.py sets the interval (30 s) and the
timeout (2.5 intervals) for jupyter-server's ping, in milliseconds; tornado's own ping, in
seconds, is hidden by jupyter-server's and is not the one that runs.

The first test (instant, in `make test`) holds serve/voila.py's numbers and the sentence
README.md and serve/voila.py's docstring say about them. The second serves the explorer with a
2 s interval (HARP_ANALYSIS_EXPLORER_PING_S; 30 s would take minutes), loads the page so that a
kernel starts, and opens the kernel's websocket by hand three times, with clients that complete
the handshake and then answer no ping, only the first, or every one: the silent one must be
dropped at the first ping due past the timeout, the one that answered once at the first due past
the timeout after its answer, and the live one kept. The two dropped must get an empty close
frame (jupyter-server's close; tornado's would say "ping timed out") and a warning each in the
server's log. It takes about 25 s with the engines' kernels compiled, so it runs in
`make check-browser` (HARP_ANALYSIS_EXPLORER_LOAD=1)."""

import base64
import os
import re
import socket
import struct
import threading
import time
import urllib.request
from collections.abc import Callable
from dataclasses import dataclass, field
from math import floor
from pathlib import Path
from urllib.parse import urlsplit

import pytest
from traitlets.config.loader import PyFileConfigLoader

CHECKOUT = Path(__file__).resolve().parents[2]
PING_S = 2.0  # the interval served to the second test
TIMEOUT_PER_INTERVAL = 2.5  # serve/voila.py's ratio
LIVE_S = 6 * PING_S  # how long the live client stays, the others' drops well inside it
# Bounds on waiting, never asserted times.
PAGE_S = 240.0  # the page load, its kernel's run of the notebook included
FRAME_S = 30.0  # the longest the clients wait for a frame the server owes them

PING, PONG, CLOSE = 0x9, 0xA, 0x8


def served_settings(interval_s: str | None = None) -> dict:
    """serve/voila.py's tornado settings, read as Voila reads it, under an interval or none."""
    variable = "HARP_ANALYSIS_EXPLORER_PING_S"
    before = os.environ.pop(variable, None)
    if interval_s is not None:
        os.environ[variable] = interval_s
    try:
        config = PyFileConfigLoader("voila.py", path=str(CHECKOUT / "serve")).load_config()
    finally:
        os.environ.pop(variable, None)
        if before is not None:
            os.environ[variable] = before
    return dict(config.Voila.tornado_settings)


def one_line(text: str) -> str:
    return " ".join(text.split())


def test_the_ping_documented_is_the_ping_configured():
    settings = served_settings()
    assert set(settings) == {"ws_ping_interval", "ws_ping_timeout"}, settings
    interval_s = settings["ws_ping_interval"] / 1000  # jupyter-server's, in milliseconds
    timeout_s = settings["ws_ping_timeout"] / 1000
    assert (interval_s, timeout_s) == (30, 75), settings
    # A timeout of one interval or less drops a live page at the first ping; a whole number of
    # intervals puts the drop on a millisecond's edge (serve/voila.py's comment).
    assert timeout_s > interval_s and timeout_s / interval_s != round(timeout_s / interval_s)
    # A silent page is dropped at the first ping due after the timeout.
    dropped_s = (floor(timeout_s / interval_s) + 1) * interval_s
    sentence = (
        f"the server pings each page every {interval_s:g} s and drops one that has answered "
        f"nothing for {timeout_s:g} s, which it finds when a ping is due"
    )
    after = f"{dropped_s:g} s after it"
    docstring = one_line((CHECKOUT / "serve" / "voila.py").read_text().split('"""')[1])
    readme = one_line((CHECKOUT / "README.md").read_text())
    for name, text in (("serve/voila.py", docstring), ("README.md", readme)):
        assert sentence in text, f"{name} does not say: {sentence}"
        assert after in text[text.index(sentence) :][:300], f"{name} does not say: {after}"

    short = served_settings(str(PING_S))
    assert short == {
        "ws_ping_interval": round(1000 * PING_S),
        "ws_ping_timeout": round(1000 * PING_S * TIMEOUT_PER_INTERVAL),
    }


@dataclass
class RawClient:
    """A websocket client by hand on the kernel's channels: it answers the pings ``answers``
    says to (by their number, from 1), records when each ping and the close frame came (seconds
    after the handshake) and stops at the close frame, the end of the stream, or ``stay_s``."""

    url: str
    kernel: str
    name: str
    answers: Callable[[int], bool]
    stay_s: float = FRAME_S
    pings_s: list[float] = field(default_factory=list)
    answered_s: list[float] = field(default_factory=list)
    closed_s: float | None = None
    close_payload: bytes | None = None
    ended: str = ""
    _buffer: bytes = b""
    _opened: float = 0.0
    _deadline: float = 0.0

    def run(self) -> None:
        address = urlsplit(self.url)
        with socket.create_connection((address.hostname, address.port), timeout=1.0) as sock:
            key = base64.b64encode(os.urandom(16)).decode()
            sock.sendall(
                (
                    f"GET /api/kernels/{self.kernel}/channels?session_id={self.name} HTTP/1.1\r\n"
                    f"Host: {address.netloc}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                    f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n"
                ).encode()
            )
            self._sock = sock
            self._deadline = time.monotonic() + FRAME_S
            head = self._read_until(b"\r\n\r\n")
            assert head.startswith(b"HTTP/1.1 101"), head
            self._opened = time.monotonic()
            self._deadline = self._opened + self.stay_s
            try:
                self._frames()
            except EOFError:
                self.ended = "end of stream"
            except TimeoutError:
                self.ended = "stayed"

    def _elapsed(self) -> float:
        return time.monotonic() - self._opened

    def _receive(self) -> None:
        while True:
            try:
                chunk = self._sock.recv(65536)
                break
            except TimeoutError:
                if time.monotonic() > self._deadline:
                    raise
        if not chunk:
            raise EOFError
        self._buffer += chunk

    def _read(self, count: int) -> bytes:
        while len(self._buffer) < count:
            self._receive()
        out, self._buffer = self._buffer[:count], self._buffer[count:]
        return out

    def _read_until(self, end: bytes) -> bytes:
        while end not in self._buffer:
            self._receive()
        head, self._buffer = self._buffer.split(end, 1)
        return head

    def _frames(self) -> None:
        while True:
            first, second = self._read(2)
            opcode, length = first & 0x0F, second & 0x7F
            if length == 126:
                (length,) = struct.unpack(">H", self._read(2))
            elif length == 127:
                (length,) = struct.unpack(">Q", self._read(8))
            payload = self._read(length)
            if opcode == PING:
                self.pings_s.append(self._elapsed())
                if self.answers(len(self.pings_s)):
                    self._sock.sendall(masked_frame(PONG, payload))
                    self.answered_s.append(self._elapsed())
            elif opcode == CLOSE:
                self.closed_s, self.close_payload, self.ended = self._elapsed(), payload, "closed"
                return


def masked_frame(opcode: int, payload: bytes) -> bytes:
    """A client's frame (RFC 6455: masked), payload under 126 bytes."""
    mask = os.urandom(4)
    masked = bytes(byte ^ mask[i % 4] for i, byte in enumerate(payload))
    return bytes([0x80 | opcode, 0x80 | len(payload)]) + mask + masked


@pytest.mark.load
@pytest.mark.xdist_group("dask_cluster")
def test_the_served_explorer_drops_a_silent_page_and_keeps_a_live_one(serve_explorer, tmp_path):
    timeout_s = TIMEOUT_PER_INTERVAL * PING_S
    with serve_explorer(
        tmp_path, environment={"HARP_ANALYSIS_EXPLORER_PING_S": str(PING_S)}
    ) as served:
        url, _ = served
        page = urllib.request.urlopen(url, timeout=PAGE_S).read().decode()
        kernel = re.search(r'"kernelId": "([0-9a-f-]{36})"', page)
        assert kernel, "the page names no kernel"
        clients = [
            RawClient(url, kernel[1], "silent", lambda ping: False),
            RawClient(url, kernel[1], "answers-once", lambda ping: ping == 1),
            RawClient(url, kernel[1], "live", lambda ping: True, stay_s=LIVE_S),
        ]
        threads = [threading.Thread(target=client.run) for client in clients]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    silent, once, live = clients
    log = (tmp_path / "voila.log").read_text()
    report = "\n".join(
        f"{c.name}: pings at {[round(t, 2) for t in c.pings_s]}, answered "
        f"{[round(t, 2) for t in c.answered_s]}, {c.ended} at {c.closed_s}"
        for c in clients
    )
    print(report)

    # The live client: pinged every PING_S seconds (so the interval is read in milliseconds:
    # in seconds the first ping would come after 2000 s), answered, and kept.
    assert live.ended == "stayed", report
    assert len(live.pings_s) >= 5, report
    gaps = [b - a for a, b in zip([0.0, *live.pings_s], live.pings_s)]
    assert min(gaps) > 0.5 * PING_S, report  # a late ping is followed by an early one
    mean_gap = live.pings_s[-1] / len(live.pings_s)
    assert 0.95 * PING_S < mean_gap < 1.25 * PING_S, report

    # A page that never answers: pinged while within the timeout, then dropped at the first
    # ping due past it (2 pings, dropped at the third interval: 6 s for 5 s).
    within = floor(timeout_s / PING_S)
    assert silent.ended == "closed" and len(silent.pings_s) == within, report
    assert silent.closed_s is not None and silent.closed_s > timeout_s, report
    # A page that answered once: dropped at the first ping due past the timeout after its
    # answer, not one earlier (the timeout is counted from the last answer).
    assert once.ended == "closed" and len(once.pings_s) == 1 + within, report
    assert once.closed_s is not None and once.closed_s - once.answered_s[0] > timeout_s, report

    # jupyter-server's mechanism closed them (tornado's would give "ping timed out" as reason).
    for client in (silent, once):
        assert client.close_payload == b"", report
    assert log.count("WebSocket ping timeout after") == 2, log
