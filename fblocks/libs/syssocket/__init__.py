"""CODESYS's SysSocket, declared: its functions answer ERR_NOTIMPLEMENTED."""
