"""The surfaces of a running PLC: the servers that show it and change it
(the web monitor, OPC UA, the Modbus TCP server). Each reads the engine
through one SnapshotHub and writes through one Access (engine/snapshot.py,
engine/access.py); host.py starts the servers a configuration asks for."""
