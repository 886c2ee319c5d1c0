"""Beckhoff TwinCAT 3 Tc2_Utilities (Beckhoff Information System, "TwinCAT
3 PLC Lib: Tc2_Utilities") for what has a meaning on a PC or offline: the
string, number, byte order and checksum helpers, FB_FormatString, the time
conversions (FILETIME, TIMESTRUCT, DT) and the local time of the engine's
clock (NT_GetTime, FB_LocalSystemTime), the time zone conversions,
FB_MemRingBuffer. It uses Tc2_System's types (T_MaxString, PVOID ...) and
MEMCPY, as in TwinCAT.

services.st declares the blocks that act on the computer or ask Windows
over ADS (NT_Shutdown, FB_GetAdaptersInfo ...): they answer ERR TRUE,
ERRID 6 (ADS "target port not found").
"""
