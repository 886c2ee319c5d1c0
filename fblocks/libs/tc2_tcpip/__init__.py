"""Beckhoff's Tc2_tcpip, declared: see its ST files."""
