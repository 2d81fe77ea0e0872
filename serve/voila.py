"""Voila's settings for the explorer's web page (`make explore`, tests/browser), read with
`--Voila.config_file_paths=serve`.

Every page load starts a kernel of its own (about 310 MB; up to 130 MB more where the reader
asks for the calibrated MKS, whose tables of the last 16 guns it keeps). A kernel no page is
connected to (the page closed, its request aborted, its connection lost) is shut down after ten
idle minutes; a page left open keeps its kernel. A lost connection is found by pinging: the
server pings each page every 30 s and drops one that has answered nothing for 75 s, which it
finds when a ping is due: at the third after the page's last answer, 90 s after it (60 to 90 s
after the page fell silent). A page that misses one ping is kept, and the browser answers pings
itself, even while the page's script is busy. HARP_ANALYSIS_EXPLORER_PING_S sets the interval in
seconds (the timeout is 2.5 intervals), for tests/browser/test_explorer_ping.py.

At most HARP_ANALYSIS_EXPLORER_KERNELS kernels (8 by default) live at once: beyond
that a page load gets a short page saying so (HTTP 503), not a kernel. Neither Voila 0.5 nor
jupyter-server has a cap of its own; Voila's prelaunch hook, called before each page's kernel
is started, refuses the page instead.
"""

import os

from tornado.web import HTTPError

c = get_config()  # noqa: F821  (defined by traitlets when it loads this file)

MAX_KERNELS = int(os.environ.get("HARP_ANALYSIS_EXPLORER_KERNELS", "8"))

c.MappingKernelManager.cull_idle_timeout = 600
c.MappingKernelManager.cull_interval = 60
c.MappingKernelManager.cull_connected = False

# Pings (issue 34). The kernels' websocket (jupyter-server's KernelWebsocketHandler, which Voila
# serves) pings through jupyter-server's WebSocketMixin, in MILLISECONDS: every ws_ping_interval
# it closes the connection if the page's last pong is more than ws_ping_timeout old, else pings.
# The timeout is 2.5 intervals, not jupyter-server's default 3: at 3 the check falls exactly on
# the third ping due after an answer, and whether the page is dropped then or one interval later
# turns on a millisecond (measured, a client that answered the first ping only: its answer found
# 90 000 ms old at the check in one run, 89 997 ms in another: 90 s would keep it 30 s more). It
# must exceed one interval: the first ping goes out one interval after the page connects, so a
# timeout of one interval or less drops a live page at the first check.
# tornado >= 6.5 has a ping of its own (websocket_ping_interval and _timeout, in seconds, the
# timeout no longer than the interval), but WebSocketMixin's ping_interval and ping_timeout hide
# tornado's: websocket_ping_* are never read for the kernels, and tornado's pinger is handed
# these numbers read as seconds (a first ping after 30 000 s), whence the warning in the log at
# the first connection, "The websocket_ping_timeout (75000) cannot be longer than the
# websocket_ping_interval (30000). Setting websocket_ping_timeout=30000": tornado's, in seconds,
# not the timeout served.
PING_INTERVAL_S = float(os.environ.get("HARP_ANALYSIS_EXPLORER_PING_S", "30"))
c.Voila.tornado_settings = {
    "ws_ping_interval": round(1000 * PING_INTERVAL_S),
    "ws_ping_timeout": round(2500 * PING_INTERVAL_S),
}


def refuse_beyond_the_cap(handler, notebook, cwd):
    """HTTP 503 with a sentence for the reader once MAX_KERNELS kernels live or are starting
    (a starting kernel is pending until it answers, and counts)."""
    manager = handler.kernel_manager
    live = set(manager.list_kernel_ids()) | set(manager._pending_kernels)
    if len(live) >= MAX_KERNELS:
        raise HTTPError(
            503,
            reason=(
                f"The explorer is busy: {MAX_KERNELS} pages are open, as many as this machine "
                "serves at once. Please try again in a few minutes."
            ),
        )
    return notebook


c.VoilaConfiguration.prelaunch_hook = refuse_beyond_the_cap
