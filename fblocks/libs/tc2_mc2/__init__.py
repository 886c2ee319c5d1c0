"""Beckhoff's Tc2_mc2, declared: see its ST files."""
