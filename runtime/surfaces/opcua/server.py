"""The OPC UA server of a running PLC: an asyncua Server in its own thread
with its own event loop (in the servers' process: surfaces/process.py),
publishing the engine's variables from the snapshot hub and writing through
the one write API.

    handle = start(surfaces, config)   # returns once the endpoint listens
    handle.url                         # opc.tcp://127.0.0.1:4840/softplc/
    handle.stop()                      # loop ended, thread joined, socket closed

Every ``config.period`` the server looks at the hub's latest snapshot and,
when it is a new one, writes the values that changed since the last one into
their nodes, so a subscription sees data changes at that rate. An online
change (a new ``Snapshot.generation``) rebuilds the tree: only what changed
(space.add_tree), so subscriptions of what stays go on.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from asyncua import Server, ua

from ...config.servers import ServerConfig
from ...io.loop_thread import LoopThread
from .security import load_credentials
from .space import add_enums, add_tree, tree_items, variant
from .tree import READER, Tree, Variable, published
from .typemap import node_id
from .users import PlcUsers, load_users
from .writes import PlcAttributeService

log = logging.getLogger("softplc.surfaces.opcua")

NAMESPACE = "urn:softplc"
PATH = "/softplc/"
#: published variables (array elements count one each) unless [opcua] max_variables says otherwise
MAX_VARIABLES = 10_000
START_TIMEOUT_S = 60.0
#: what one client may make the server hold (asyncua's defaults: 1,000 connections, a message of
#: 100 MB, 500 parsed messages queued per connection): connections at once, the largest message
#: taken (a write of a big array fits), messages waiting behind the one in work
MAX_CONNECTIONS = 32
MAX_MESSAGE = 16 * 1024 * 1024
MAX_QUEUED = 50


class OpcuaServer:
    """The handle start() returns (see the module docstring)."""

    def __init__(self, surfaces, config: ServerConfig) -> None:
        self.surfaces = surfaces
        self.config = config
        options = config.options
        self.namespace = options.get("namespace") or NAMESPACE
        self.limit = options.get("max_variables") or MAX_VARIABLES
        self.users = load_users(options.get("users") or {}, options.get("users_file"))
        self.anonymous = options.get("anonymous", True)
        self.certificate: Path | None = options.get("certificate")
        self.private_key: Path | None = options.get("private_key")
        self.url = ""
        self.tree: Tree | None = None
        self.published = 0  # snapshots published (tests wait on it)
        self._server: Server | None = None
        self._idx = 0
        self._variables: dict = {}  # NodeId -> Variable
        self._last: dict = {}  # path -> value as stored, as last published
        self._signatures: dict = {}  # NodeId -> what the node is (space.add_tree), for an online change
        self._generation = -1
        self._seen = 0  # the sequence of the last snapshot published
        self._stopping: asyncio.Event | None = None
        self._runner = LoopThread("opcua", on_error=lambda exc: log.error("opcua: the server stopped: %s", exc))

    # ------------------------------------------------------------ the caller's thread

    def start(self) -> OpcuaServer:
        try:
            self._runner.start(self._main, START_TIMEOUT_S)
        except TimeoutError:
            self.stop()
            raise TimeoutError(f"opcua: the server did not start within {START_TIMEOUT_S} s") from None
        return self

    def stop(self) -> None:
        stopping = self._stopping
        if stopping is not None:
            self._runner.call_soon(stopping.set)
        self._runner.join()
        self.surfaces.hub.unwatch(READER)

    # ------------------------------------------------------------ the server's thread

    async def _main(self, ready: Callable[[], None]) -> None:
        self._stopping = asyncio.Event()
        server = self._server = await self._make_server()
        self._idx = await server.register_namespace(self.namespace)
        await self._build()
        await server.start()
        try:
            port = server.bserver.port if server.bserver is not None else self.config.port
            self.url = f"opc.tcp://{self.config.host}:{port}{PATH}"
            _fix_endpoint_urls(server, self.url)
            ready()
            await self._publish_loop()
        finally:
            await server.stop()

    async def _make_server(self) -> Server:
        secure = self.certificate is not None or self.private_key is not None
        credentials = load_credentials(self.certificate, self.private_key) if secure else None
        users = PlcUsers(self.users, self.anonymous, encrypted_only=secure)
        server = Server(user_manager=users)
        await server.init()
        server.iserver.max_connections = MAX_CONNECTIONS
        server.iserver.max_pending_messages_per_connection = MAX_QUEUED
        server.limits.max_message_size = MAX_MESSAGE
        server.limits.max_chunk_count = -(-MAX_MESSAGE // server.limits.max_recv_buffer)
        server.set_endpoint(f"opc.tcp://{self.config.host}:{self.config.port}{PATH}")
        server.set_server_name("softplc")
        await server.set_application_uri(self.namespace + ":server")
        tokens: list = [ua.AnonymousIdentityToken] if self.anonymous else []
        if self.users:
            tokens.append(ua.UserNameIdentityToken)
        server.set_identity_tokens(tokens)
        if credentials is not None:
            server.iserver.certificate, server.iserver.private_key = credentials  # what load_certificate() sets
            server.set_security_policy([ua.SecurityPolicyType.Basic256Sha256_SignAndEncrypt])
        else:
            server.set_security_policy([ua.SecurityPolicyType.NoSecurity])
        iserver = server.iserver
        iserver.attribute_service = PlcAttributeService(
            iserver.aspace, self.surfaces.access, self._variables, bool(self.users), self._written
        )
        return server

    async def _build(self) -> None:
        """The tree of the engine's current program, as nodes (again after an online change)."""
        server = self._server
        assert server is not None
        hub = self.surfaces.hub
        tree = await asyncio.to_thread(self.surfaces.call, published, self.limit)
        if tree.left_out:
            log.warning(
                "opcua: %d variable(s) not published: more than %d values ([opcua] max_variables)",
                tree.left_out,
                self.limit,
            )
        await asyncio.to_thread(hub.watch, READER, tree.watched)
        # with the paths just watched: taken now before the first scan, else at the end of the next
        snap = await asyncio.to_thread(hub.current, True)
        enums = await add_enums(server, self._idx, {n: e for n, e in tree.enums.items() if not self._has_enum(n)})
        enums.update({n: node_id(f"#type.{n}", self._idx) for n in tree.enums})
        known = self._signatures
        self._signatures = await add_tree(server, tree_items(self._idx, tree, enums, snap.values), known)
        self.tree = tree
        self._variables.clear()
        self._variables.update({node_id(v.path, self._idx): v for v in tree.variables})
        # a node kept from before the change holds the last value published: the
        # publish below writes what the snapshot has new for it; a new node has it
        last, self._last = self._last, dict(snap.values)
        for nid, var in self._variables.items():
            if known.get(nid) is not None:
                self._last.update({p: last.get(p) for p in var.watched})
        self._generation = snap.generation
        await self.publish(snap)
        log.info("opcua: %d variables published", len(tree.variables))

    def _has_enum(self, name: str) -> bool:
        assert self._server is not None
        return node_id(f"#type.{name}", self._idx) in self._server.iserver.aspace

    async def _publish_loop(self) -> None:
        assert self._stopping is not None
        period = self.config.period_ns / 1e9
        while not self._stopping.is_set():
            snap = self.surfaces.hub.latest
            if snap is not None and snap.sequence != self._seen:
                if snap.generation != self._generation:
                    await self._build()
                else:
                    await self.publish(snap)
            try:
                await asyncio.wait_for(self._stopping.wait(), period)
            except TimeoutError:
                pass

    async def publish(self, snap) -> int:
        """Write what changed since the last snapshot into the nodes; the number of variables written."""
        assert self._server is not None and self.tree is not None
        self._seen = snap.sequence
        values, last = snap.values, self._last
        stamp: Any = datetime.fromtimestamp(snap.wall, UTC)  # asyncua annotates ua.DateTime
        iserver = self._server.iserver
        written = 0
        for nid, var in self._variables.items():
            changed = [p for p in var.watched if values.get(p, last.get(p)) != last.get(p)]
            if not changed:
                continue
            for p in changed:
                last[p] = values[p]
            dv = _SharedDataValue(variant(var, last), SourceTimestamp=stamp, ServerTimestamp=stamp)
            await iserver.write_attribute_value(nid, dv)
            written += 1
        self.published += 1
        return written

    def _written(self, var: Variable, value: ua.DataValue) -> None:
        """A client's write was made: the next snapshot that differs from it is published."""
        self._last.update(dict.fromkeys(var.watched, None))


class _SharedDataValue(ua.DataValue):
    """A DataValue published once and never changed afterwards: asyncua's
    monitored items deep-copy what they are given, to keep it from being
    changed under them: publishing 1,000 changed variables to a subscription
    took 119 ms of the server thread with the copies, 35 ms without. This
    one is made for a single publish and never changed: theirs to keep."""

    def __deepcopy__(self, memo: dict) -> _SharedDataValue:
        return self


def _fix_endpoint_urls(server: Server, url: str) -> None:
    """With port 0 the endpoints were described before the port was known."""
    for endpoint in server.iserver.endpoints:
        endpoint.EndpointUrl = url
        endpoint.Server.DiscoveryUrls = [url]


def start(surfaces, config: ServerConfig) -> OpcuaServer:
    return OpcuaServer(surfaces, config).start()
