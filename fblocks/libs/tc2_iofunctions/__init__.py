"""Beckhoff's Tc2_iofunctions, declared: see its ST files."""
