"""CODESYS's SysDir, declared: its functions answer ERR_NOTIMPLEMENTED."""
