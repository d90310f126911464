"""Patching nodes: panel patterns and their mapping from a development onto its surface."""
