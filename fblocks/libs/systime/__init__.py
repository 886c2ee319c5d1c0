"""CODESYS's SysTime and SysTimeRtc: the task clock in ms/us/ns, and the
date of softplc's clock (in virtual time: the epoch plus the virtual
clock), through the runtime's clock service (st/native.CLOCK)."""
