"""CODESYS's SysFile, declared: its functions answer ERR_NOTIMPLEMENTED."""
