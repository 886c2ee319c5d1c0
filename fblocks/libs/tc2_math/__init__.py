"""Beckhoff TwinCAT 3 Tc2_Math (Beckhoff Information System, "TwinCAT 3
PLC Lib: Tc2_Math"): FLOOR, CEIL, FRAC, LTRUNC, LMOD, MODABS, MODTURNS,
written in ST (math.st)."""
