"""CODESYS's SysTypes2 Interfaces (namespace SysTypes) and the error codes
of CmpErrors: the RTS_IEC_* types and result codes the system libraries
(SysFile, SysCom, SysTime ...) take and return."""
