"""The web monitor: a page served by the PLC process ([web] in the
configuration, or `softplc run --web [HOST:]PORT`) showing the tasks, the
drivers and their nodes, a live variable tree with write, force and
unforce, a trend chart and the log (README "Web monitor").

    handle = start(surfaces, config)   # surfaces: host.Surfaces; config: the [web] ServerConfig
    handle.url, handle.stop()

Starlette (routes, static files, server-sent events) served by uvicorn in a
thread of its own (server.py); app.py the JSON API, tree.py the variable
tree, stream.py the live values, logbuffer.py the log, static/ the page
(plain HTML, CSS and JavaScript: no CDN, no build step).
"""

from .server import WebHandle, start

__all__ = ["WebHandle", "start"]
