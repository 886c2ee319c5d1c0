"""Beckhoff's Tc2_serialcom, declared: see its ST files."""
