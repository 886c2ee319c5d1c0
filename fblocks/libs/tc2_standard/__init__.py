"""Beckhoff TwinCAT 3 Tc2_Standard (Beckhoff Information System, "TwinCAT
3 PLC Lib: Tc2_Standard"): the IEC blocks as TwinCAT declares them. The
timers, edge detectors and bistables are softplc's standard blocks
(fblocks/iec/standard_fbs.st: SR and RS take TwinCAT's SET1/RESET and
SET/RESET1); counters.st holds the counters with TwinCAT's inputs (RESET,
LOAD) and WORD counts; functions.py the string functions with TwinCAT's
parameter names (CONCAT(STR1, STR2) ...)."""
