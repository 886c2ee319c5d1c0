"""Beckhoff TwinCAT 3 Tc2_System (Beckhoff Information System, "TwinCAT 3
PLC Lib: Tc2_System") for what has a meaning on a PC or offline: memory
through pointers (MEMCPY ...), the system types (PVOID, T_MaxString,
HRESULT ...), the clock (F_GetSystemTime, GETSYSTEMTIME ...), the task
(GETCURTASKINDEX, _TaskInfo, TwinCAT_SystemInfoVarList), bit functions,
ADSLOG* into softplc's log, TestAndSet and FB_IecCriticalSection.

The ADS blocks (ads.st) and the file blocks (files.st) have their real
signatures and answer as TwinCAT does when its ADS router or system
service does not answer: bBusy/BUSY FALSE, bError/ERR TRUE, nErrId/ERRID 6
("target port not found", Beckhoff Information System, ADS Return Codes).
Files are not written by softplc: TwinCAT reaches them through its system
service (AMS port 10000), and a PLC program that writes on the host from
a test would surprise.
"""
