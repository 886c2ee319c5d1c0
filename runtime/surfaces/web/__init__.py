"""The web monitor: a page served by the servers' process ([web] in the
configuration, or `softplc run --web [HOST:]PORT`) showing the tasks, the
drivers and their nodes, a live variable tree with write, force and
unforce, a trend chart and the log (docs/guide/surfaces.md "Web monitor").

    handle = start(surfaces, config)   # surfaces: child.RemoteSurfaces (or host.Surfaces); config: [web]
    handle.url, handle.stop()

Starlette (routes, static files, server-sent events) served by uvicorn in a
thread of its own (server.py); app.py the JSON API, tree.py the variable
tree, stream.py the live values, logbuffer.py the log, plc.py what the page
asks of the PLC's process, static/ the page (plain HTML, CSS and
JavaScript: no CDN, no build step). The web framework is imported by
start(), not with this package: the servers' process imports the log
buffer without it.
"""

from __future__ import annotations

from typing import Any


def start(surfaces, config) -> Any:
    """server.start: the handle of the server, listening."""
    from .server import start as start_server

    return start_server(surfaces, config)


__all__ = ["start"]
