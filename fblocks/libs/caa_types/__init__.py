"""CODESYS's CAA Types (namespace CAA): the basic types of the CAA
libraries (CAA.HANDLE, CAA.SIZE ...)."""
