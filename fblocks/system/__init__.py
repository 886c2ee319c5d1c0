"""Runtime system library: PLC_DIAG, the engine diagnostics a program can read."""
