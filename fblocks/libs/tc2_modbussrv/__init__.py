"""Beckhoff's Tc2_modbussrv, declared: see its ST files."""
