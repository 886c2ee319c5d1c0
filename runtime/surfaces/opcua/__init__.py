"""The OPC UA server of a running PLC ([opcua] in the configuration), on
asyncua: every program instance, FB instance, struct, array and global as a
node tree with IEC types mapped to OPC UA types, values from the snapshot
hub at the configured period, writes through the one write API, anonymous
read-only by default, user/password and certificate modes.

    start(surfaces, config) -> OpcuaServer    (.url, .stop())

Modules: server.py (the thread, the loop, publishing), tree.py (what is
published), space.py (the nodes), typemap.py (IEC <-> OPC UA types and
values), writes.py (a client's write), users.py (logins, password hashes),
security.py (the certificate mode's files).
"""

from .server import OpcuaServer, start

__all__ = ["OpcuaServer", "start"]
