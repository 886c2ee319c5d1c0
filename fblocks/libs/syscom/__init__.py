"""CODESYS's SysCom, declared: its functions answer ERR_NOTIMPLEMENTED."""
