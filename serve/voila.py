"""Voila's settings for the explorer's web page (`make explore`, tests/browser), read with
`--Voila.config_file_paths=serve`.

Every page load starts a kernel of its own (about 310 MB). A kernel no page is connected to
(the page closed, its request aborted, its connection lost: the server pings each page every
30 s and drops one silent for 90 s) is shut down after ten idle minutes; a page left open keeps
its kernel. At most HARP_ANALYSIS_EXPLORER_KERNELS kernels (8 by default) live at once: beyond
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
c.Voila.tornado_settings = {"ws_ping_interval": 30_000, "ws_ping_timeout": 90_000}


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
